#!/usr/bin/env bash
# Speed-up of `camdyn sweep` on one machine: a 200-point speed sweep of a case-A7-like
# scene (paper cam, rigid follower, Lee; separates above 6.41 rev/s) with --jobs 1,
# --jobs 2 and mpirun -np 2, measured side by side (wall time), rows checked identical.
# usage: bench/sweep_speedup.sh [BUILD_DIR] [T_END]   (defaults: build, 2.0 s of cam time)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}
t_end=${2:-2.0}
camdyn=$build/camdyn
work=$(mktemp -d /tmp/camdyn_sweep_bench.XXXXXX)
trap 'rm -rf "$work"' EXIT
args=("$here/examples/case_A7.toml" --key cam.speed_rev_s --from 5 --to 9 --points 200
      --set run.t_end="$t_end" --no-timing --quiet)
TIMEFORMAT='%R %U %S'
wall() {  # "wall cpu" seconds of a command (cpu = user + sys of it and its children)
  local out
  out=$( { time "$@" >/dev/null 2>&1; } 2>&1 | tail -1 )
  set -- $out
  echo "$1 $(echo "$2 + $3" | bc -l)"
}
echo "camdyn sweep speed-up: 200 points, case A7 scene, cam.speed_rev_s 5..9, t_end = $t_end s"
echo "cores: $(nproc); load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
read -r w1 c1 < <(wall "$camdyn" sweep "${args[@]}" --jobs 1 --out "$work/j1")
read -r w2 c2 < <(wall "$camdyn" sweep "${args[@]}" --jobs 2 --out "$work/j2")
if command -v mpirun >/dev/null; then
  read -r wm cm < <(wall mpirun --allow-run-as-root --oversubscribe -np 2 "$camdyn" sweep "${args[@]}" --out "$work/m2")
  cmp "$work/j1/sweep.csv" "$work/m2/sweep.csv"
else
  wm=nan; cm=nan
fi
cmp "$work/j1/sweep.csv" "$work/j2/sweep.csv"
sep=$(awk -F, 'NR>1 && $3>0' "$work/j1/sweep.csv" | wc -l)
printf '%-16s %10s %10s %9s\n' run "wall [s]" "cpu [s]" speed-up
printf '%-16s %10.2f %10.2f %9.2f\n' "--jobs 1" "$w1" "$c1" 1
printf '%-16s %10.2f %10.2f %9.2f\n' "--jobs 2" "$w2" "$c2" "$(echo "$w1 / $w2" | bc -l)"
if [ "$wm" != nan ]; then
  printf '%-16s %10.2f %10.2f %9.2f\n' "mpirun -np 2" "$wm" "$cm" "$(echo "$w1 / $wm" | bc -l)"
fi
echo "cpu = user + sys of the command and its children (equal cpu and halved wall = perfect scaling)"
echo "rows identical (--no-timing): yes; points that separate: $sep of 200"
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
