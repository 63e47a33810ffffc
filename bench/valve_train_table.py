#!/usr/bin/env python3
"""The valve-train examples' table of docs/guide/valve_trains.md, from the current build.

    python3 bench/valve_train_table.py [--bin build/camdyn] [--out FILE.md]

One revolution at 25 rev/s, rtol 1e-8, of examples/ohc_bucket_tappet.toml and
examples/ohv_pushrod_train.toml with Lee (arkode-erk, arkode-dirk), the event method
(arkode-erk, cvode-bdf) and penalty (k_p 2e9, arkode-erk): steps, rejected steps, impacts,
CPU (Summary::cpu_seconds, one run), Newton iterations of the implicit engines and the
energy residual. Writes Markdown to --out (default: stdout).
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile

from markdown_out import write_markdown

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLES = [("OHC", "examples/ohc_bucket_tappet.toml"), ("OHV", "examples/ohv_pushrod_train.toml")]
RUNS = [("Lee / arkode-erk", {"contact.model": "lee", "solver.integrator": "arkode-erk"}),
        ("Lee / arkode-dirk", {"contact.model": "lee", "solver.integrator": "arkode-dirk"}),
        ("event / arkode-erk", {"contact.model": "event", "solver.integrator": "arkode-erk"}),
        ("event / cvode-bdf", {"contact.model": "event", "solver.integrator": "cvode-bdf"}),
        ("penalty (k_p 2e9) / arkode-erk", {"contact.model": "penalty", "solver.integrator": "arkode-erk",
                                            "contact.penalty_stiffness": 2e9})]
COMMON = {"cam.speed_rev_s": 25.0, "run.t_end": 0.04, "solver.rtol": 1e-8}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "camdyn"))
    ap.add_argument("--out", default=None)
    a = ap.parse_args(argv)
    lines = ["| example | method / engine | steps | rejected | impacts | CPU s | Newton iterations | energy residual [J] |",
             "|---|---|---|---|---|---|---|---|"]
    with tempfile.TemporaryDirectory() as tmp:
        for name, scene in EXAMPLES:
            for label, sets in RUNS:
                cmd = [a.bin, "run", os.path.join(ROOT, scene), "-q", "--out", tmp]
                for k, v in dict(COMMON, **sets).items():
                    cmd += ["--set", f"{k}={v}"]
                r = subprocess.run(cmd, capture_output=True, text=True)
                with open(os.path.join(tmp, "summary.json")) as f:
                    s = json.load(f)
                with open(os.path.join(tmp, "events.csv"), newline="") as f:
                    impacts = sum(1 for e in csv.DictReader(f) if e["kind"] == "impact")
                fin = "" if s["finished"] else f" (not finished: {s['message'][:60]})"
                nni = s.get("nonlin_iters", 0)
                lines.append(f"| {name} | {label}{fin} | {s['steps']:,} | {s['rejected_steps']:,} | {impacts} | "
                             f"{s['cpu_seconds']:.2g} | {nni:,} | {s['energy_residual']:.2g} |")
                if r.returncode not in (0, 1):
                    print(f"valve_train_table: {' '.join(cmd)}: exit {r.returncode}: {r.stderr.strip()}", file=sys.stderr)
                    return 2
    text = ("Measured: one revolution at 25 rev/s, rtol 1e-8 (`python3 bench/valve_train_table.py`, single "
            "runs, CPU of the run itself).\n\n" + "\n".join(lines) + "\n")
    write_markdown(text, a.out, orphan=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
