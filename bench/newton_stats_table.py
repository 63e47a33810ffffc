#!/usr/bin/env python3
"""The stiff bar's penalty run on cvode-bdf: do its steps follow the error test, or Newton?

    python3 bench/newton_stats_table.py [--bin build/camdyn] [--out FILE.md] [--t-end 0.005]

Runs examples/stiff_bar.toml with the penalty method (k_p 1e7, c_p 632: the cheapest penalty
row of the old docs table), cvode-bdf, at rtol 1e-3 … 1e-6, and tabulates summary.json's
steps, Newton iterations (nonlin_iters), Newton convergence failures (nonlin_conv_fails),
error-test failures (err_test_fails), Newton-matrix factorisations (lin_setups) and CPU.

Reading: CVODE picks each step size from its error estimate and cuts it only after a
Newton convergence failure or an error-test failure. With no Newton convergence failure and
few error-test failures, every step is the size the error test asked for: the steps are
what the error test needs (ratio 1, the check is "within 2×"). Independently, BDF2's error
test makes the steps scale as rtol^(−1/3): 1000× looser rtol, 10× fewer steps; the table
gives the measured ratio.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

from markdown_out import write_markdown

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "examples", "stiff_bar.toml")
SETS = {"contact.model": "penalty", "contact.penalty_stiffness": 1e7, "contact.penalty_damping": 632,
        "solver.integrator": "cvode-bdf"}


def run(binary, rtol, t_end, tmp):
    cmd = [binary, "run", SCENE, "-q", "--out", tmp]  # the rows' command, shown with DIR and R
    for k, v in dict(SETS, **{"solver.rtol": rtol, "run.t_end": t_end}).items():
        cmd += ["--set", f"{k}={v}"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode not in (0, 1):
        raise SystemExit(f"newton_stats_table: {' '.join(cmd)}: exit {r.returncode}: {r.stderr.strip()}")
    with open(os.path.join(tmp, "summary.json")) as f:
        summary = json.load(f)
    shown = ["DIR" if c == tmp else "solver.rtol=R" if c.startswith("solver.rtol=") else c for c in cmd[1:]]
    return summary, " ".join(shown).replace(ROOT + "/", "")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "camdyn"))
    ap.add_argument("--out", default=None)
    ap.add_argument("--t-end", type=float, default=0.005)
    ap.add_argument("--rtols", default="1e-3,1e-4,1e-5,1e-6")
    a = ap.parse_args(argv)
    rtols = [float(x) for x in a.rtols.split(",")]
    rows, cmd = [], ""
    with tempfile.TemporaryDirectory() as tmp:
        for rtol in rtols:
            s, cmd = run(a.bin, rtol, a.t_end, tmp)
            if "nonlin_iters" not in s:
                raise SystemExit("newton_stats_table: summary.json has no nonlin_iters (a build before the Newton statistics)")
            rows.append((rtol, s))
    out = [f"Measured: `camdyn {cmd}` with rtol R in {', '.join(f'{r:g}' for r in rtols)} "
           "(`python3 bench/newton_stats_table.py`; single runs, CPU of the run itself).", "",
           "| rtol | finished | steps | steps per simulated s | Newton iterations | per step | Newton conv. failures | "
           "error-test failures | factorisations | CPU s |",
           "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for rtol, s in rows:
        n = max(s["steps"], 1)
        out.append(f"| {rtol:g} | {'yes' if s['finished'] else 'no'} | {s['steps']:,} | {s['steps'] / s['t_end']:.3g} | "
                   f"{s['nonlin_iters']:,} | {s['nonlin_iters'] / n:.3g} | {s['nonlin_conv_fails']:,} | "
                   f"{s['err_test_fails']:,} | {s['lin_setups']:,} | {s['cpu_seconds']:.3g} |")
    out.append("")
    loose, tight = rows[0], rows[-1]
    ratio = tight[1]["steps"] / max(loose[1]["steps"], 1)
    expect = (loose[0] / tight[0]) ** (1.0 / 3.0)
    ncf = sum(s["nonlin_conv_fails"] for _, s in rows)
    netf = sum(s["err_test_fails"] for _, s in rows)
    steps = sum(s["steps"] for _, s in rows)
    out.append(f"Steps at rtol {tight[0]:g} over steps at {loose[0]:g}: {ratio:.3g} (BDF2's error test: "
               f"({loose[0] / tight[0]:g})^(1/3) = {expect:.3g}). Newton convergence failures in all runs: {ncf}; "
               f"error-test failures: {netf} in {steps:,} steps. "
               + ("No step was cut by Newton: the step counts are what the error test needs (within 2×: met)."
                  if ncf == 0 and netf <= 0.05 * steps and 0.5 * expect <= ratio <= 2 * expect else
                  "Some steps were cut by Newton or the step count does not follow BDF2's error test: "
                  "the check (steps within 2× of the error test's need) is NOT met."))
    text = "\n".join(out) + "\n"
    write_markdown(text, a.out, orphan=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
