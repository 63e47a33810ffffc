#!/usr/bin/env bash
# camdyn — first-time setup on Debian 12 (run as root, from any directory):
#   installs the missing build dependencies, builds camdyn (Release, Ninja) into build/,
#   runs the built-in default scene (the paper's case B2) and draws its figures.
#
#   scripts/setup.sh              everything above
#   scripts/setup.sh --deps-only  only install the missing Debian packages
#   scripts/setup.sh --build-only install missing packages and build, no run
#   scripts/setup.sh --peers      only the optional peers of bench/peers/peers.py (Siconos,
#                                 MuJoCo: python3-siconos libmujoco-dev); nothing else needs them
# The documentation site: scripts/docs.sh after a build (Sphinx, MyST, Breathe, Doxygen).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"

PACKAGES=(build-essential cmake ninja-build libsundials-dev libeigen3-dev libsuitesparse-dev
          libtomlplusplus-dev libcli11-dev libgtest-dev googletest libbenchmark-dev
          python3 python3-numpy python3-matplotlib clang libclang-rt-14-dev
          pybind11-dev python3-dev python3-pytest pkg-config
          libopenmpi-dev openmpi-bin chromium
          python3-sphinx python3-myst-parser python3-breathe doxygen)

# Install the packages of PACKAGES that are not installed yet (no apt at all otherwise).
install_missing_packages() {
  local missing=() p status
  for p in "${PACKAGES[@]}"; do
    status="$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)"
    if [[ "$status" != "installed" ]]; then
      missing+=("$p")
    fi
  done
  if [[ ${#missing[@]} -eq 0 ]]; then
    echo "setup: all build dependencies are installed"
    return 0
  fi
  echo "setup: installing ${missing[*]}"
  local sudo=()
  if [[ "$(id -u)" -ne 0 ]]; then
    if command -v sudo >/dev/null 2>&1; then
      sudo=(sudo)
    else
      echo "setup: missing packages (${missing[*]}) and not root: run this script as root" >&2
      return 1
    fi
  fi
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive \
    apt-get install -y --no-install-recommends "${missing[@]}"
}

# Configure (once) and build build/ in Release with Ninja.
configure_and_build() {
  if [[ ! -f build/CMakeCache.txt ]]; then
    cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
  else
    cmake -S . -B build  # re-run: picks up new source files (the globs)
  fi
  cmake --build build -j2
}

mode="${1:-all}"
case "$mode" in
  --deps-only)
    install_missing_packages
    exit 0
    ;;
  --build-only)
    install_missing_packages
    configure_and_build
    exit 0
    ;;
  --peers)
    PACKAGES=(python3-siconos libmujoco-dev)
    install_missing_packages
    exit 0
    ;;
  all | "")
    ;;
  *)
    echo "usage: scripts/setup.sh [--deps-only | --build-only | --peers]" >&2
    exit 2
    ;;
esac

install_missing_packages
configure_and_build

echo
echo "setup: running the default scene (paper case B2: elastic follower at 5 rev/s)"
./build/camdyn run --out camdyn-out --plot

echo
echo "setup: done."
echo "  program:  $ROOT/build/camdyn   (camdyn --help)"
echo "  outputs:  $ROOT/camdyn-out/history.csv, events.csv, summary.json"
shopt -s nullglob
figures=("$ROOT"/camdyn-out/*.png)
if [[ ${#figures[@]} -gt 0 ]]; then
  echo "  figures:  ${figures[*]}"
else
  echo "  figures:  none drawn (python3-matplotlib missing?)"
fi
