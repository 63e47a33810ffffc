#!/usr/bin/env bash
# Lee on cvode-bdf (src/contact/methods/lee_cvode.cpp since issue 23; the tables in
# docs/background/method_notes.md were measured with the deleted lee_multistep.cpp) side by side with Lee on the one-step
# engines and the event-driven method, same scene and tolerance, one process after
# another on this machine: CPU (Summary::cpu_seconds), steps, CVODE restarts, max force.
# usage: bench/lee_cvode_table.sh [BUILD_DIR]
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
camdyn=${1:-$here/build}/camdyn
work=$(mktemp -d /tmp/camdyn_lee_cvode.XXXXXX)
trap 'rm -rf "$work"' EXIT
row() {  # label scene method engine extra --set args...
  local label=$1 scene=$2 method=$3 engine=$4; shift 4
  "$camdyn" run "$scene" --out "$work/o" --set contact.model="$method" \
    --set solver.integrator="$engine" "$@" >/dev/null 2>&1 || true
  python3 - "$work/o/summary.json" "$label" "$method" "$engine" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
print(f"| {sys.argv[2]} | {sys.argv[3]} | {sys.argv[4]} | {s['cpu_seconds']:.3g} | {s['steps']} | "
      f"{s.get('engine_restarts', '')} | {s['separations']}/{s['impacts']} | {s['max_contact_force']:.6g} | "
      f"{'' if s['finished'] else s['message']} |")
PY
}
echo "| scene | method | engine | CPU s | steps | CVODE restarts | sep./impacts | max force | |"
echo "|---|---|---|---:|---:|---:|---|---:|---|"
ex=$here/examples
for e in cvode-bdf arkode-erk arkode-dirk; do row "B1 1 s" $ex/case_B1.toml lee $e; done
row "B1 1 s" $ex/case_B1.toml event cvode-bdf
for e in cvode-bdf arkode-erk; do row "B2 0.3 s" $ex/case_B2.toml lee $e --set run.t_end=0.3; done
row "B2 0.3 s" $ex/case_B2.toml event cvode-bdf --set run.t_end=0.3
for rt in 1e-3 1e-6; do
  for e in cvode-bdf arkode-dirk; do row "stiff bar rtol $rt" $ex/stiff_bar.toml lee $e --set solver.rtol=$rt; done
  row "stiff bar rtol $rt" $ex/stiff_bar.toml event cvode-bdf --set solver.rtol=$rt
done
for e in cvode-bdf arkode-erk arkode-dirk; do
  row "B1 1000 elements 0.05 s" $ex/case_B1.toml lee $e --set follower.elements=1000 --set run.t_end=0.05
done
row "B1 1000 elements 0.05 s" $ex/case_B1.toml event cvode-bdf --set follower.elements=1000 --set run.t_end=0.05
