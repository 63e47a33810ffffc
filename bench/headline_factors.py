#!/usr/bin/env python3
"""Why each headline ratio is what it is: the two runs' work, from the generated rows.

For every docs/bench/generated/wp_<case>/work_precision.csv, takes the runs the headline
compares — the cheapest finished Lee run and the cheapest finished penalty (and event) run
whose err_force is at most the target (1e-3), the rule of camdyn bench's headlines — and
writes their steps, right-hand-side evaluations, Newton iterations, Newton-matrix setups,
CPU and CPU per step, and splits the CPU ratio into the two factors

    CPU(other)/CPU(Lee) = [steps(other)/steps(Lee)] x [CPU per step(other)/CPU per step(Lee)].

The ratio is checked against the case's headlines.csv (it must be the same pair of runs).

usage: bench/headline_factors.py --dir docs/bench/generated [--out FILE] [--target 1e-3]
"""
import argparse
import csv
import math
import os
import sys

from markdown_out import write_markdown

CASES = ["A", "A7", "B1", "B2", "stiff", "ohc", "ohv", "B1_1000"]


def num(x):
    try:
        return float(x)
    except (TypeError, ValueError):
        return math.nan


def cheapest(rows, method, target):
    best = None
    for r in rows:
        if r["method"] != method or r["finished"] != "1":
            continue
        if not (num(r["err_force"]) <= target):
            continue
        if best is None or num(r["cpu_seconds"]) < num(best["cpu_seconds"]):
            best = r
    return best


def settings(r):
    s = f"{r['method']} {r['engine']}"
    if r["method"] == "lee":
        s += f" tol_u {num(r['tol']):.3g}"
    elif r["method"] == "penalty":
        s += f" {r['variant']} k_p {num(r['kp']):.3g} c_p {num(r['cp']):.3g} rtol {num(r['tol']):.3g}"
    else:
        s += f" rtol {num(r['tol']):.3g}"
    return s


def work(r):
    steps = max(1, int(r["steps"]))
    cpu = num(r["cpu_seconds"])
    rhs = int(r["rhs_evals"])
    nni = int(r.get("nonlin_iters") or 0)
    return {
        "steps": steps, "rhs": rhs, "rhs_per_step": rhs / steps, "nni": nni,
        "nni_per_step": nni / steps, "setups": int(r.get("lin_setups") or 0),
        "rejected": int(r.get("rejected_steps") or 0), "cpu": cpu, "us_per_step": 1e6 * cpu / steps,
        "us_per_rhs": 1e6 * cpu / max(1, rhs), "err": num(r["err_force"]),
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dir", required=True)
    ap.add_argument("--out", default="-")
    ap.add_argument("--target", type=float, default=1e-3)
    a = ap.parse_args()
    out = ["# What the headline ratios are made of", "",
           "The runs each headline compares (the cheapest of each method at err_force ≤ "
           f"{a.target:g}, from `wp_<case>/work_precision.csv`), their work, and the CPU ratio split "
           "into the step ratio and the CPU-per-step ratio (their product). CPU: "
           "`Summary::cpu_seconds` of the bench run (one machine, shared: compare within a row). "
           "Newton iterations and setups are the implicit engines' counters (0 on arkode-erk; "
           "Lee's located step on arkode-erk iterates its force shape inside the step, which "
           "the right-hand-side count carries).", ""]
    found = False
    for c in CASES:
        p = os.path.join(a.dir, f"wp_{c}", "work_precision.csv")
        if not os.path.exists(p):
            continue
        with open(p, newline="") as f:
            rows = list(csv.DictReader(f))
        heads = {}
        hp = os.path.join(a.dir, f"wp_{c}", "headlines.csv")
        if os.path.exists(hp):
            with open(hp, newline="") as f:
                heads = {r["versus"]: num(r["ratio"]) for r in csv.DictReader(f)}
        lee = cheapest(rows, "lee", a.target)
        for versus in ("penalty", "event"):
            other = cheapest(rows, versus, a.target)
            if lee is None or other is None:
                out += [f"## {c}: Lee against {versus}", "",
                        f"No {'Lee' if lee is None else versus} run reaches err_force ≤ {a.target:g}.", ""]
                continue
            found = True
            wl, wo = work(lee), work(other)
            ratio = wo["cpu"] / wl["cpu"]
            step_ratio = wo["steps"] / wl["steps"]
            per_step = wo["us_per_step"] / wl["us_per_step"]
            check = heads.get(versus, math.nan)
            same = math.isfinite(check) and abs(check - ratio) <= 1e-6 * max(1.0, ratio)
            out += [f"## {c}: Lee against {versus}", "",
                    "| run | settings | err_force | CPU s | steps | rejected | rhs | rhs/step | Newton it. | "
                    "Newton it./step | setups | µs per step | µs per rhs |",
                    "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
            for name, r, w in (("Lee", lee, wl), (versus, other, wo)):
                out.append(f"| {name} | {settings(r)} | {w['err']:.3g} | {w['cpu']:.4g} | {w['steps']:,} | "
                           f"{w['rejected']:,} | {w['rhs']:,} | {w['rhs_per_step']:.2f} | {w['nni']:,} | "
                           f"{w['nni_per_step']:.2f} | {w['setups']:,} | {w['us_per_step']:.3g} | "
                           f"{w['us_per_rhs']:.3g} |")
            fewer = (f"{step_ratio:.3g}× fewer steps than {versus}" if step_ratio >= 1
                     else f"{1 / step_ratio:.3g}× more steps than {versus}")
            out += ["",
                    f"CPU ratio {ratio:.3g} = steps {step_ratio:.3g}× × CPU per step {per_step:.3g}×: "
                    f"Lee takes {fewer}, and a Lee step costs {1 / per_step:.3g}× one {versus} step. "
                    + (f"(headlines.csv: {check:.3g}, the same pair of runs.)" if same else
                       f"(headlines.csv says {check:.3g}: **not the same pair of runs**.)"), ""]
    if not found:
        sys.exit(f"headline_factors.py: no wp_<case>/work_precision.csv with both runs under {a.dir}")
    text = "\n".join(out) + "\n"
    write_markdown(text, a.out)


if __name__ == "__main__":
    main()
