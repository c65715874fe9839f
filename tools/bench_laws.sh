#!/bin/bash
# The cost of the basal laws and of mu(I) (docs/throughput.md, "Cost of the flow laws"): a
# 160 000-particle granular layer sliding down a 30-degree bed, 0.3 s at 1 thread, once per law.
#   bash tools/bench_laws.sh [path/to/talus]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
talus="${1:-$root/build/tools/talus}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
row() {
  local name=$1 scene=$2
  shift 2
  "$talus" run "$root/tools/bench_scenes/$scene" --out "$out/$name" --quiet --threads 1 "$@"
  python3 - "$out/$name/summary.json" "$name" <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); p = d['phase_seconds']; n = d['particle_steps']
print(f"{sys.argv[2]:8s} {d['particle_steps_per_second']:.3g} p-steps/s  grid {1e9*p['grid']/n:5.1f}  "
      f"p2g {1e9*p['p2g']/n:5.1f}  g2p {1e9*p['g2p']/n:5.1f} ns per particle-step")
PY
}
row coulomb basal_slope.toml
row voellmy basal_slope.toml --set 'domain.z_min.law="voellmy"' --set domain.z_min.xi=1000
row samosat basal_slope.toml --set 'domain.z_min.law="samosat"'
row sticky basal_slope.toml --set 'domain.z_min.law="sticky"'
row mu_i basal_slope_mu_i.toml
