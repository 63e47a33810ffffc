#!/usr/bin/env python3
"""Lee's classic step against the located step, measured side by side (issue 34 item 1).

For each case the classic step (`contact.lee_step = "classic"`) and the located step (the
default) run interleaved (classic, located, classic, located, ...), best CPU of --reps kept;
each is compared with the event-driven method at rtol 1e-10 (same scene, same output grid):
max |u_c − u_ref|, max |v_c − v_ref| and max |F − F_ref| / max |F_ref| over the output
rows (an impact's impulse is not a row: the force error near an impact is the classic
step's force spike against the reference's zero). Needs a camdyn CLI that still
has the classic step (built before its retirement, e.g. main at 1e02bdb).

Usage: python3 bench/classic_vs_located.py --bin OLD/camdyn [--reps 3] [--engine arkode-erk]
"""
import argparse, csv, json, os, subprocess, sys, tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
EX = os.path.join(HERE, "..", "examples")
CASES = [("A", "case_A.toml", ["run.t_end=1.0"]),
         ("A7", "case_A7.toml", ["run.t_end=1.0"]),
         ("B1", "case_B1.toml", ["run.t_end=0.2"])]


def run(b, scene, sets, out):
    cmd = [b, "run", os.path.join(EX, scene), "--out", out]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=1800)
    with open(os.path.join(out, "summary.json")) as f:
        d = json.load(f)
    with open(os.path.join(out, "history.csv")) as f:
        rows = {round(float(r["t"]), 9): (float(r["u_c"]), float(r["v_c"]), float(r["contact_force"])) for r in csv.DictReader(f)}
    return d, rows


def err(rows, ref):
    eu = ev = ef = 0.0
    fmax = max(abs(r[2]) for r in ref.values())
    for t, (u, v, F) in rows.items():
        if t in ref:
            eu = max(eu, abs(u - ref[t][0]))
            ev = max(ev, abs(v - ref[t][1]))
            ef = max(ef, abs(F - ref[t][2]) / fmax)
    return eu, ev, ef


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", required=True)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--engine", default="arkode-erk")
    a = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="classic_")
    print("| case | step | CPU s (best of %d) | steps | rejected | impacts/separations | max abs u_c error | max abs v_c error | max force error / max force |" % a.reps)
    print("|---|---|---:|---:|---:|---|---:|---:|---:|")
    for name, scene, sets in CASES:
        base = sets + [f"solver.integrator={a.engine}"]
        _, ref = run(a.bin, scene, sets + [f"solver.integrator={a.engine}", "contact.model=event",
                                            "solver.rtol=1e-10", "solver.atol=1e-12"], os.path.join(tmp, "ref"))
        cfg = [("classic", base + ["contact.model=lee", "contact.lee_step=classic"]),
               ("located", base + ["contact.model=lee", "contact.lee_step=located"])]
        best = [None, None]
        for _ in range(a.reps):
            for k, (_, s) in enumerate(cfg):
                d, rows = run(a.bin, scene, s, os.path.join(tmp, str(k)))
                if best[k] is None or d["cpu_seconds"] < best[k][0]["cpu_seconds"]:
                    best[k] = (d, rows)
        for k, (label, _) in enumerate(cfg):
            d, rows = best[k]
            eu, ev, ef = err(rows, ref)
            fin = "" if d["finished"] else " (NOT finished: %s)" % d["message"]
            print(f"| {name} | {label} | {d['cpu_seconds']:.3g}{fin} | {d['steps']} | {d['rejected_steps']} | "
                  f"{d.get('impacts', 0)}/{d.get('separations', 0)} | {eu:.2g} | {ev:.2g} | {ef:.2g} |", flush=True)


if __name__ == "__main__":
    sys.exit(main())
