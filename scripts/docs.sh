#!/usr/bin/env bash
# camdyn — build the documentation site (from any directory):
#   scripts/docs.sh [BUILD_DIR]      default BUILD_DIR: build/ (must hold the built camdyn and
#                                    build/python; scripts/setup.sh --build-only makes them)
# Output: BUILD_DIR/docs/html/index.html. Sphinx + MyST (Markdown pages) + Breathe (C++ API from
# Doxygen XML of include/camdyn) + autodoc (Python API from build/python). Warnings are errors.
#
# Steps, each from the code, so no page can drift from it:
#   1. docs/reference/generated/scene_keys.md   ← camdyn scene --keys   (the scene's key table)
#      docs/reference/generated/cli.md          ← camdyn --help, camdyn CMD --help
#   2. docs/_generated/tutorials/*               ← the tutorials' figures, by running the tutorial
#      files in docs/tutorials/ (skipped with CAMDYN_DOCS_TUTORIALS=skip when ctest ran them)
#   3. BUILD_DIR/docs/doxygen/xml                ← doxygen on include/camdyn
#   4. sphinx-build -W --keep-going -b html docs BUILD_DIR/docs/html
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="$(cd "${1:-$ROOT/build}" && pwd)"
CAMDYN="$BUILD/camdyn"
PYTHON="${CAMDYN_PYTHON:-/usr/bin/python3}"   # Debian's, where python3-sphinx etc. live
OUT="$BUILD/docs"
[[ -x "$CAMDYN" ]] || { echo "docs: $CAMDYN not built (scripts/setup.sh --build-only)" >&2; exit 2; }
for tool in doxygen sphinx-build; do
  command -v "$tool" >/dev/null || { echo "docs: $tool missing (scripts/setup.sh --deps-only)" >&2; exit 2; }
done

# 1. generated reference pages
GEN="$ROOT/docs/reference/generated"
mkdir -p "$GEN"
"$CAMDYN" scene --keys > "$GEN/scene_keys.md.tmp" && mv "$GEN/scene_keys.md.tmp" "$GEN/scene_keys.md"
{
  echo '**camdyn**'
  echo
  echo '```text'
  "$CAMDYN" --help
  echo '```'
  for cmd in run cam scene plot report bench jump sweep spectrum campbell; do
    echo
    echo "**camdyn $cmd**"
    echo
    echo '```text'
    "$CAMDYN" "$cmd" --help
    echo '```'
  done
} > "$GEN/cli.md.tmp"
mv "$GEN/cli.md.tmp" "$GEN/cli.md"
# the history columns line of `camdyn run --help`
"$CAMDYN" run --help | sed -n 's/^history.csv columns: \(.*\)$/\1/p' |
  tr ',' '\n' | sed 's/.*/`&`/' | paste -sd' ' > "$GEN/history_columns.md"
[[ -s "$GEN/history_columns.md" ]] || { echo "docs: no history columns in camdyn run --help" >&2; exit 1; }

# 2. the tutorials' figures
if [[ "${CAMDYN_DOCS_TUTORIALS:-run}" != "skip" ]]; then
  CAMDYN_BUILD_DIR="$BUILD" "$ROOT/docs/tutorials/run_tutorial.sh" all
fi

# 3. Doxygen XML of the public headers
mkdir -p "$OUT/doxygen"
sed -e "s|@INPUT@|$ROOT/include/camdyn|" -e "s|@OUTPUT@|$OUT/doxygen|" \
  "$ROOT/docs/Doxyfile.in" > "$OUT/doxygen/Doxyfile"
(cd "$OUT/doxygen" && doxygen Doxyfile > doxygen.log 2>&1) ||
  { cat "$OUT/doxygen/doxygen.log" >&2; echo "docs: doxygen failed" >&2; exit 1; }

# 4. the site
rm -rf "$OUT/html" "$OUT/doctrees"
CAMDYN_BUILD_DIR="$BUILD" CAMDYN_DOXYGEN_XML="$OUT/doxygen/xml" \
  "$PYTHON" -m sphinx -W --keep-going -q -b html -d "$OUT/doctrees" "$ROOT/docs" "$OUT/html"
# 5. every key of the key table is on the built scene-key page
"$CAMDYN" scene --keys --json | "$PYTHON" -c '
import html, json, sys
page = open(sys.argv[1], encoding="utf-8").read()
keys = [k["key"] for k in json.load(sys.stdin)]
# a key is on the page as an inline-code cell: <span class="pre">cam.lift</span></code>
missing = [k for k in keys if "<span class=\"pre\">" + html.escape(k) + "</span></code>" not in page]
if missing:
    sys.exit("docs: keys missing from the built scene-key page: " + ", ".join(missing))
print(f"docs: all {len(keys)} scene keys are on reference/scene_keys.html")
' "$OUT/html/reference/scene_keys.html"
echo "docs: $OUT/html/index.html"
