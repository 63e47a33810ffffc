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
wall() {  # wall seconds of a command
  local t0 t1
  t0=$(date +%s.%N); "$@"; t1=$(date +%s.%N)
  echo "$t1 - $t0" | bc -l
}
echo "camdyn sweep speed-up: 200 points, case A7 scene, cam.speed_rev_s 5..9, t_end = $t_end s"
echo "cores: $(nproc); load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
w1=$(wall "$camdyn" sweep "${args[@]}" --jobs 1 --out "$work/j1")
w2=$(wall "$camdyn" sweep "${args[@]}" --jobs 2 --out "$work/j2")
if command -v mpirun >/dev/null; then
  wm=$(wall mpirun --allow-run-as-root --oversubscribe -np 2 "$camdyn" sweep "${args[@]}" --out "$work/m2")
  cmp "$work/j1/sweep.csv" "$work/m2/sweep.csv"
else
  wm=nan
fi
cmp "$work/j1/sweep.csv" "$work/j2/sweep.csv"
sep=$(awk -F, 'NR>1 && $3>0' "$work/j1/sweep.csv" | wc -l)
printf '%-16s %10s %9s\n' run "wall [s]" speed-up
printf '%-16s %10.2f %9.2f\n' "--jobs 1" "$w1" 1
printf '%-16s %10.2f %9.2f\n' "--jobs 2" "$w2" "$(echo "$w1 / $w2" | bc -l)"
if [ "$wm" != nan ]; then
  printf '%-16s %10.2f %9.2f\n' "mpirun -np 2" "$wm" "$(echo "$w1 / $wm" | bc -l)"
fi
echo "rows identical (--no-timing): yes; points that separate: $sep of 200"
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
