#!/usr/bin/env bash
# Tutorial 1: a valve train from scratch, from a lift table to the float speed.
# usage: valve_train_from_scratch.sh OUT   (run from the repository root, camdyn on PATH)
set -euo pipefail
OUT=$1
SCENE=docs/tutorials/valve_train.toml

# 1. Check the scene: every key is validated, every default filled in.
camdyn scene "$SCENE" --resolved > "$OUT/resolved.toml"

# 2. The cam: lift, velocity and acceleration over one revolution (cam.csv + figures).
camdyn cam "$SCENE" --out "$OUT/cam" --quiet

# 3. The float (jump) speed of the rigid model: closed form, no simulation.
camdyn jump "$SCENE" --out "$OUT/jump" | tail -1

# 4. One revolution at the design speed, 25 rev/s, with its figures.
camdyn run "$SCENE" --out "$OUT/run_25" --plot --quiet

# 5. Speed sweep across the float speed: one revolution per point, on 2 threads.
camdyn sweep "$SCENE" --key cam.speed_rev_s --from 60 --to 100 --points 21 \
  --set run.t_end=0.025 --jobs 2 --out "$OUT/sweep" --plot --quiet

# 6. Above the float speed: where does the follower leave the cam, where does it land?
camdyn run "$SCENE" --set cam.speed_rev_s=90 --set run.t_end=0.0112 --out "$OUT/run_90" --plot --quiet
python3 - "$OUT/run_90/summary.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
print("90 rev/s: first separation at %.1f deg, first impact at %.1f deg, %.2f m/s" %
      (s["first_separation_theta_deg"], s["first_impact_theta_deg"], s["max_impact_velocity"]))
PY
