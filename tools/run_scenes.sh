#!/usr/bin/env bash
# Runs the cascade scenes of data/scenes/ to their end, checks that each finished, and derives the
# numbers and figures of docs/scenes/*.md from their outputs (not in CI: minutes per scene).
#
#   bash tools/run_scenes.sh                         # every scene, outputs in ./scenes_out/<scene>
#   bash tools/run_scenes.sh vajont whymper          # some of them
#   TALUS_SCENES_OUT=/tmp/s bash tools/run_scenes.sh cengalo -- --set simulation.dx=2
#   bash tools/run_scenes.sh --analyse-only fluela   # redo the post-processing of an earlier run
#
# Options (environment): TALUS (the binary, default build/tools/talus), TALUS_SCENES_OUT (output
# root, default ./scenes_out), TALUS_THREADS (default 2). Arguments after `--` go to every
# `talus run`. The Wolfsgruben scene needs ../shared next to the project and is skipped without it.
# Each scene's derived results are in <out>/<scene>/analysis/ (text, CSV, PNG). Exit status: the
# number of scenes that failed.
set -uo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
talus="${TALUS:-$root/build/tools/talus}"
out="${TALUS_SCENES_OUT:-$PWD/scenes_out}"
threads="${TALUS_THREADS:-2}"
all=(vajont cengalo fluela whymper wolfsgruben)

scenes=()
extra=()
analyseOnly=0
while (($#)); do
  case "$1" in
    --) shift; extra=("$@"); break ;;
    --analyse-only) analyseOnly=1 ;;
    -h|--help) sed -n '2,15p' "${BASH_SOURCE[0]}"; exit 0 ;;
    *) scenes+=("$1") ;;
  esac
  shift
done
((${#scenes[@]})) || scenes=("${all[@]}")
[ -x "$talus" ] || { echo "run_scenes: $talus not found (build first: ninja -C build)" >&2; exit 2; }

shared="$root/../shared/data/avaframe_avaWog"
ref="$shared/reference_com1DFA_avaWogNullTest/relWog_005698a9de_C_L_null_dfa"

# Scene-specific post-processing; $1 = the scene's output directory.
analyse_vajont() {
  local d="$1" a="$1/analysis"
  "$talus" series-stats "$d/series.csv" > "$a/series_stats.txt"
  # Run-up: the highest ground the water reached (at least 0.5 m deep), and the wetted area.
  "$talus" map-stats "$d/maps/water/max_flow_height_vertical.tif" --threshold 0.5 --threshold 2 \
    --ground "$d/maps/ground_elevation.tif" > "$a/water_extent.txt"
  # Deposit cross-sections across the valley (west to east), before and after.
  local y
  for y in 250 375 500; do
    "$talus" profile "$d/maps/rock/initial_thickness.tif" "$d/maps/rock/deposit_thickness.tif" \
      --label "rock before" --label "rock after" --ground "$d/maps/ground_elevation.tif" \
      --line "2600000,$((1200000 + y)) 2600700,$((1200000 + y))" --step 5 \
      --title "Cross-section y = $y m: slide before and after" \
      --out "$a/section_y$y.csv" --plot "$a/section_y$y.png" > "$a/section_y$y.txt"
  done
}

analyse_cengalo() {
  local d="$1" a="$1/analysis"
  "$talus" series-stats "$d/series.csv" > "$a/series_stats.txt"
  {
    echo "# eroded ice (volume = Σ erosion depth x cell area)"
    "$talus" map-stats "$d/maps/ice/erosion_depth.tif" --threshold 0.01
    echo "# initial ice"
    "$talus" map-stats "$d/maps/ice/initial_thickness.tif" --threshold 0.01
    echo "# eroded sediment"
    "$talus" map-stats "$d/maps/sediment/erosion_depth.tif" --threshold 0.01
    echo "# rock deposit: run-out along the valley axis from the face"
    "$talus" map-stats "$d/maps/rock/deposit_thickness.tif" --threshold 0.5 --threshold 5 \
      --path "2600200,1200600 2602190,1200600" --half-width 300
  } > "$a/volumes.txt"
}

analyse_fluela() {
  local d="$1" a="$1/analysis"
  "$talus" series-stats "$d/series.csv" > "$a/series_stats.txt"
  # Longitudinal profile from the top of the release down the flow path.
  "$talus" profile "$d/maps/rock/initial_thickness.tif" "$d/maps/rock/deposit_thickness.tif" \
    "$d/maps/snow/initial_thickness.tif" "$d/maps/snow/deposit_thickness.tif" \
    --label "rock before" --label "rock after" --label "snow before" --label "snow after" \
    --line "2600140,1200450 2601250,1200450" --step 3 \
    --title "Longitudinal profile: rock and snow thickness before and after" \
    --out "$a/profile.csv" --plot "$a/profile.png" > "$a/profile.txt"
  {
    echo "# rock deposit"
    "$talus" map-stats "$d/maps/rock/deposit_thickness.tif" --threshold 0.5 --threshold 5 \
      --ground "$d/maps/ground_elevation.tif" --path "2600140,1200450 2601250,1200450" --half-width 300
    echo "# snow eroded"
    "$talus" map-stats "$d/maps/snow/erosion_depth.tif" --threshold 0.1
    echo "# snow entrained along the path (kg per metre; the snow's density 250 kg/m3)"
    "$talus" map-stats "$d/maps/snow/erosion_depth.tif" --aimec --path "2600140,1200450 2601250,1200450" \
      --domain-width 300 --threshold 0.1 --scale 250 --out "$a/entrained_along_path.csv" \
      --integral-plot "$a/entrained_along_path.png" --integral-label "entrained snow (kg per m of path)"
  } > "$a/deposit.txt"
}

analyse_whymper() {
  local d="$1" a="$1/analysis"
  "$talus" series-stats "$d/series.csv" --front-window 25 --front-step 5 \
    --front-plot "$a/front_speed.png" --front-csv "$a/front_speed.csv" > "$a/series_stats.txt"
  "$talus" profile "$d/maps/max_speed.tif" --label "couloir" --line "2600450,1200400 2601790,1200400" \
    --step 5 --out "$a/max_speed_couloir.csv" > /dev/null
  "$talus" profile "$d/maps/max_speed.tif" --label "glacier" --line "2600450,1200150 2601790,1200150" \
    --step 5 --out "$a/max_speed_glacier.csv" > /dev/null
  {
    # The resting snow cover is >= 0.5 m everywhere along both corridors, so run-out is read from
    # where anything moved (maximum speed) and from the ice alone.
    for p in "couloir 2600450,1200400 2601790,1200400" "glacier 2600450,1200150 2601790,1200150"; do
      set -- $p
      echo "# run-out along the $1 track: maximum speed >= 1 and 5 m/s within 60 m of it"
      "$talus" map-stats "$d/maps/max_speed.tif" --threshold 1 --threshold 5 --path "$2 $3" --half-width 60
      echo "# run-out along the $1 track: ice flow height >= 0.5 m, ice deposit >= 0.1 m"
      "$talus" map-stats "$d/maps/ice/max_flow_height_vertical.tif" --threshold 0.5 --path "$2 $3" --half-width 60
      "$talus" map-stats "$d/maps/ice/deposit_thickness.tif" --threshold 0.1 --path "$2 $3" --half-width 60
    done
  } > "$a/runout.txt"
}

analyse_wolfsgruben() {
  local d="$1" a="$1/analysis"
  "$talus" series-stats "$d/series.csv" > "$a/series_stats.txt"
  local path="$shared/Inputs/LINES/path_aimec.shp"
  {
    echo "# peak flow thickness (slope-normal, m) against ${ref##*/}_pft.asc"
    "$talus" compare "$d/maps/max_flow_height_slope_normal.tif" "${ref}_pft.asc" --threshold 0.1 --threshold 0.5 \
      --threshold 1 --path "$path" --half-width 300 \
      --png "$a/overlap_pft_1m.png" --dem "$shared/Inputs/avaWog.asc" --title "Peak flow thickness >= 0.1 m"
    echo "# peak speed (m/s) against ${ref##*/}_pfv.asc"
    "$talus" compare "$d/maps/max_speed.tif" "${ref}_pfv.asc" --threshold 1 --threshold 10 --threshold 20 \
      --path "$path" --half-width 300
    echo "# peak pressure (kPa) against ${ref##*/}_ppr.asc (AIMEC's run-out: 1 kPa)"
    "$talus" compare "$d/maps/max_pressure.tif" "${ref}_ppr.asc" --threshold 1 --threshold 10 \
      --path "$path" --half-width 300
    echo "# AIMEC: run-out and areas along the path (ppr 1 kPa, pft 0.1 m)"
    "$talus" compare "$d/maps/max_pressure.tif" "${ref}_ppr.asc" --aimec --path "$path" --threshold 1 \
      --dem "$shared/Inputs/avaWog.asc"
    "$talus" compare "$d/maps/max_flow_height_slope_normal.tif" "${ref}_pft.asc" --aimec --path "$path" \
      --threshold 0.1 --dem "$shared/Inputs/avaWog.asc"
  } > "$a/comparison.txt"
}

failed=0
for s in "${scenes[@]}"; do
  scene="$root/data/scenes/$s.toml"
  if [ ! -f "$scene" ]; then
    echo "run_scenes: no scene $scene" >&2
    failed=$((failed + 1))
    continue
  fi
  if [ "$s" = wolfsgruben ] && [ ! -d "$shared" ]; then
    echo "run_scenes: $s skipped: $shared not found"
    continue
  fi
  d="$out/$s"
  if ((!analyseOnly)); then
    echo "run_scenes: $s -> $d"
    rm -rf "$d"
    if ! "$talus" run "$scene" --out "$d" --threads "$threads" --quiet "${extra[@]}"; then
      echo "run_scenes: $s FAILED (talus run)" >&2
      failed=$((failed + 1))
      continue
    fi
  fi
  # Finished: status completed and the simulated time is the scene's end time.
  status="$(sed -n 's/.*"status": "\([^"]*\)".*/\1/p' "$d/summary.json")"
  simulated="$(sed -n 's/.*"simulated_time": \([0-9.eE+-]*\).*/\1/p' "$d/summary.json")"
  endTime="$(sed -n 's/^end_time *= *\([0-9.]*\).*/\1/p' "$scene" | head -1)"
  for ((i = 0; i < ${#extra[@]}; i++)); do
    case "${extra[$i]}" in simulation.end_time=*) endTime="${extra[$i]#*=}" ;; esac
  done
  if [ "$status" != completed ] || ! awk -v a="$simulated" -v b="$endTime" 'BEGIN { exit !(a + 1e-9 >= b) }'; then
    echo "run_scenes: $s FAILED: status '$status', simulated $simulated s of $endTime s" >&2
    failed=$((failed + 1))
    continue
  fi
  mkdir -p "$d/analysis"
  if ! "analyse_$s" "$d"; then
    echo "run_scenes: $s FAILED (post-processing)" >&2
    failed=$((failed + 1))
    continue
  fi
  particles="$(sed -n 's/.*"particles": \([0-9]*\),.*/\1/p' "$d/summary.json" | head -1)"
  wall="$(sed -n 's/.*"wall_seconds": \([0-9.]*\).*/\1/p' "$d/summary.json")"
  echo "run_scenes: $s ok: $particles particles, $simulated s simulated in $wall s; results in $d/analysis"
done
exit "$failed"
