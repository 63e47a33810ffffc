#!/usr/bin/env python3
"""A valve train with a progressive valve spring against the same train with a linear one.

The two-mass OHC train (examples/ohc_bucket_tappet.toml without the valve spring's coil
masses: the valve spring 35 N/mm, 250 N preload, c = 2) and its twin whose valve spring is a
`progressive_spring` with a linear table (the same force law: the monotone interpolation
reproduces linear data), and a third with a truly progressive table (35 → 54 N/mm). Each
binary runs each scene interleaved (A B A B …, the machine's load falls on all alike); the
best CPU seconds (summary.json cpu_seconds) of --reps runs are kept.

Usage:
  python3 bench/progressive_vs_linear.py --bin build/camdyn [--before-bin OLD/camdyn]
      [--reps 5] [--engines arkode-erk,arkode-dirk] [--method lee]
Prints a Markdown table: CPU s, steps and rhs evaluations per scene, and progressive/linear.
"""
import argparse
import json
import os
import subprocess
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLE = os.path.join(HERE, "..", "examples", "ohc_bucket_tappet.toml")
LINEAR_SPRING = '''name = "valve_spring"
type = "spring"
nodes = ["valve", "ground"]
stiffness = 35000.0                     # N/m = 35 N/mm
preload = 250.0                         # N, installed load
damping = 2.0
'''
TABLE = '''name = "valve_spring"
type = "progressive_spring"
nodes = ["valve", "ground"]
deflections = [0, 0.005, 0.010, 0.015, 0.020, 0.025]
forces = {forces}
installed_deflection = 0.0071428571428571435
damping = 2.0
'''


def scenes(tmp):
    src = open(EXAMPLE).read()
    lin = src.replace('mass = 0.030                            # kg of coil: surge ½√(k/m_s) = 540 Hz\nmasses = 6\n', '')
    assert lin != src and LINEAR_SPRING in lin, "examples/ohc_bucket_tappet.toml changed: update this script"
    out = {"linear": lin,
           "progressive, linear table": lin.replace(LINEAR_SPRING, TABLE.format(forces="[0, 175, 350, 525, 700, 875]")),
           "progressive, 35 → 54 N/mm": lin.replace(LINEAR_SPRING, TABLE.format(forces="[0, 175, 360, 570, 810, 1080]"))}
    paths = {}
    for k, text in out.items():
        p = os.path.join(tmp, k.split(",")[0] + str(len(paths)) + ".toml")
        open(p, "w").write(text)
        paths[k] = p
    return paths


def run(binary, scene, engine, method, out):
    subprocess.run([binary, "run", scene, "--out", out, "--quiet", "--set", f"solver.integrator={engine}",
                    "--set", f"contact.model={method}"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", required=True)
    ap.add_argument("--before-bin")
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--engines", default="arkode-erk,arkode-dirk")
    ap.add_argument("--method", default="lee")
    a = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="prog_lin_")
    paths = scenes(tmp)
    bins = [("after", a.bin)] + ([("before", a.before_bin)] if a.before_bin else [])
    print("| binary | engine | scene | CPU s | steps | rhs evals | CPU / linear |")
    print("|---|---|---|---:|---:|---:|---:|")
    for eng in a.engines.split(","):
        best = {}
        for _ in range(a.reps):
            for bname, b in bins:
                for sname, p in paths.items():
                    d = run(b, p, eng, a.method, os.path.join(tmp, "out"))
                    k = (bname, sname)
                    if d.get("finished") and (k not in best or d["cpu_seconds"] < best[k]["cpu_seconds"]):
                        best[k] = d
        for bname, _ in bins:
            lin = best.get((bname, "linear"))
            for sname in paths:
                d = best.get((bname, sname))
                if d is None:
                    print(f"| {bname} | {eng} | {sname} | failed | | | |")
                    continue
                ratio = d["cpu_seconds"] / lin["cpu_seconds"] if lin else float("nan")
                print(f"| {bname} | {eng} | {sname} | {d['cpu_seconds']:.4g} | {d['steps']} | {d['rhs_evals']} | {ratio:.2f} |",
                      flush=True)


if __name__ == "__main__":
    main()
