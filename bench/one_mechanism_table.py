#!/usr/bin/env python3
"""Before/after table of issue 23 ("one mechanism"), measured side by side in one run.

Each row runs the same scene with the same method and engine through two configurations,
interleaved (before, after, before, after, …) so that the machine's load falls on both
alike, and keeps the best CPU time of each:

  before = --before-bin: an older camdyn CLI (e.g. one built at 8adb79a, where single
           followers still ran on the single-follower stack — FollowerModel,
           src/legacy/engines.cpp, lee_located.cpp / lee_multistep.cpp — deleted since),
  after  = --bin (every scene on the mechanism);
  rows: A, A7, B1, B2, the stiff bar, B1 with 1000 elements, OHC and OHV one revolution.

Usage:
  python3 bench/one_mechanism_table.py --bin build/camdyn --before-bin OLD/camdyn
      [--reps 3] [--engines arkode-erk,arkode-dirk,cvode-bdf] [--rows A,A7,...] > table.md
Prints a Markdown table: CPU s before / after, ratio after/before, steps, events, and
whether the two runs agree (same number of impacts and separations; event times within
1e-6 s). A row whose "after" is more than 10 % slower is marked.
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
EX = os.path.join(HERE, "..", "examples")

# name, scene, overrides, single follower (unused: every row compares the two binaries)
ROWS = [
    ("A", "case_A.toml", ["run.t_end=0.1"], True),
    ("A7", "case_A7.toml", ["run.t_end=0.1"], True),
    ("B1", "case_B1.toml", ["run.t_end=0.1"], True),
    ("B2", "case_B2.toml", ["run.t_end=0.1"], True),
    ("stiff bar (0.01 s)", "stiff_bar.toml", ["run.t_end=0.01"], True),
    ("B1, 1000 elements (0.01 s)", "case_B1.toml", ["follower.elements=1000", "run.t_end=0.01"], True),
    ("OHC one rev", "ohc_bucket_tappet.toml", [], False),
    ("OHV one rev", "ohv_pushrod_train.toml", [], False),
]


def run(binary, scene, sets, out):
    cmd = [binary, "run", os.path.join(EX, scene), "--out", out]
    for s in sets:
        cmd += ["--set", s]
    p = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, timeout=900)
    with open(os.path.join(out, "summary.json")) as f:
        d = json.load(f)
    ev = []
    path = os.path.join(out, "events.csv")
    if os.path.exists(path):
        with open(path) as f:
            ev = [(float(r["t"]), r["kind"]) for r in csv.DictReader(f)]
    return d, ev


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", required=True)
    ap.add_argument("--before-bin", required=True)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--engines", default="arkode-erk,arkode-dirk,cvode-bdf")
    ap.add_argument("--method", default="lee")
    ap.add_argument("--rows", default=None)
    a = ap.parse_args()
    want = None if a.rows is None else set(a.rows.split(","))
    print("| scene | engine | CPU s before | CPU s after | after/before | steps before | steps after | events (imp/sep) | agree |")
    print("|---|---|---:|---:|---:|---:|---:|---|---|")
    tmp = tempfile.mkdtemp(prefix="one_mech_")
    for name, scene, sets, single in ROWS:
        if want is not None and name.split(" ")[0] not in want:
            continue
        for eng in a.engines.split(","):
            base = sets + [f"solver.integrator={eng}", f"contact.model={a.method}"]
            cfg = [(a.before_bin, base), (a.bin, base)]
            best = [None, None]
            for _ in range(a.reps):
                for k, (b, s) in enumerate(cfg):
                    try:
                        d, ev = run(b, scene, s, os.path.join(tmp, str(k)))
                    except Exception as e:  # a timeout or a missing summary
                        d, ev = {"finished": False, "cpu_seconds": float("nan"), "steps": 0, "message": str(e)}, []
                    if best[k] is None or d["cpu_seconds"] < best[k][0]["cpu_seconds"]:
                        best[k] = (d, ev)
            (d0, e0), (d1, e1) = best
            ok0, ok1 = d0.get("finished"), d1.get("finished")
            agree = "—"
            if ok0 and ok1:
                same = len(e0) == len(e1) and all(k0 == k1 and abs(t0 - t1) <= 1e-6 for (t0, k0), (t1, k1) in zip(e0, e1))
                agree = "yes" if same else f"no ({len(e0)} vs {len(e1)} events)"
            c0, c1 = d0["cpu_seconds"], d1["cpu_seconds"]
            ratio = c1 / c0 if ok0 and ok1 and c0 > 0 else float("nan")
            mark = " **slower**" if ratio > 1.10 else ""
            cpu0 = f"{c0:.3g}" if ok0 else f"failed: {d0.get('message', '')[:60]}"
            cpu1 = f"{c1:.3g}" if ok1 else f"failed: {d1.get('message', '')[:60]}"
            ev = f"{d1.get('impacts', 0)}/{d1.get('separations', 0)}"
            print(f"| {name} | {eng} | {cpu0} | {cpu1} | {ratio:.2f}{mark} | {d0.get('steps', 0)} | {d1.get('steps', 0)} | {ev} | {agree} |", flush=True)


if __name__ == "__main__":
    sys.exit(main())
