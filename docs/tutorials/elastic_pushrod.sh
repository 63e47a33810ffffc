#!/usr/bin/env bash
# Tutorial 3: an elastic pushrod — choosing the contact method, the engine and the tolerance.
# usage: elastic_pushrod.sh OUT   (run from the repository root, camdyn on PATH)
set -euo pipefail
OUT=$1
SCENE=examples/ohv_pushrod_train.toml   # lifter, pushrod as 4 bar elements, rocker 1.5, valve, seat

# One camshaft revolution at 25 rev/s (the scene's t_end), four ways:
camdyn run "$SCENE" --out "$OUT/lee_erk" --quiet                                  # the default: Lee, arkode-erk, rtol 1e-8
camdyn run "$SCENE" --out "$OUT/lee_dirk" --set solver.integrator=arkode-dirk --quiet
camdyn run "$SCENE" --out "$OUT/event_erk" --set contact.model=event --quiet       # the event-driven baseline
camdyn run "$SCENE" --out "$OUT/lee_erk_rtol6" --set solver.rtol=1e-6 --set contact.tol_u=1e-7 --quiet

# Compare them: steps, CPU, impacts, and how far each valve motion is from the first run.
python3 docs/tutorials/compare_runs.py "$OUT/pushrod_runs.png" \
  "$OUT/lee_erk" "Lee, arkode-erk, rtol 1e-8" \
  "$OUT/lee_dirk" "Lee, arkode-dirk, rtol 1e-8" \
  "$OUT/event_erk" "event-driven, arkode-erk" \
  "$OUT/lee_erk_rtol6" "Lee, arkode-erk, rtol 1e-6"
