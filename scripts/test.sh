#!/usr/bin/env bash
# camdyn — build and run the test suite (from any directory):
#   scripts/test.sh [CTEST ARGS...]      e.g. scripts/test.sh -L stability
# Installs missing Debian packages first (no apt at all when nothing is missing), builds
# build/ (Release, Ninja) and runs ctest; exits non-zero on any failure.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"

"$ROOT/scripts/setup.sh" --build-only
ctest --test-dir build --output-on-failure -j2 "$@"
