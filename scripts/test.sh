#!/usr/bin/env bash
# camdyn — build and run the test suite (from any directory):
#   scripts/test.sh [CTEST ARGS...]      the default suite (every test but the label "long"),
#                                        e.g. scripts/test.sh -L stability
#   scripts/test.sh --long [CTEST ARGS]  only the long runs (label "long": B1 for 100
#                                        revolutions, the shared-library install test,
#                                        ~10–15 min), e.g. scripts/test.sh --long -R shared
# Installs missing Debian packages first (no apt at all when nothing is missing), builds
# build/ (Release, Ninja) and runs ctest; exits non-zero on any failure.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"

"$ROOT/scripts/setup.sh" --build-only
if [[ "${1:-}" == "--long" ]]; then
  shift
  exec ctest --test-dir build --output-on-failure -j2 -L long "$@"
fi
exec ctest --test-dir build --output-on-failure -j2 -LE long "$@"
