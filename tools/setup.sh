#!/usr/bin/env bash
# Talus set-up on Debian 12: install the Debian packages Talus needs, build, then either run the
# embedded default scene (`demo`, the default) or the test suite (`test`).
#   bash tools/setup.sh          # install, build, run the default scene into ./talus_out
#   bash tools/setup.sh test     # install, build, run the tests, then the sanitized tests and the
#                                # fuzzers of the file readers (what CI runs)
#   bash tools/setup.sh quick    # install, build, run the tests only
set -euo pipefail

mode="${1:-demo}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${TALUS_BUILD_DIR:-$root/build}"

packages=(
  cmake ninja-build g++ pkg-config ccache
  libopenvdb-dev libblosc-dev libboost-iostreams-dev libtbb-dev libeigen3-dev
  libhdf5-dev zlib1g-dev libgtest-dev libtomlplusplus-dev libcli11-dev
  libgdal-dev gdal-bin libcairo2-dev libnlopt-cxx-dev libhwy-dev
  libopenmpi-dev openmpi-bin
  clang libclang-rt-14-dev
  pybind11-dev python3-dev python3-numpy
  ffmpeg
)
# What only the tests use: pytest and the examples' h5py and Matplotlib (the Python module),
# Chromium, which loads report.html headless, and Blender, which `talus render` drives (optional
# for users: the command says how to install it).
if [ "$mode" != demo ]; then
  packages+=(python3-pytest python3-h5py python3-matplotlib chromium blender)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "talus setup: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

jobs="$(nproc)"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
# The demo builds only what it runs (the talus program); the tests build everything.
if [ "$mode" = demo ]; then
  cmake --build "$build" -j "$jobs" --target talus
else
  cmake --build "$build" -j "$jobs"
fi

sanitized_checks() {
  # ASan + UBSan build (clang) of the libraries, the test suite and the libFuzzer targets.
  local san="${TALUS_SANITIZE_BUILD_DIR:-$root/build-san}"
  CC=clang CXX=clang++ cmake -S "$root" -B "$san" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DTALUS_SANITIZE=ON -DTALUS_FUZZ=ON >/dev/null
  cmake --build "$san" -j "$jobs"
  # The MPI tests (Ranks*, RunOnRanks*) run in the Release stage only: they launch mpirun, and
  # the kernels they run are the ones the sanitized suite covers in one process.
  # The long physics validations repeat kernels the other tests already run under the
  # sanitizers; skipping them keeps CI inside its budget (the loads on colliders, calibration,
  # detrainment and the two slowest hard cases were 10 of the sanitized suite's 28 test-minutes:
  # their kernels run under the sanitizers in the shorter tests of the same classes).
  # The water's smooth_pressure splash test took 207 s under the sanitizers (31 s in Release); its
  # pass runs under them in TaitWater.SmoothPressureIsBitIdenticalAtOneAndTwoThreads (24 s).
  # Resume.ARunExtended... (93 s sanitized) repeats the checkpoint read and write of
  # Resume.KilledAfterACheckpoint... (85 s, kept), and the rock block into ice and snow (54 s) the
  # kernels of the other hard cases: both run in the Release suite.
  # Two write-fault tests check the system's cause in the message (ENOSPC, EFBIG): in the clang/ASan build HDF5's error stack does not carry
  # it ("HDF5 call failed"), so they run in the Release suite only (not yet understood).
  ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir "$san" --output-on-failure -j "$jobs" --timeout 1200 \
    -E "Ranks|ColumnCollapse|Heap\.|DamBreak|ImpulseWave|WaterSurfaceMap\.ADam|WaterColumn|SnowSlab|Determinism|BasalLaws|Rheology|MuI\.Steady|DiskFull\.ARunFillingATmpfs|WriteFaults\.AFileSizeLimit|ColliderLoads\.(WallPanels|APanels|AWallPanelOnAJet)|Calibration\.Recovers|Detrainment\.A(Slow|Fast)|HardCases\.(StiffRock|RockBlockHitsWater)|TaitWater\.SmoothPressureKeeps|Resume\.ARunExtended|HardCases\.RockBlockHitsIce"
  # Each reader of user files is fuzzed from its committed seed corpus (tests/fuzz/seeds/<target>/)
  # in a scratch copy: the scene reader for TALUS_FUZZ_SECONDS (90), the others for
  # TALUS_FUZZ_FILE_SECONDS (25) each.
  local target corpus seconds sealed
  # Allocations over 1 GB return NULL as malloc does on a real machine: a damaged size field
  # inside HDF5's own metadata makes HDF5 ask for terabytes, and HDF5 fails cleanly on NULL (Talus
  # refuses the file) where ASan's default would abort the run.
  local asan=detect_leaks=0:allocator_may_return_null=1:max_allocation_size_mb=1024
  local -A runs=([scene]=350 [raster]=12000 [polygon]=11000 [level_set]=7800 [checkpoint]=4000)
  for target in scene raster polygon level_set checkpoint; do
    corpus="$(mktemp -d)"
    cp "$root"/tests/fuzz/seeds/"$target"/* "$corpus"/
    seconds="${TALUS_FUZZ_FILE_SECONDS:-25}"
    if [ "$target" = scene ]; then
      cp "$root"/data/scenes/*.toml "$corpus"/
      seconds="${TALUS_FUZZ_SECONDS:-90}"
    fi
    echo "talus setup: fuzzing the $target reader for $seconds s"
    # A fixed seed and a cap on the number of inputs: every CI run replays the same mutations
    # whatever the machine's speed, so CI is reproducible (explore with other seeds and longer runs
    # by hand). The seed does not fix the sequence entirely (comparisons traced on addresses vary
    # with ASLR).
    sealed=1
    if [ "$target" = checkpoint ]; then
      # The checkpoint's sealed seeds (a body behind a valid checksum) are replayed once; the
      # mutations stay in front of the checksum (TALUS_FUZZ_SEALED=0). Mutating behind it reached
      # HDF5 1.10's own parser, which on such forged files copies from NULL or allocates without
      # end (CI of stop 61 at input 302): faults of HDF5's, docs/reliability.md.
      ASAN_OPTIONS=$asan "$san/tests/fuzz/talus_checkpoint_fuzzer" "$root"/tests/fuzz/seeds/checkpoint/*
      sealed=0
    fi
    ASAN_OPTIONS=$asan TALUS_FUZZ_SEALED=$sealed \
      "$san/tests/fuzz/talus_${target}_fuzzer" "$corpus" -seed=1 -runs="${runs[$target]}" \
      -max_total_time="$seconds" -rss_limit_mb=3072 -timeout=30 -print_final_stats=1
    rm -rf "$corpus"
  done
}

# Open MPI refuses to start as root unless told so (CI runs as root); the MPI tests launch mpirun.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

case "$mode" in
  demo)
    "$build/tools/talus" run --out "${TALUS_OUT:-$root/talus_out}"
    ;;
  test)
    ctest --test-dir "$build" --output-on-failure -j "$jobs" --timeout 1200
    sanitized_checks
    ;;
  quick)
    ctest --test-dir "$build" --output-on-failure -j "$jobs" --timeout 1200
    ;;
  build)
    ;;
  *)
    echo "usage: tools/setup.sh [demo|test|quick|build]" >&2
    exit 2
    ;;
esac
