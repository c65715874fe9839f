#!/usr/bin/env bash
# Soak test (not CI; hours at full length): the embedded default scene run for LENGTH_FACTOR times
# its simulated length, once straight through and once killed (SIGKILL, as a crashing machine or
# a batch system would) at KILLS random instants and resumed from its checkpoint after each.
# Checkpoints: the scene's own (a tenth of the end time) and one every CHECKPOINT_EVERY wall
# seconds by SIGUSR1. Reports
#   - memory: resident set size sampled every second (rss_*.csv), first/median/last/peak;
#   - identity: every output file of the resumed run against the straight run, byte for byte
#     (summary.json without its wall-clock figures);
#   - half-written files: temporaries (*.tmp) found after each kill and at the end.
#   bash tools/soak.sh                                   # 10x the length, 10 kills
#   bash tools/soak.sh --length-factor 1 --kills 3       # the short version (a few minutes)
# Options: --talus BIN (build/tools/talus), --out DIR (soak_out), --threads N (2), --seed N,
# --checkpoint-every S (60). Exit status 0 when every check passed, 1 otherwise.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
talus="$root/build/tools/talus"
out="soak_out"
factor=10
kills=10
threads=2
every=60
seed="$$"
while [ $# -gt 0 ]; do
  case "$1" in
    --talus) talus="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --length-factor) factor="$2"; shift 2 ;;
    --kills) kills="$2"; shift 2 ;;
    --threads) threads="$2"; shift 2 ;;
    --checkpoint-every) every="$2"; shift 2 ;;
    --seed) seed="$2"; shift 2 ;;
    *) echo "soak: unknown option $1 (see the head of $0)" >&2; exit 2 ;;
  esac
done
[ -x "$talus" ] || { echo "soak: $talus: not found; build first (bash tools/setup.sh)" >&2; exit 2; }
RANDOM="$seed"

rm -rf "$out"
mkdir -p "$out"
out="$(cd "$out" && pwd)"
report="$out/report.txt"
"$talus" default-scene > "$out/scene.toml"
end_time="$(awk -v f="$factor" '/^end_time/ { print $3 * f; exit }' "$out/scene.toml")"
# Frames every tenth of the run keep the disk use small at 10x (the default is every 5 s).
sets=(--set "simulation.end_time=$end_time" --set "output.frame_interval=$(awk -v e="$end_time" 'BEGIN { print e / 10 }')")

say() { echo "$*" | tee -a "$report"; }

# Runs talus in the background, samples its RSS into $1 and sends SIGUSR1 every $every s.
# With a kill delay ($3 > 0) it sends SIGKILL after that many seconds. Sets $status and $wall.
watch_run() {
  local rss="$1" label="$2" kill_after="$3"
  shift 3
  local start now pid next_ckpt=$every
  start="$(date +%s.%N)"
  "$talus" "$@" --threads "$threads" --quiet 2>>"$out/stderr.log" &
  pid=$!
  status=""
  while kill -0 "$pid" 2>/dev/null; do
    now="$(awk -v s="$start" -v n="$(date +%s.%N)" 'BEGIN { printf "%.1f", n - s }')"
    local kb
    kb="$(awk '/^VmRSS/ { print $2 }' "/proc/$pid/status" 2>/dev/null || true)"
    [ -n "$kb" ] && echo "$label,$now,$kb" >> "$rss"
    if awk -v n="$now" -v c="$next_ckpt" 'BEGIN { exit !(n >= c) }'; then
      kill -USR1 "$pid" 2>/dev/null || true
      next_ckpt=$((next_ckpt + every))
    fi
    if [ "$kill_after" != 0 ] && awk -v n="$now" -v k="$kill_after" 'BEGIN { exit !(n >= k) }'; then
      kill -KILL "$pid" 2>/dev/null || true
      wait "$pid" 2>/dev/null || true
      status=killed
      break
    fi
    sleep 1
  done
  if [ -z "$status" ]; then
    if wait "$pid"; then status=0; else status=$?; fi
  fi
  wall="$(awk -v s="$start" -v n="$(date +%s.%N)" 'BEGIN { printf "%.1f", n - s }')"
}

temporaries() { find "$1" -name '*.tmp' | sed "s|^$1/||" | sort | tr '\n' ' '; }

say "soak: default scene x$factor (end time $end_time s), $kills kills, $threads threads, seed $seed, $(date -u +%FT%TZ)"

echo "run,seconds,rss_kb" > "$out/rss_straight.csv"
watch_run "$out/rss_straight.csv" straight 0 run "$out/scene.toml" "${sets[@]}" --out "$out/straight"
straight_wall="$wall"
say "straight run: exit $status, $straight_wall s"
[ "$status" = 0 ] || { say "soak: FAILED (the straight run did not complete)"; exit 1; }

# Kill instants: uniform in [0.2, 1.0] x (straight wall time / kills) after each (re)start, so
# the kills fall over the whole run and the last resume still has part of it to do.
echo "run,seconds,rss_kb" > "$out/rss_killed.csv"
ok=1
started=0
for ((k = 1; k <= kills; ++k)); do
  delay="$(awk -v w="$straight_wall" -v n="$kills" -v r="$RANDOM" 'BEGIN { printf "%.1f", (0.2 + 0.8 * r / 32767) * w / n }')"
  if [ "$started" = 0 ] || [ ! -f "$out/killed/checkpoint.h5" ]; then
    args=(run "$out/scene.toml" "${sets[@]}" --out "$out/killed")
    mode=start
    if [ "$started" = 1 ]; then rm -rf "$out/killed"; mode="start again (no checkpoint yet)"; fi
  else
    args=(run "$out/scene.toml" "${sets[@]}" --resume "$out/killed")
    mode=resume
  fi
  started=1
  watch_run "$out/rss_killed.csv" "segment$k" "$delay" "${args[@]}"
  if [ "$status" != killed ]; then
    say "kill $k: the run ended (exit $status) before the kill at $delay s"
    [ "$status" = 0 ] || ok=0
    break
  fi
  ckpt="none"
  [ -f "$out/killed/checkpoint.h5" ] && ckpt="$(awk -v m="$(stat -c %Y "$out/killed/checkpoint.h5")" -v n="$(date +%s)" 'BEGIN { print n - m " s old" }')"
  say "kill $k: $mode, SIGKILL after $delay s; checkpoint $ckpt; temporaries: $(temporaries "$out/killed")"
done
if [ "$status" = killed ]; then
  watch_run "$out/rss_killed.csv" final 0 run "$out/scene.toml" "${sets[@]}" --resume "$out/killed"
  say "final resume: exit $status, $wall s"
  [ "$status" = 0 ] || ok=0
fi

# Identity: every file of the straight run, byte for byte, except: summary.json without its
# wall-clock figures; .vdb files without the random UUID OpenVDB gives each file; and
# checkpoint.h5, whose last state depends on when the SIGUSR1s came (resume checks it instead).
no_uuid() { perl -0777 -pe 's/[0-9a-f]{8}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{12}/UUID/g' "$1"; }
strip_wall() {
  sed -E 's/"(wall_seconds|particle_steps_per_second|particle_steps_per_second_per_thread|seconds)": [^,]*,?//g;
          /"phase_seconds"/d' "$1"
}
files=0 differ=0
while IFS= read -r f; do
  files=$((files + 1))
  if [ "$f" = summary.json ]; then
    cmp -s <(strip_wall "$out/straight/$f") <(strip_wall "$out/killed/$f") || { say "differs: $f"; differ=$((differ + 1)); }
  elif [[ "$f" == *.vdb ]]; then
    cmp -s <(no_uuid "$out/straight/$f") <(no_uuid "$out/killed/$f") || { say "differs: $f"; differ=$((differ + 1)); }
  elif ! cmp -s "$out/straight/$f" "$out/killed/$f"; then
    say "differs: $f"
    differ=$((differ + 1))
  fi
done < <(cd "$out/straight" && find . -type f ! -name '*.tmp' ! -name checkpoint.h5 | sed 's|^\./||' | sort)
[ "$differ" = 0 ] || ok=0
left="$(temporaries "$out/killed")"
[ -z "$left" ] || ok=0
say "identity: $((files - differ)) of $files files identical to the straight run"
say "temporaries left at the end: ${left:-none}"

# Memory (MB), samples after the first 10 s of each start: first, median, last and peak.
for run in straight killed; do
  mb="$(awk -F, 'NR > 1 && $2 >= 10 { printf "%.0f\n", $3 / 1024 }' "$out/rss_$run.csv")"
  if [ -z "$mb" ]; then say "rss $run: no samples"; continue; fi
  n="$(echo "$mb" | wc -l)"
  say "rss $run (MB): first $(echo "$mb" | head -1), median $(echo "$mb" | sort -n | sed -n "$(((n + 1) / 2))p"), last $(echo "$mb" | tail -1), peak $(echo "$mb" | sort -n | tail -1) ($n samples)"
done
if [ "$ok" = 1 ]; then say "soak: passed"; else say "soak: FAILED"; fi
[ "$ok" = 1 ]
