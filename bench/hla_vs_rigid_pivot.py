#!/usr/bin/env python3
"""examples/ohc_finger_hla.toml against the same train on a rigid pivot, side by side.

The rigid-pivot train is the example without the HLA: the plunger node and the HLA element
removed, the finger a two-node lever [roller, tip] (fixed pivot, the same ratio) and the
HLA's plunger spring (2000 N/m, 10 N) moved onto the roller to keep the finger on the cam. Each case
runs `camdyn run SCENE --quiet --set solver.integrator=E --set contact.model=M` in the
order HLA, rigid, HLA, rigid, … (interleaved: the machine is shared); the table gives the
best CPU seconds (summary.json `cpu_seconds`) of the repeats, the steps and the ratio.

  python3 bench/hla_vs_rigid_pivot.py [--camdyn build/camdyn] [--repeats 3]
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def rigid_pivot(text):
    blocks = re.split(r"(?m)^(?=\[\[)", text)
    out = []
    for b in blocks:
        if b.startswith("[[nodes]]") and 'name = "plunger"' in b:
            continue
        if b.startswith("[[elements]]") and 'name = "hla"' in b:
            continue
        if b.startswith("[[elements]]") and 'name = "finger"' in b:
            b = b.replace('nodes = ["roller", "tip", "plunger"]', 'nodes = ["roller", "tip"]')
            # the HLA's plunger spring, now on the roller: it keeps the finger on the cam
            b += ('[[elements]]\nname = "finger_spring"\ntype = "spring"\nnodes = ["roller", "ground"]\n'
                  'stiffness = 2000.0\npreload = 10.0\n\n')
        out.append(b)
    t = "".join(out).replace("element_forces = true", "element_forces = false")
    return t.replace('title = "OHC roller finger follower on a hydraulic lash adjuster"',
                     'title = "OHC roller finger follower on a rigid pivot"')


def run(camdyn, scene, out, integ, model):
    cmd = [camdyn, "run", scene, "--quiet", "--out", out, "--set", f"solver.integrator={integ}",
           "--set", f"contact.model={model}"]
    p = subprocess.run(cmd, capture_output=True, text=True)
    try:
        with open(os.path.join(out, "summary.json")) as f:
            s = json.load(f)
    except OSError:
        s = {}
    return p.returncode, s


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--camdyn", default=os.path.join(ROOT, "build", "camdyn"))
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--cases", default="cvode-bdf:lee,cvode-bdf:event,arkode-dirk:lee,arkode-dirk:event,"
                                       "arkode-erk:lee,arkode-erk:event")
    a = ap.parse_args()
    ex = os.path.join(ROOT, "examples", "ohc_finger_hla.toml")
    tmp = tempfile.mkdtemp(prefix="hla_bench_")
    rigid = os.path.join(tmp, "rigid.toml")
    with open(ex) as f, open(rigid, "w") as g:
        g.write(rigid_pivot(f.read()))
    print("| engine | method | HLA cpu s | HLA steps | rigid cpu s | rigid steps | HLA/rigid | contract (HLA, rigid) |")
    print("|---|---|---|---|---|---|---|---|")
    for case in a.cases.split(","):
        integ, model = case.split(":")
        best = {"hla": None, "rigid": None}
        info = {}
        for r in range(a.repeats):
            for name, scene in (("hla", ex), ("rigid", rigid)):
                out = os.path.join(tmp, f"{name}_{integ}_{model}_{r}")
                rc, s = run(a.camdyn, scene, out, integ, model)
                cpu = s.get("cpu_seconds") if rc == 0 else None
                if cpu is not None and (best[name] is None or cpu < best[name]):
                    best[name] = cpu
                info[name] = (s.get("steps"), rc, s.get("contract", {}).get("held"))
        f = lambda x: "failed" if x is None else f"{x:.4f}"
        ratio = f"{best['hla'] / best['rigid']:.2f}" if best["hla"] and best["rigid"] else "—"
        print(f"| {integ} | {model} | {f(best['hla'])} | {info['hla'][0]} | {f(best['rigid'])} | "
              f"{info['rigid'][0]} | {ratio} | exit {info['hla'][1]} held {info['hla'][2]}, "
              f"exit {info['rigid'][1]} held {info['rigid'][2]} |")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
