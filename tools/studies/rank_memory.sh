#!/bin/bash
# Rank memory over a run: the default scene at dx 2 m for 3 s on 2 ranks (a frame at the start,
# 10 checkpoints, the end's files), each rank's resident set sampled every 0.25 s, then each
# rank's peak (summary.json) and the median of the run's middle half (between the writes).
# Usage: bash tools/studies/rank_memory.sh TALUS_BINARY OUT_DIR [--set KEY=VALUE ...]
#   (docs/scaling.md, "Rank 0's view", "Frames in parts"); the options go to `talus run`.
set -euo pipefail
BIN=$1; OUT=$2; shift 2
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
rm -rf "$OUT" "$OUT.rss"
mpirun --oversubscribe -np 2 "$BIN" run --quiet --threads 1 --set simulation.dx=2 --set simulation.end_time=3 "$@" --out "$OUT" &
mp=$!
sleep 0.5
while kill -0 $mp 2>/dev/null; do
  for p in $(pgrep -x talus || true); do echo "$p $(awk '/VmRSS/{print $2}' /proc/$p/status 2>/dev/null)"; done >> "$OUT.rss"
  sleep 0.25
done
wait $mp
python3 - "$OUT" <<'PY'
import collections, json, statistics, sys
out = sys.argv[1]
j = json.load(open(out + '/summary.json'))
rss = collections.defaultdict(list)
for line in open(out + '.rss'):
    a = line.split()
    if len(a) == 2: rss[a[0]].append(int(a[1]) / 1024)
print("wall %.1f s, particles %d, rank 0 gathered every particle %d times" % (
    j['wall_seconds'], j['particles'], j.get('rank0_gathered_every_particle', -1)))
for r in j['per_rank']:
    print("rank %d: peak %.1f MB, compute %.1f s, communication %.1f s" % (
        r['rank'], r['memory_bytes']['peak_resident'] / 2**20, r['compute_seconds'], r['communication_seconds']))
for pid, v in sorted(rss.items(), key=lambda kv: -max(kv[1])):  # rank 0 (the outputs) first
    mid = v[len(v) // 4: 3 * len(v) // 4] or v
    print("process %s: largest sample %.1f MB, median of the middle half %.1f MB" % (pid, max(v), statistics.median(mid)))
PY
