#!/usr/bin/env bash
# Regenerate every measured table and figure the docs quote, from the current build, into
# docs/bench/generated/ (issue 36), each stamped with the commit and the date:
#
#   wp_<case>/            camdyn bench <case>: work_precision.csv/.md, headlines.csv, wp_*.png
#                         for the cases A A7 B1 B2 stiff ohc ohv (full: also B1_1000)
#   tol_sweep/            camdyn bench --tolerance-sweep (quick: 4 decades of rtol, 5 s budget,
#                         every scene but the stiff bar over 0.02 s; tol_sweep_stiff/: the
#                         stiff bar over 0.005 s, references at rtol 1e-8)
#   bench_cam.md          build/bench/bench_cam (bench/bench_cam_table.py): Cam::evaluate and
#                         Cam::motion ns per call, the motion-law run landing on its joints
#                         (when built: cmake --build build --target bench_cam)
#   headline_factors.md   bench/headline_factors.py: for each headline, both runs' steps, rhs
#                         evaluations, Newton iterations and CPU per step, from wp_<case>/
#   scale/                build/bench/bench_scale sweep + scripts/bench_scale_plot.py (when the
#                         bench targets are built: cmake --build build --target bench_scale)
#   one_mechanism.md      bench/one_mechanism_table.py, only with CAMDYN_BEFORE_BIN=<older camdyn>
#   valve_trains.md       bench/valve_train_table.py: the examples' table of docs/guide/valve_trains.md
#   newton_stiff.md       the stiff bar's penalty on cvode-bdf: steps and Newton statistics against
#                         rtol (bench/newton_stats_table.py), the "steps follow the error test" check
#   peers/                bench/peers/peers.py: camdyn, Siconos and MuJoCo on the two-mass valve
#                         train and case A (peers.md, peers.csv, peers_*.png); a peer that is not
#                         installed is skipped with one line (install: scripts/setup.sh --peers)
#   headlines.csv/.md     every case's headlines (Lee against the best penalty and the best
#                         event run at equal accuracy, with their goals); the README and
#                         docs/background/performance.md quote these between
#                         <!-- headline SCENE VERSUS --> … <!-- /headline --> markers, and
#                         tests/study/test_doc_headlines.cpp checks each quote equals them
#   STAMP.md              commit, date, mode, the commands and the run time of each part
#
# usage: scripts/regenerate_docs_numbers.sh [--quick] [--build DIR] [--cases "A B2 ..."]
#                                           [--repeats N] [--quote | --quote-only]
#   --quick   the bench's quick sweep, 1 timing repeat, the short tolerance sweep; the whole
#             run takes under 10 minutes on an idle 2-core machine (the references are
#             cached by camdyn bench: a second run is faster)
#   --quote   also rewrite the quoted headlines in README.md and
#             docs/background/performance.md from the new headlines.csv (otherwise the test
#             tells which quotes are stale); --quote-only: only that, from the existing file
#   --repeats N  timing repeats of every bench run (default 1; the full mode's runs over 1 s
#             are timed once whatever N; 3 triples the full mode's CPU)
#   --cases   only these work-precision cases (the headlines are gathered from every
#             wp_<case>/ present, each stamped by the run that made it)
#   --no-tol-sweep  leave tol_sweep/ as it is
#   --no-peers      leave peers/ as it is
#   --only PARTS    only these parts (comma-separated: wp, tol, scale, cam, factors, one, valve,
#             newton, peers;
#             wp with --cases); their rows are appended to STAMP.md under "partial run"
#   --jobs N  run up to N parts at once (default 1; the work-precision cases, the tolerance
#             sweeps, scale, cam, valve trains, Newton statistics and peers are independent;
#             the costliest cases start first). Each part's CPU column is its own processes'
#             whatever N; its wall column then includes waiting for the other parts
#   --check-repeat CASE   only check: rerun `camdyn bench CASE` with the mode of the committed
#             wp_CASE/ into a temporary directory and compare the rows with
#             scripts/bench_rows_equal.py (timings aside); exit 1 when a row differs
# Timings are CPU seconds (Summary::cpu_seconds, median of the repeats); on a shared
# machine they are noisy: compare ratios. Run it at low priority (it uses nice -n 5).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="$ROOT/build"
MODE=full
QUOTE=0
TOL=1
PEERS=1
ONLY=""
REPEATS=""
CHECK=""
CASES=""
JOBS=1
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) MODE=quick ;;
    --repeats) REPEATS="$2"; shift ;;
    --build) BUILD="$(cd "$2" && pwd)"; shift ;;
    --cases) CASES="$2"; shift ;;
    --quote) QUOTE=1 ;;
    --quote-only) QUOTE=2 ;;
    --no-tol-sweep) TOL=0 ;;
    --no-peers) PEERS=0 ;;
    --only) ONLY="$2"; shift ;;
    --jobs) JOBS="$2"; shift ;;
    --check-repeat) CHECK="$2"; shift ;;
    -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d'; exit 0 ;;
    *) echo "regenerate_docs_numbers.sh: unknown argument '$1' (allowed: --quick, --repeats N, --build DIR, --cases LIST, --quote, --quote-only, --no-tol-sweep, --no-peers, --only PARTS, --jobs N, --check-repeat CASE)" >&2; exit 2 ;;
  esac
  shift
done
quote() {
  python3 - "$ROOT/docs/bench/generated/headlines.csv" "$ROOT/README.md" "$ROOT/docs/background/performance.md" <<'EOF'
import csv, re, sys
with open(sys.argv[1], newline="") as f:
    q = {(r["scene"], r["versus"]): r["quoted"] for r in csv.DictReader(f)}
pat = re.compile(r"(<!-- headline (\S+) (\S+) -->)(.*?)(<!-- /headline -->)")
for path in sys.argv[2:]:
    s = open(path).read()
    t = pat.sub(lambda m: m.group(1) + q.get((m.group(2), m.group(3)), m.group(4)) + m.group(5), s)
    if t != s:
        open(path, "w").write(t)
EOF
}
for part in ${ONLY//,/ }; do
  case "$part" in
    wp|tol|scale|cam|factors|one|valve|newton|peers) ;;
    *) echo "regenerate_docs_numbers.sh: --only: unknown part '$part' (allowed: wp, tol, scale, cam, factors, one, valve, newton, peers)" >&2; exit 2 ;;
  esac
done
[[ "$JOBS" =~ ^[1-9][0-9]*$ ]] || { echo "regenerate_docs_numbers.sh: --jobs: '$JOBS' is not a whole number ≥ 1" >&2; exit 2; }
if [ "$QUOTE" = 2 ]; then quote; exit 0; fi
CAMDYN="$BUILD/camdyn"
[ -x "$CAMDYN" ] || { echo "regenerate_docs_numbers.sh: $CAMDYN not found (build camdyn_cli first)" >&2; exit 2; }
if [ -z "$CASES" ]; then
  CASES="A A7 B1 B2 stiff ohc ohv"
  [ "$MODE" = full ] && CASES="$CASES B1_1000"
  # with --jobs, the costliest cases first (they overlap the rest)
  [ "$JOBS" -gt 1 ] && CASES="$(for c in B1_1000 stiff $CASES; do echo "$c"; done | awk '!seen[$0]++' | grep -xF -f <(tr ' ' '\n' <<< "$CASES") | tr '\n' ' ')"
fi
OUT="$ROOT/docs/bench/generated"
mkdir -p "$OUT"
cd "$ROOT"
if [ -n "$CHECK" ]; then
  [ -f "$OUT/wp_$CHECK/work_precision.md" ] || { echo "regenerate_docs_numbers.sh: --check-repeat: no $OUT/wp_$CHECK/ to compare with" >&2; exit 2; }
  if grep -q "Mode: quick" "$OUT/wp_$CHECK/work_precision.md"; then ARGS=(--quick --repeats 1); else ARGS=(--repeats 1 --budget 10); fi
  TMP="$(mktemp -d)"
  trap 'rm -rf "$TMP"' EXIT
  echo "== check: $CAMDYN bench $CHECK ${ARGS[*]} against $OUT/wp_$CHECK (made at: $(head -1 "$OUT/wp_$CHECK/work_precision.md"))" >&2
  nice -n 5 "$CAMDYN" bench "$CHECK" "${ARGS[@]}" --quiet --no-plot --out "$TMP"
  python3 "$ROOT/scripts/bench_rows_equal.py" "$OUT/wp_$CHECK" "$TMP"
  exit $?
fi
COMMIT="$(git rev-parse --short=12 HEAD 2>/dev/null || echo unknown)"
git diff --quiet HEAD -- src include CMakeLists.txt 2>/dev/null || COMMIT="$COMMIT+uncommitted"
DATE="$(date -u +%Y-%m-%dT%H:%M:%SZ)"
STAMP="Generated by \`scripts/regenerate_docs_numbers.sh$([ "$MODE" = quick ] && echo ' --quick' || true)\` at commit $COMMIT on $DATE (build $BUILD)."
LOG="$OUT/STAMP.md"
T0=$(date +%s)
CPU_TOTAL=0
LOAD0="$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo '?')"
{
  echo "# Generated numbers"
  echo
  echo "$STAMP"
  echo
  echo "| part | command | wall s | CPU s |"
  echo "|---|---|---|---|"
} > "$LOG.tmp"
PARTS="$LOG.parts"  # one file per part (its STAMP rows; .cpu: its CPU seconds), gathered in order
rm -rf "$PARTS"
mkdir -p "$PARTS"
SEQ=0
FRAG="$PARTS/000"
PIDS=()
# the load average every 30 s while the script runs (its range goes to STAMP.md)
( while :; do cut -d' ' -f1 /proc/loadavg 2>/dev/null >> "$PARTS/load"; sleep 30; done ) &
LOAD_PID=$!
trap 'kill "$LOAD_PID" 2>/dev/null || true' EXIT

# The figures need matplotlib (Debian's python3-matplotlib): the first python3 that has it.
PLOT_PY=python3
for py in python3 /usr/bin/python3; do
  if "$py" -c "import matplotlib" 2>/dev/null; then PLOT_PY="$py"; break; fi
done

want() {  # want PART: is this part run (no --only, or listed in it)?
  [ -z "$ONLY" ] || [[ ",$ONLY," == *",$1,"* ]]
}

stamp_md() {  # prepend the stamp to a Markdown file (after its front matter, if any)
  local f="$1"
  [ -f "$f" ] || return 0
  if [ "$(head -1 "$f")" = "---" ]; then
    awk -v s="<!-- $STAMP -->" 'NR==1{print; fm=1; next} fm && $0=="---"{print; print ""; print s; fm=0; next} {print}' "$f" > "$f.tmp"
  else
    { echo "<!-- $STAMP -->"; echo; cat "$f"; } > "$f.tmp"
  fi
  mv "$f.tmp" "$f"
}

logline() {  # logline TEXT: a STAMP row of the current part
  echo "$1" >> "$FRAG"
}

spawn() {  # spawn FN ARGS...: run a part (its rows in its own file), in the background with --jobs
  SEQ=$(( SEQ + 1 ))
  FRAG="$PARTS/$(printf %03d "$SEQ")"
  if [ "$JOBS" -gt 1 ]; then
    while [ "$(running)" -ge "$JOBS" ]; do sleep 2; done
    ( "$@" ) &
    PIDS+=($!)
  else
    "$@"
  fi
}

running() {  # how many spawned parts still run
  local n=0 p
  for p in "${PIDS[@]}"; do kill -0 "$p" 2>/dev/null && n=$(( n + 1 )); done
  echo "$n"
}

gather() {  # wait for every part, then append their rows in order and add up their CPU
  local f p
  for p in "${PIDS[@]}"; do wait "$p" || true; done
  PIDS=()
  for f in "$PARTS"/[0-9][0-9][0-9]; do
    [ -f "$f" ] && cat "$f" >> "$LOG.tmp"
    [ -f "$f.cpu" ] && CPU_TOTAL=$(( CPU_TOTAL + $(awk '{s += $1} END {print s + 0}' "$f.cpu") ))
  done
  rm -f "$PARTS"/[0-9][0-9][0-9] "$PARTS"/[0-9][0-9][0-9].cpu
}

run_part() {  # run_part NAME CMD...: time it (wall, and CPU of the part's processes), log it
  local name="$1"; shift
  local t=$(date +%s) tf rc=0 cpu="–"
  tf="$(mktemp)"
  echo "== $name: $*" >&2
  if [ -x /usr/bin/time ]; then
    /usr/bin/time -f "%U %S" -o "$tf" "$@" || rc=$?
    cpu="$(awk 'END{printf "%.0f", $1 + $2}' "$tf" 2>/dev/null || echo –)"
    [[ "$cpu" =~ ^[0-9]+$ ]] && echo "$cpu" >> "$FRAG.cpu" 
  else
    "$@" || rc=$?
  fi
  rm -f "$tf"
  if [ "$rc" = 0 ]; then
    logline "| $name | \`$*\` | $(( $(date +%s) - t )) | $cpu |"
  else
    logline "| $name | \`$*\` | FAILED (exit $rc) after $(( $(date +%s) - t )) s | $cpu |"
  fi
}

# full: one timing per run unless --repeats N (3 on a quiet machine: runs under 0.1 s are then
# repeated up to 0.2 s, which triples the sweep's CPU), a 10 s CPU budget per run (a run over
# it is stopped and the same setting's tighter tolerances are skipped), elastic bars over 0.05 s
if [ "$MODE" = quick ]; then BENCH_ARGS=(--quick --repeats "${REPEATS:-1}"); else BENCH_ARGS=(--repeats "${REPEATS:-1}" --budget 10); fi
want wp || CASES=""
wp_case() {
  rm -rf "$OUT/wp_$1"
  run_part "work-precision $1" nice -n 5 "$CAMDYN" bench "$1" "${BENCH_ARGS[@]}" --quiet --out "$OUT/wp_$1"
  stamp_md "$OUT/wp_$1/work_precision.md"
}
for c in $CASES; do spawn wp_case "$c"; done

if [ "$MODE" = quick ]; then
  # every scene but the stiff bar over 0.02 s; the stiff bar (its cvode-bdf references at
  # rtol 1e-10 take minutes) over 0.005 s with references at 1e-8, as the hand run of
  # docs/bench_tolerance_sweep.md
  TOL_ARGS=(--rtols 1e-2,1e-4,1e-6,1e-8 --heavy-rtols 1e-2,1e-4,1e-6 --reference-rtol 1e-10 --budget 5 --t-end 0.02
            A A7 B1 B2 ohc ohv)
  TOL_STIFF_ARGS=(--rtols 1e-2,1e-4,1e-6 --heavy-rtols 1e-2,1e-4,1e-6 --reference-rtol 1e-8 --budget 2 --t-end 0.005 stiff)
else
  # every decade, over longer horizons (0.05 s; the stiff bar 0.01 s) with the same
  # references; the sweep's own default (rtol 1e-12 references for every scene, the stiff
  # bar's on cvode-bdf over 0.05 s) takes hours of CPU
  TOL_ARGS=(--rtols 1e-2,1e-3,1e-4,1e-5,1e-6,1e-7,1e-8 --heavy-rtols 1e-2,1e-3,1e-4,1e-5,1e-6
            --reference-rtol 1e-10 --budget 5 --t-end 0.05 A A7 B1 B2 ohc ohv)
  TOL_STIFF_ARGS=(--rtols 1e-2,1e-3,1e-4,1e-5,1e-6 --heavy-rtols 1e-2,1e-3,1e-4,1e-5,1e-6 --reference-rtol 1e-8
                  --budget 2 --t-end 0.01 stiff)
fi
want tol || TOL=2
tol_part() {
  rm -rf "$OUT/$1"
  run_part "$2" nice -n 5 "$CAMDYN" bench --tolerance-sweep "${@:3}" --quiet --out "$OUT/$1"
  stamp_md "$OUT/$1/tol_sweep.md"
}
if [ "$TOL" = 1 ]; then
  spawn tol_part tol_sweep "tolerance sweep" "${TOL_ARGS[@]}"
  spawn tol_part tol_sweep_stiff "tolerance sweep, stiff bar" "${TOL_STIFF_ARGS[@]}"
elif [ "$TOL" = 0 ]; then
  spawn logline "| tolerance sweep | not rerun (--no-tol-sweep) | – | – |"
fi

scale_part() {
  mkdir -p "$OUT/scale"
  if [ "$MODE" = quick ]; then SCALE=(sweep 10000 erk,dirk,cvode 60); else SCALE=(sweep 100000 erk,dirk,cvode 60); fi
  run_part "scale" bash -c "nice -n 5 '$BUILD/bench/bench_scale' ${SCALE[*]} > '$OUT/scale/bench_scale.csv'"
  run_part "scale figure" bash -c "{ printf '# Cost against mesh size (bench_scale ${SCALE[*]})\n\nWhole Lee runs of case B1 with the bar cut into N elements (bench/bench_scale.cpp); figure: bench_scale.png.\n\n![CPU per step, per rhs evaluation and memory per element against N](bench_scale.png)\n\n'; '$PLOT_PY' scripts/bench_scale_plot.py '$OUT/scale/bench_scale.csv' '$OUT/scale/bench_scale.png'; } > '$OUT/scale/bench_scale.md'"
  stamp_md "$OUT/scale/bench_scale.md"
}
if ! want scale; then
  :
elif [ -x "$BUILD/bench/bench_scale" ]; then
  spawn scale_part
else
  spawn logline "| scale | skipped: $BUILD/bench/bench_scale not built (cmake --build build --target bench_scale) | – | – |"
fi

table_part() {  # table_PART NAME OUTFILE CMD: a part that writes one Markdown file
  run_part "$1" bash -c "$3"
  stamp_md "$2"
}
if ! want cam; then
  :
elif [ -x "$BUILD/bench/bench_cam" ]; then
  spawn table_part "cam evaluation" "$OUT/bench_cam.md" "nice -n 5 python3 bench/bench_cam_table.py --bin '$BUILD/bench/bench_cam' $([ "$MODE" = quick ] && echo '--reps 3 --min-time 0.05' || echo '--reps 5 --min-time 0.1') --out '$OUT/bench_cam.md'"
else
  spawn logline "| cam evaluation | skipped: $BUILD/bench/bench_cam not built (cmake --build build --target bench_cam) | – | – |"
fi

if ! want one; then
  :
elif [ -n "${CAMDYN_BEFORE_BIN:-}" ]; then
  spawn table_part "one mechanism" "$OUT/one_mechanism.md" "nice -n 5 python3 bench/one_mechanism_table.py --bin '$CAMDYN' --before-bin '$CAMDYN_BEFORE_BIN' > '$OUT/one_mechanism.md'"
else
  spawn logline "| one mechanism | skipped: set CAMDYN_BEFORE_BIN to an older camdyn binary (bench/one_mechanism_table.py) | – | – |"
fi

if want valve; then
  spawn table_part "valve-train examples" "$OUT/valve_trains.md" "nice -n 5 python3 bench/valve_train_table.py --bin '$CAMDYN' --out '$OUT/valve_trains.md'"
fi
if want newton; then
  spawn table_part "stiff bar Newton statistics" "$OUT/newton_stiff.md" "nice -n 5 python3 bench/newton_stats_table.py --bin '$CAMDYN' --out '$OUT/newton_stiff.md'"
fi

want peers || PEERS=2
if [ "$PEERS" = 1 ]; then
  PEER_ARGS=(--camdyn "$CAMDYN" --build "$BUILD" --out "$OUT/peers")
  [ "$MODE" = quick ] && PEER_ARGS+=(--quick --repeats 1)
  spawn run_part "peers" nice -n 5 /usr/bin/python3 bench/peers/peers.py "${PEER_ARGS[@]}"
elif [ "$PEERS" = 0 ]; then
  spawn logline "| peers | not rerun (--no-peers) | – | – |"
fi
gather

if want wp; then
# every case's headlines in one file, with the text the docs quote
python3 - "$OUT" "$STAMP" A A7 B1 B2 stiff ohc ohv B1_1000 <<'EOF'
import csv, math, os, sys
out, stamp, cases = sys.argv[1], sys.argv[2], sys.argv[3:]
rows = []
for c in cases:
    p = os.path.join(out, f"wp_{c}", "headlines.csv")
    if not os.path.exists(p):
        continue
    with open(p, newline="") as f:
        for r in csv.DictReader(f):
            try:
                x = float(r["ratio"])
            except ValueError:
                x = math.nan
            r["quoted"] = f"{x:.3g}×" if math.isfinite(x) else r["verdict"]
            rows.append(r)
cols = ["scene", "versus", "target", "ratio", "goal", "verdict", "quoted", "lee", "other"]
with open(os.path.join(out, "headlines.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=cols, extrasaction="ignore")
    w.writeheader()
    w.writerows(rows)
with open(os.path.join(out, "headlines.md"), "w") as f:
    f.write(f"<!-- {stamp} -->\n\n# Headlines: Lee's CPU against the best penalty and event runs\n\n")
    f.write(f"Gathered {stamp[10:]} Each case's table carries the stamp of the run that made it "
            "(first line of wp_<case>/work_precision.md).\n\nAt equal accuracy: the cheapest run of each method whose contact-force error "
            "(err_force, per case in wp_<case>/work_precision.md) is at most the target. "
            "Ratio = CPU of the other method / CPU of Lee.\n\n")
    f.write("| scene | versus | target | ratio | goal | verdict | cheapest Lee | cheapest other |\n")
    f.write("|---|---|---|---|---|---|---|---|\n")
    for r in rows:
        f.write(f"| {r['scene']} | {r['versus']} | {r['target']} | {r['quoted']} | {r['goal'] or '–'} | "
                f"{r['verdict']} | {r['lee']} | {r['other']} |\n")
EOF
fi

if want factors; then
  JOBS=1 spawn table_part "headline factors" "$OUT/headline_factors.md" "python3 bench/headline_factors.py --dir '$OUT' --out '$OUT/headline_factors.md'"
  gather
fi

if [ "$QUOTE" = 1 ]; then quote; fi

kill "$LOAD_PID" 2>/dev/null || true
LOAD_RANGE="$(sort -g "$PARTS/load" 2>/dev/null | sed -n '1p;$p' | paste -sd' ' | awk '{print $1 "–" ($2 == "" ? $1 : $2)}')"
rm -rf "$PARTS"
echo "| total$([ "$JOBS" -gt 1 ] && echo " ($JOBS parts at once)") | | $(( $(date +%s) - T0 )) | $CPU_TOTAL |" >> "$LOG.tmp"
{ echo; echo "Load average (1, 5, 15 min) at the start: $LOAD0; at the end: $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo '?'); the 1-minute load sampled every 30 s ranged ${LOAD_RANGE:-?} (the machine's $(nproc 2>/dev/null || echo '?') cores are shared: the CPU column is the parts' own processes)."; } >> "$LOG.tmp"
if [ -n "$ONLY" ] && [ -f "$LOG" ]; then  # a partial run: the full run's record stays, this one is appended
  { echo; echo "## Partial run (--only $ONLY)"; echo; tail -n +3 "$LOG.tmp"; } >> "$LOG"
  rm -f "$LOG.tmp"
else
  mv "$LOG.tmp" "$LOG"
fi
echo "regenerate_docs_numbers.sh: $MODE run done in $(( $(date +%s) - T0 )) s; see $LOG" >&2
