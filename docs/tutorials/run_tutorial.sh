#!/usr/bin/env bash
# Runs a tutorial (or a how-to's code) exactly as its page shows it, and checks that it made
# the figures the page shows. The ctest tests tutorial_* call this; scripts/docs.sh calls it
# with "all" before building the site.
#   docs/tutorials/run_tutorial.sh NAME | all
#   NAME: valve_train_from_scratch | preload_study | elastic_pushrod | own_follower | read_events
# Environment: CAMDYN_BUILD_DIR (default build/): its camdyn, python/ and tutorials/ are used.
# Output: docs/_generated/tutorials/NAME/ (figures included by the pages; not in git).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
BUILD="${CAMDYN_BUILD_DIR:-$ROOT/build}"
# camdyn first on PATH; Debian's python3 (numpy, matplotlib) before any pyenv/venv one.
export PATH="$BUILD:/usr/bin:$PATH" PYTHONPATH="$BUILD/python" MPLBACKEND=Agg
cd "$ROOT"

ALL=(valve_train_from_scratch preload_study elastic_pushrod own_follower read_events)

run_one() {
  local name=$1 out="docs/_generated/tutorials/$1" figures=()
  rm -rf "$out"
  mkdir -p "$out"
  echo "== $name"
  case "$name" in
    valve_train_from_scratch)
      bash docs/tutorials/valve_train_from_scratch.sh "$out"
      figures=(cam/cam_kinematics.png run_25/contact_force.png sweep/sweep_force.png run_90/displacement.png) ;;
    preload_study)
      python3 docs/tutorials/preload_study.py "$out"
      figures=(float_speed_vs_preload.png) ;;
    elastic_pushrod)
      bash docs/tutorials/elastic_pushrod.sh "$out"
      figures=(pushrod_runs.png) ;;
    own_follower)
      "$BUILD/tutorials/own_follower" docs/tutorials/valve_train.toml "$out/cpp" 25
      python3 docs/tutorials/own_follower.py "$out" "$out/cpp"
      figures=(own_follower.png) ;;
    read_events)
      camdyn run examples/ohc_bucket_tappet.toml --set cam.speed_rev_s=75 --out "$out/ohc_75" --quiet
      python3 docs/howto/read_events.py "$out/ohc_75"
      figures=() ;;
    *)
      echo "run_tutorial: unknown tutorial '$name' (${ALL[*]})" >&2
      exit 2 ;;
  esac
  local f
  for f in "${figures[@]}"; do
    [[ -s "$out/$f" ]] || { echo "run_tutorial: $name did not make $out/$f" >&2; exit 1; }
  done
}

if [[ "${1:-}" == "all" ]]; then
  for n in "${ALL[@]}"; do run_one "$n"; done
else
  run_one "${1:?usage: run_tutorial.sh NAME|all}"
fi
