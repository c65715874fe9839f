#!/usr/bin/env bash
# The box of the dam break onto a box (the case's scene at --cells 10: dx 0.5/9 m, the walls on
# node rows, c = 50 m/s) with
# and without its edges, at CFL 0.4 and 0.1: the structure's load against the time step
# (docs/convergence.md, "Dam break onto a box"). Each run is 1.2 s of the half tank at 1 thread.
#   bash tools/studies/box_edges.sh [TALUS] [OUTDIR]
set -euo pipefail
talus=${1:-build/tools/talus}
out=${2:-/tmp/talus_box_edges}
mkdir -p "$out"
# name, the structure's min and max: the box; the box across the tank (a step: no side edges);
# the box above the water (no top edge); both (a wall across the tank: no edges).
variants=("box:0.6635, 0.2985, -0.2:0.8245, 1, 0.161" "step:0.6635, -1, -0.2:0.8245, 1, 0.161"
          "tall:0.6635, 0.2985, -0.2:0.8245, 1, 1.5" "wall:0.6635, -1, -0.2:0.8245, 1, 1.5")
# The case's own scene (talus work-precision --single obstacle_impact --scene), varied by --set.
"$talus" work-precision --single obstacle_impact --cells 10 --scene >"$out/case.toml"
for v in "${variants[@]}"; do
  IFS=: read -r name lo hi <<<"$v"
  for cfl in 0.4 0.1; do
    dir="$out/${name}_cfl$cfl"
    "$talus" run "$out/case.toml" --out "$dir" --threads 1 --set simulation.end_time=1.2 --set simulation.cfl=$cfl \
      --set "structures.box.min=[$lo]" --set "structures.box.max=[$hi]" --set output.series_interval=0.01 \
      --set output.h5=false --set output.vdb=false --set output.plots=false >"$dir.log" 2>&1
    # The whole tank's load along -x, 5-sample (0.05 s) centred means: its peak for t <= 1 s and
    # its mean over 0.6-1.0 s, as the validation case reads it.
    python3 - "$dir/series.csv" "$name" "$cfl" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
t = [float(r["time_s"]) for r in rows]
f = [-2 * float(r["force_x_N_box"]) for r in rows]
m = [sum(f[max(0, i - 2):i + 3]) / len(f[max(0, i - 2):i + 3]) for i in range(len(f))]
peak = max((v, s) for v, s in zip(m, t) if s <= 1 + 1e-9)
press = [v for v, s in zip(m, t) if 0.6 - 1e-9 <= s <= 1 + 1e-9]
print(f"{sys.argv[2]:5s} CFL {sys.argv[3]}: peak {peak[0]:.0f} N at {peak[1]:.2f} s, 0.6-1.0 s {sum(press) / len(press):.0f} N")
PY
  done
done
