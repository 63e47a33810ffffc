#!/usr/bin/env bash
# The README's quick starts, run as a new user would (issue 26):
#   * README.md has at most 250 lines;
#   * the ```sh block after "<!-- quickstart: cli -->" runs (bash -e) in a fresh directory
#     holding build/ (this build) and examples/;
#   * the ```python block after "<!-- quickstart: python -->" runs with build/python on
#     PYTHONPATH in the same directory.
# usage: readme_quickstart_test.sh README.md BUILD_DIR WORK_DIR
set -euo pipefail
README=$1 BUILD=$2 WORK=$3
ROOT="$(cd "$(dirname "$README")" && pwd)"

lines=$(wc -l < "$README")
if (( lines > 250 )); then
  echo "README.md has $lines lines (at most 250: move the rest into docs/)" >&2
  exit 1
fi
echo "README.md: $lines lines"

# The fenced block right after the marker line.
block() {
  awk -v m="$1" '
    $0 == m { found = 1; next }
    found == 1 && /^```/ { found = 2; next }
    found == 2 && /^```/ { exit }
    found == 2 { print }' "$README"
}

rm -rf "$WORK"
mkdir -p "$WORK"
ln -s "$BUILD" "$WORK/build"
ln -s "$ROOT/examples" "$WORK/examples"
block '<!-- quickstart: cli -->' > "$WORK/quickstart.sh"
block '<!-- quickstart: python -->' > "$WORK/quickstart.py"
for f in quickstart.sh quickstart.py; do
  [[ -s "$WORK/$f" ]] || { echo "README: no block after the marker for $f" >&2; exit 1; }
done
cd "$WORK"
echo "== command line"
cat quickstart.sh
bash -euo pipefail quickstart.sh
echo "== Python"
PYTHONPATH=build/python MPLBACKEND=Agg /usr/bin/python3 quickstart.py
echo "readme_quickstart: both quick starts ran"
