#!/usr/bin/env bash
# ctest "sweep_mpi" (label mpi): the same sweep with --jobs 1, --jobs 2 and
# mpirun -np 2 gives byte-identical sweep.csv and poincare.csv (--no-timing writes
# cpu_seconds as 0, the one column that may differ), and the timed runs agree on every
# column but cpu_seconds.
# usage: sweep_mpi_test.sh CAMDYN MPIEXEC SOURCE_DIR WORK_DIR
set -euo pipefail
camdyn=$1; mpiexec=$2; src=$3; work=$4
rm -rf "$work"; mkdir -p "$work"; cd "$work"
args=("$src/examples/case_A7.toml" --key cam.speed_rev_s --from 6 --to 8 --points 9
      --set run.t_end=0.5 --set run.output_dt=0 --set run.settle_revolutions=1 --quiet)
"$camdyn" sweep "${args[@]}" --no-timing --jobs 1 --out j1
"$camdyn" sweep "${args[@]}" --no-timing --jobs 2 --out j2
"$mpiexec" --allow-run-as-root --oversubscribe -np 2 "$camdyn" sweep "${args[@]}" --no-timing --out m2
"$mpiexec" --allow-run-as-root --oversubscribe -np 2 "$camdyn" sweep "${args[@]}" --out m2t
for d in j2 m2; do
  cmp j1/sweep.csv $d/sweep.csv
  cmp j1/poincare.csv $d/poincare.csv
done
# timed: all columns but cpu_seconds
col=$(head -1 j1/sweep.csv | tr ',' '\n' | grep -n '^cpu_seconds$' | cut -d: -f1)
diff <(cut -d, -f"$col" --complement j1/sweep.csv) <(cut -d, -f"$col" --complement m2t/sweep.csv)
rows=$(($(wc -l < j1/sweep.csv) - 1))
[ "$rows" -eq 9 ] || { echo "expected 9 rows, got $rows"; exit 1; }
# --resume on another sweep's directory under mpirun: exit 2, the message printed once
set +e
"$mpiexec" --allow-run-as-root --oversubscribe -np 2 "$camdyn" sweep "$src/examples/case_A7.toml" \
  --key spring.stiffness --from 400 --to 500 --points 3 --quiet --out m2 --resume > bad.txt 2>&1
rc=$?
set -e
[ "$rc" -eq 2 ] || { echo "mpirun --resume on another sweep: exit $rc, expected 2"; cat bad.txt; exit 1; }
[ "$(grep -c 'is from another sweep' bad.txt)" -eq 1 ] || { echo "message not printed once:"; cat bad.txt; exit 1; }
# A network entry's key by name (issue 26): elements.valve_spring.preload of the OHC example,
# the same rows with --jobs 1, --jobs 2 and mpirun -np 2; the key's values in the first column
nargs=("$src/examples/ohc_bucket_tappet.toml" --key elements.valve_spring.preload --from 150 --to 350
       --points 3 --set run.t_end=0.02 --no-timing --quiet)
"$camdyn" sweep "${nargs[@]}" --jobs 1 --out n1
"$camdyn" sweep "${nargs[@]}" --jobs 2 --out n2
"$mpiexec" --allow-run-as-root --oversubscribe -np 2 "$camdyn" sweep "${nargs[@]}" --out nm
cmp n1/sweep.csv n2/sweep.csv
cmp n1/sweep.csv nm/sweep.csv
[ "$(cut -d, -f1 nm/sweep.csv | tr '\n' ' ')" = "elements.valve_spring.preload 150 250 350 " ] ||
  { echo "network sweep: unexpected first column"; cat nm/sweep.csv; exit 1; }
# an unknown entry name under mpirun: exit 2, the names listed, printed once
set +e
"$mpiexec" --allow-run-as-root --oversubscribe -np 2 "$camdyn" sweep "$src/examples/ohc_bucket_tappet.toml" \
  --key elements.spring.preload --from 1 --to 2 --points 2 --quiet --out nbad > nbad.txt 2>&1
rc=$?
set -e
[ "$rc" -eq 2 ] || { echo "mpirun unknown entry name: exit $rc, expected 2"; cat nbad.txt; exit 1; }
[ "$(grep -c "no \[\[elements\]\] entry named 'spring'; \[\[elements\]\] has 2 entries: stem, valve_spring" nbad.txt)" -eq 1 ] ||
  { echo "unknown-name message not printed once:"; cat nbad.txt; exit 1; }
echo "sweep_mpi: --jobs 1, --jobs 2 and mpirun -np 2 agree ($rows rows; network key: 3 rows); bad --resume and a bad entry name exit 2"
