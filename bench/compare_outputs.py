#!/usr/bin/env python3
"""Do two camdyn binaries give the same results? summary.json (every field but cpu_seconds,
wall_seconds, rhs_evals), history.csv and events.csv compared byte for byte on issue 34's
rows (A, A7, B1, B2 to 0.1 s, ohc_bucket_tappet, ohv_pushrod_train, ohc_finger_criteria).

Usage:
  python3 bench/compare_outputs.py OLD_BIN NEW_BIN [MODELS [ENGINES [ROWS]]]
    MODELS  comma-separated contact.model values (default event,penalty)
    ENGINES comma-separated solver.integrator values (default the three ODE engines)
    ROWS    comma-separated row names (default all)
Prints one line per run and the number of runs that differ."""
import filecmp, json, os, subprocess, sys, tempfile
EX = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples")
old, new = sys.argv[1], sys.argv[2]
models = sys.argv[3].split(",") if len(sys.argv) > 3 else ["event", "penalty"]
engines = sys.argv[4].split(",") if len(sys.argv) > 4 else ["arkode-erk", "arkode-dirk", "cvode-bdf"]
rows = [("A", "case_A.toml", ["run.t_end=0.1"]), ("A7", "case_A7.toml", ["run.t_end=0.1"]),
        ("B1", "case_B1.toml", ["run.t_end=0.1"]), ("B2", "case_B2.toml", ["run.t_end=0.1"]),
        ("OHC", "ohc_bucket_tappet.toml", []), ("OHV", "ohv_pushrod_train.toml", []),
        ("finger", "ohc_finger_criteria.toml", [])]
if len(sys.argv) > 5: rows = [r for r in rows if r[0] in sys.argv[5].split(",")]
TMP = tempfile.mkdtemp(prefix="camdyn_cmp_")
SKIP = {"cpu_seconds", "wall_seconds", "rhs_evals"}
def strip(d):
    if isinstance(d, dict): return {k: strip(v) for k, v in d.items() if k not in SKIP}
    if isinstance(d, list): return [strip(v) for v in d]
    return d
def diff(a, b, path=""):
    out = []
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b)):
            if a.get(k) != b.get(k): out += diff(a.get(k), b.get(k), path + "." + k)
    elif isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        for i, (x, y) in enumerate(zip(a, b)):
            if x != y: out += diff(x, y, path + f"[{i}]")
    else: out.append(f"{path}: {a} vs {b}")
    return out
bad = 0
for name, scene, sets in rows:
    for m in models:
        for e in engines:
            outs = []
            for tag, b in (("o", old), ("n", new)):
                d = os.path.join(TMP, tag)
                cmd = [b, "run", os.path.join(EX, scene), "--out", d, "--quiet", "--set", f"contact.model={m}",
                       "--set", f"solver.integrator={e}"]
                for s in sets: cmd += ["--set", s]
                r = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
                outs.append((d, r.returncode))
            (do, ro), (dn, rn) = outs
            so = json.load(open(do + "/summary.json")); sn = json.load(open(dn + "/summary.json"))
            dd = diff(strip(so), strip(sn))
            h = filecmp.cmp(do + "/history.csv", dn + "/history.csv", shallow=False)
            ev = (not os.path.exists(do + "/events.csv")) or filecmp.cmp(do + "/events.csv", dn + "/events.csv", shallow=False)
            ok = not dd and h and ev and ro == rn
            bad += not ok
            print(f"{name:7s} {m:8s} {e:12s} rc {ro}/{rn} summary {'same' if not dd else 'DIFF'} history {'same' if h else 'DIFF'} events {'same' if ev else 'DIFF'} rhs {so.get('rhs_evals')} -> {sn.get('rhs_evals')}", flush=True)
            for x in dd[:6]: print("     ", x)
print("mismatching rows:", bad)
