#!/usr/bin/env bash
# Runs tools/studies/thin_release.toml at grid spacing $1 (m) into thin_release_dx$1/ and prints
# the run-out along the slope (peak flow height >= 5 cm, AvaFrame's threshold), the peak flow
# heights and the speed. Needs `talus` on PATH or TALUS=path/to/talus.
set -euo pipefail
dx=${1:?usage: thin_release.sh DX}
talus=${TALUS:-talus}
here=$(cd "$(dirname "$0")" && pwd)
out=thin_release_dx$dx
"$talus" run "$here/thin_release.toml" --set simulation.dx="$dx" --out "$out" --quiet
"$talus" map-stats "$out/maps/max_flow_height_slope_normal.tif" --threshold 0.05 \
  --path "2600000,1200010 2600400,1200010" --half-width 10 | tail -2
python3 - "$out" <<'PY'
import csv, json, sys
d = sys.argv[1]
rows = list(csv.DictReader(open(d + "/series.csv")))
s = json.load(open(d + "/summary.json"))
print(f"{d}: {s['particles']} particles, {s['steps']} steps, {s['wall_seconds']:.1f} s wall, "
      f"max speed {max(float(r['max_speed_m_s']) for r in rows):.2f} m/s")
PY
