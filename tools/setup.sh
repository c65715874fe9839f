#!/usr/bin/env bash
# Talus set-up on Debian 12: install the Debian packages Talus needs, build, then either run the
# embedded default scene (`demo`, the default) or the test suite (`test`).
#   bash tools/setup.sh          # install, build, run the default scene into ./talus_out
#   bash tools/setup.sh test     # install, build, run the tests
set -euo pipefail

mode="${1:-demo}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${TALUS_BUILD_DIR:-$root/build}"

packages=(
  cmake ninja-build g++ pkg-config ccache
  libopenvdb-dev libboost-iostreams-dev libtbb-dev libeigen3-dev
  libhdf5-dev libgtest-dev libtomlplusplus-dev libcli11-dev
  libgdal-dev gdal-bin libcairo2-dev
)

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
cmake --build "$build" -j "$jobs"

case "$mode" in
  demo)
    "$build/tools/talus" run --out "${TALUS_OUT:-$root/talus_out}"
    ;;
  test)
    ctest --test-dir "$build" --output-on-failure -j "$jobs" --timeout 1200
    ;;
  build)
    ;;
  *)
    echo "usage: tools/setup.sh [demo|test|build]" >&2
    exit 2
    ;;
esac
