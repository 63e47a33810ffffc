#!/usr/bin/env bash
# ctest "report_browser" (label report): the report page of a run and of a sweep (issue 26),
# written by --plot and by `camdyn report DIR`, opens in headless Chromium with every image
# loaded; it refers to no other file; its words agree with the scene's lift table and with
# events.csv (a second path: awk). A page with a broken image is seen as broken (the check
# can fail). Exit 77 (skipped) without chromium (scripts/setup.sh installs it).
# usage: report_browser_test.sh CAMDYN SOURCE_DIR WORK_DIR
set -euo pipefail
camdyn=$1; src=$2; work=$3
chromium=/usr/bin/chromium
[ -x "$chromium" ] || chromium=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$chromium" ]; then echo "chromium not installed: skipped"; exit 77; fi
rm -rf "$work"; mkdir -p "$work"; cd "$work"

# The page with a tiny script that writes a marker after load: ALL-IMAGES-LOADED N when
# every <img> is complete with a natural width, else IMAGES-BROKEN N.
images_in_browser() {  # FILE → the marker text
  local page=$1 check="$work/check_$(basename "$(dirname "$1")").html" profile
  python3 - "$page" "$check" <<'PY'
import sys
t = open(sys.argv[1], encoding="utf-8").read()
js = ("<script>window.addEventListener('load',function(){var im=Array.prototype.slice.call(document.images);"
      "var ok=im.length>0&&im.every(function(i){return i.complete&&i.naturalWidth>0;});"
      "var p=document.createElement('p');p.id='camdyn-check';"
      "p.textContent=(ok?'ALL-IMAGES-LOADED ':'IMAGES-BROKEN ')+im.length;document.body.appendChild(p);});</script>")
assert "</body>" in t
open(sys.argv[2], "w", encoding="utf-8").write(t.replace("</body>", js + "</body>"))
PY
  profile=$(mktemp -d "$work/chromium-profile.XXXXXX")
  timeout 120 "$chromium" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync \
    --user-data-dir="$profile" --virtual-time-budget=5000 --dump-dom "file://$check" 2>/dev/null |
    grep -o '<p id="camdyn-check">[^<]*</p>' | sed 's/<[^>]*>//g'
  rm -rf "$profile"
}

# a network run with --plot: report.html next to the figures
"$camdyn" run "$src/examples/ohc_bucket_tappet.toml" --set contacts.seat.restitution=0.3 --out run --plot --quiet
test -f run/report.html
# a sweep with --plot
"$camdyn" sweep "$src/examples/case_A7.toml" --key cam.speed_rev_s --from 6 --to 8 --points 3 \
  --set run.t_end=0.3 --out sweep --plot --quiet
test -f sweep/report.html
# camdyn report DIR draws the figures again and rewrites the page
rm run/report.html run/*.png
"$camdyn" report run > report.txt
grep -qx "report: run/report.html" report.txt

for f in run/report.html sweep/report.html; do
  if grep -Eo "(src|href)=['\"][^'\"]*" "$f" | grep -v "data:image/png;base64,"; then
    echo "$f refers to something outside itself"; exit 1
  fi
done

got=$(images_in_browser run/report.html)
[ "$got" = "ALL-IMAGES-LOADED 5" ] || { echo "run page: '$got', expected ALL-IMAGES-LOADED 5"; exit 1; }
got=$(images_in_browser sweep/report.html)
[ "$got" = "ALL-IMAGES-LOADED 3" ] || { echo "sweep page: '$got', expected ALL-IMAGES-LOADED 3"; exit 1; }
# control: one image's data cut short → seen as broken
mkdir -p broken
python3 -c "
import re, sys
t = open('run/report.html', encoding='utf-8').read()
t = re.sub(r'base64,([A-Za-z0-9+/]{40})[A-Za-z0-9+/=]+', r'base64,\1', t, count=1)
open('broken/report.html', 'w', encoding='utf-8').write(t)"
got=$(images_in_browser broken/report.html)
[ "$got" = "IMAGES-BROKEN 5" ] || { echo "broken page: '$got', expected IMAGES-BROKEN 5"; exit 1; }

# The words. The scene's lift table peaks at 8 mm at 180°:
grep -q "cam lift: peak 8 mm at 180.0° cam" run/report.html || { echo "no cam-lift sentence"; exit 1; }
# the seat's impacts, counted and the largest found by awk in events.csv (t,kind,v,theta,impulse,contact):
n=$(awk -F, '$2 == "impact" && $6 == "seat"' run/events.csv | wc -l)
v=$(awk -F, '$2 == "impact" && $6 == "seat" && $3 > m { m = $3; th = $4 } END { printf "%.3g m/s at %.1f", m, th * 180 / 3.141592653589793 }' run/events.csv)
[ "$n" -gt 1 ] || { echo "expected several seat impacts with restitution 0.3, got $n"; exit 1; }
grep -Eq "<b>seat</b>: opens [0-9]+ times?, first at [0-9.]+° cam; $n impacts, the largest $v° cam" run/report.html ||
  { echo "seat sentence lacks '$n impacts, the largest $v° cam':"; grep -o "<b>seat</b>[^<]*" run/report.html; exit 1; }
grep -q "Sweep of <code>cam.speed_rev_s</code> from 6 to 8: 3 points" sweep/report.html ||
  { echo "sweep sentence missing"; exit 1; }
echo "report_browser: run page (5 images) and sweep page (3 images) load in $("$chromium" --version 2>/dev/null | head -1)"
