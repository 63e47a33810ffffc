#!/usr/bin/env python3
"""Peers side by side: the same scenes on camdyn, Siconos and MuJoCo, one work–precision table.

    /usr/bin/python3 bench/peers/peers.py [--camdyn build/camdyn] [--out docs/bench/generated/peers]
                                          [--quick] [--scenes two_mass,A]

Scenes (both against camdyn's event-driven method at rtol 1e-11, exact to that tolerance):
  two_mass  bench/peers/two_mass_valve.toml: harmonic cam, tappet, elastic stem, valve,
            valve spring, seat with Newton restitution 0.3 (the valve bounces on closing).
  A         METHOD.md case A (examples/case_A.toml): the paper's cam, rigid follower, 1 s.
Methods: camdyn's Lee and event methods (and penalty on case A) at several tolerances;
Siconos 4.4 Moreau–Jean (θ = 0.5, LCP; Debian python3-siconos) and MuJoCo 2.2 (Euler,
soft contacts; Debian libmujoco-dev, through bench/peers/mujoco_peer.cpp) at several step
sizes. The peer models are in bench/peers/peer_models.py (the cam lift's frame).

Writes OUT/peers.csv (one row per run), OUT/peers.md (the table, stamped with the commit
and date) and OUT/peers_<scene>.png (CPU against error, every method). A peer that is not
installed is skipped with one line saying so; the setup does not need them:
    scripts/setup.sh --peers        (apt-get install python3-siconos libmujoco-dev)
Run with Debian's Python (/usr/bin/python3): python3-siconos installs there.

CPU: camdyn's Summary::cpu_seconds (the run, no process start), Siconos' stepping loop
(time.process_time, with the Python loop that sets the cam's force each step), MuJoCo's
stepping loop (std::clock in the driver). Best of --repeats. Errors (the same code for all):
  two_mass: err_u   max |u_valve − ref| / max u_valve on the reference's 1e-5 s grid;
            t_imp, v_imp: first seat impact's time error [s] and relative speed error;
            n_imp: seat impacts faster than 5 % of the reference's first (ref: its count),
            spurious: such impacts while the valve should rest on its seat (t < opening).
  A:        err_F   max |F − F_ref| / max F_ref on the reference's 1e-3 s grid after t = 0;
            err_u alike on the lift.
"""
from __future__ import annotations

import argparse
import csv
import json
import math
import os
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import peer_models as pm  # noqa: E402

TWO_MASS_TOML = os.path.join(HERE, "two_mass_valve.toml")
CASE_A_TOML = os.path.join(ROOT, "examples", "case_A.toml")
REF_RTOL = 1e-11
IMPACT_FRACTION = 0.05


# --------------------------------------------------------------------------- camdyn runs
def camdyn_run(camdyn, scene, out_dir, sets, repeats=1):
    """Run camdyn (best CPU of `repeats`); returns (history, events, summary)."""
    best = None
    for _ in range(max(1, repeats)):
        cmd = [camdyn, "run", scene, "-q", "--out", out_dir]
        for k, v in sets.items():
            cmd += ["--set", f"{k}={v}"]
        subprocess.run(cmd, check=True)
        with open(os.path.join(out_dir, "summary.json")) as f:
            s = json.load(f)
        if best is None or s["cpu_seconds"] < best["cpu_seconds"]:
            best = s
    hist, ev = pm.read_history(out_dir)
    return hist, ev, best


def reference(camdyn, scene, work, sets):
    d = os.path.join(work, "reference")
    sets = dict(sets, **{"contact.model": "event", "solver.integrator": "arkode-erk",
                         "solver.rtol": REF_RTOL, "solver.atol": 1e-14})
    return camdyn_run(camdyn, scene, d, sets)


# --------------------------------------------------------------------------- metrics
def seat_impacts_camdyn(ev):
    return [(float(e["t"]), abs(float(e["impact_velocity"]))) for e in ev
            if e["kind"] == "impact" and e.get("contact", "seat") == "seat"]


def two_mass_metrics(ref, ref_imp, t_open, t, u_valve, impacts):
    grid = ref["t"]
    uv = np.interp(grid, t, u_valve)
    m = {"err_u": float(np.max(np.abs(uv - ref["u_valve"])) / np.max(ref["u_valve"]))}
    v_min = IMPACT_FRACTION * ref_imp[0][1]
    fast = [(a, b) for a, b in impacts if b >= v_min]
    closing = [(a, b) for a, b in fast if a > t_open]
    m["n_imp"] = len(closing)
    m["spurious"] = len(fast) - len(closing)
    if closing:
        m["t_imp"] = abs(closing[0][0] - ref_imp[0][0])
        m["v_imp"] = abs(closing[0][1] - ref_imp[0][1]) / ref_imp[0][1]
    else:
        m["t_imp"] = m["v_imp"] = math.nan
    m["sequence"] = " ".join(f"{b:.3g}" for _, b in closing[:6])
    return m


def case_a_metrics(ref, t, u, F):
    grid = ref["t"][1:]  # after t = 0 (a time-stepping run's force is a step's mean)
    Fi = np.interp(grid, t, F)
    ui = np.interp(grid, t, u - u[0])
    uref = ref["u_c"][1:] - ref["u_c"][0]  # the lift from the start (camdyn's u_c includes the base radius)
    Fref = ref["contact_force"][1:]
    return {"err_F": float(np.max(np.abs(Fi - Fref)) / np.max(np.abs(Fref))),
            "err_u": float(np.max(np.abs(ui - uref)) / np.max(np.abs(uref)))}


# --------------------------------------------------------------------------- one scene
def run_two_mass(args, work, rows, say):
    camdyn = args.camdyn
    p = pm.TwoMass.from_toml(TWO_MASS_TOML)
    base = {"run.output_dt": 1e-5}
    ref, ref_ev, ref_sum = reference(camdyn, TWO_MASS_TOML, work, base)
    ref_imp = seat_impacts_camdyn(ref_ev)
    t_open = min(float(e["t"]) for e in ref_ev if e["kind"] == "separation" and e["contact"] == "seat")
    v_min = IMPACT_FRACTION * ref_imp[0][1]
    ref_fast = [x for x in ref_imp if x[1] >= v_min]
    say(f"two_mass: reference event rtol {REF_RTOL:g}: {ref_sum['cpu_seconds']:.3g} s, seat opens at "
        f"{t_open:.6g} s, impacts ≥ {v_min:.3g} m/s: " + " ".join(f"{b:.3g}" for _, b in ref_fast))

    def add(method, setting, cpu, steps, m):
        r = {"scene": "two_mass", "method": method, "setting": setting, "cpu_s": cpu, "steps": steps,
             "n_imp_ref": len(ref_fast)}
        r.update(m)
        rows.append(r)
        say(f"  {method:8s} {setting:22s} cpu {cpu:9.4g} s  err_u {m['err_u']:.3g}  impacts {m['n_imp']} "
            f"(+{m['spurious']} spurious)  t_imp {m['t_imp']:.3g}  v_imp {m['v_imp']:.3g}")

    tols = [1e-4, 1e-6] if args.quick else [1e-4, 1e-6, 1e-8]
    for method in ("lee", "event"):
        for tol in tols:
            d = os.path.join(work, f"{method}_{tol:g}")
            h, ev, s = camdyn_run(camdyn, TWO_MASS_TOML, d, dict(base, **{"contact.model": method,
                                  "solver.integrator": "arkode-erk", "solver.rtol": tol}), args.repeats)
            if not s["finished"]:
                say(f"  camdyn {method} rtol {tol:g}: not finished ({s['message']})")
                continue
            add(f"camdyn {method}", f"arkode-erk rtol {tol:g}", s["cpu_seconds"], s["steps"],
                two_mass_metrics(ref, ref_imp, t_open, h["t"], h["u_valve"], seat_impacts_camdyn(ev)))

    lift = pm.Lift.from_camdyn(camdyn, TWO_MASS_TOML, None, os.path.join(work, "lift"),
                               2 * math.pi * 25.0)
    steps = [1e-4, 1e-5, 1e-6] if args.quick else [1e-4, 3e-5, 1e-5, 3e-6, 1e-6]
    if "siconos" in args.peers:
        why = pm.siconos_available()
        if why:
            say(f"  Siconos skipped: {why}")
        else:
            for h in steps:
                r = min((pm.siconos_two_mass(p, lift, h, min_speed=0.0) for _ in range(args.repeats)),
                        key=lambda x: x.cpu)
                add("Siconos", f"Moreau–Jean θ=0.5 h {h:g}", r.cpu, r.steps,
                    two_mass_metrics(ref, ref_imp, t_open, r.t, r.cols["u_valve"], r.impacts))
    if "mujoco" in args.peers:
        exe, why = pm.mujoco_driver(args.build)
        if why:
            say(f"  MuJoCo skipped: {why}")
        else:
            for h in steps:
                r = min((pm.mujoco_two_mass(exe, p, lift, h, os.path.join(work, "mujoco"), min_speed=0.0)
                         for _ in range(args.repeats)), key=lambda x: x.cpu)
                add("MuJoCo", f"Euler h {h:g} τ=5h", r.cpu, r.steps,
                    two_mass_metrics(ref, ref_imp, t_open, r.t, r.cols["u_valve"], r.impacts))
    return {"reference_cpu": ref_sum["cpu_seconds"], "impacts": ref_fast, "t_open": t_open}


def run_case_a(args, work, rows, say):
    camdyn = args.camdyn
    p = pm.CaseA()
    base = {"run.output_dt": 1e-3}
    ref, _, ref_sum = reference(camdyn, CASE_A_TOML, work, base)
    say(f"A: reference event rtol {REF_RTOL:g}: {ref_sum['cpu_seconds']:.3g} s")

    def add(method, setting, cpu, steps, m):
        r = {"scene": "A", "method": method, "setting": setting, "cpu_s": cpu, "steps": steps}
        r.update(m)
        rows.append(r)
        say(f"  {method:8s} {setting:28s} cpu {cpu:9.4g} s  err_F {m['err_F']:.3g}  err_u {m['err_u']:.3g}")

    tols = [1e-4, 1e-6] if args.quick else [1e-4, 1e-6, 1e-8]
    runs = [("lee", {"solver.integrator": "arkode-erk", "solver.rtol": t}, f"arkode-erk rtol {t:g}") for t in tols]
    runs += [("event", {"solver.integrator": "arkode-erk", "solver.rtol": t}, f"arkode-erk rtol {t:g}") for t in tols]
    runs += [("penalty", {"solver.integrator": "cvode-bdf", "solver.rtol": 1e-8, "contact.penalty_stiffness": kp,
                          "contact.penalty_damping": 2 * math.sqrt(kp)}, f"cvode-bdf k_p {kp:g} crit.")
             for kp in ([1e6, 1e8] if args.quick else [1e6, 1e7, 1e8])]
    for method, sets, setting in runs:
        d = os.path.join(work, f"{method}_{setting.replace(' ', '_')}")
        h, _, s = camdyn_run(camdyn, CASE_A_TOML, d, dict(base, **{"contact.model": method}, **sets), args.repeats)
        if not s["finished"]:
            say(f"  camdyn {method} {setting}: not finished ({s['message']})")
            continue
        add(f"camdyn {method}", setting, s["cpu_seconds"], s["steps"],
            case_a_metrics(ref, h["t"], h["u_c"], h["contact_force"]))

    lift = pm.Lift.from_camdyn(camdyn, None, "A", os.path.join(work, "lift"), 2 * math.pi * 1.75)
    steps = [1e-3, 1e-4, 1e-5] if args.quick else [1e-3, 3e-4, 1e-4, 3e-5, 1e-5]
    if "siconos" in args.peers:
        why = pm.siconos_available()
        if why:
            say(f"  Siconos skipped: {why}")
        else:
            for h in steps:
                r = min((pm.siconos_case_a(p, lift, h) for _ in range(args.repeats)), key=lambda x: x.cpu)
                add("Siconos", f"Moreau–Jean θ=0.5 h {h:g}", r.cpu, r.steps,
                    case_a_metrics(ref, r.t, r.cols["u_c"], r.cols["contact_force"]))
    if "mujoco" in args.peers:
        exe, why = pm.mujoco_driver(args.build)
        if why:
            say(f"  MuJoCo skipped: {why}")
        else:
            for h in steps:
                r = min((pm.mujoco_case_a(exe, p, lift, h, os.path.join(work, "mujoco")) for _ in range(args.repeats)),
                        key=lambda x: x.cpu)
                add("MuJoCo", f"Euler h {h:g} τ=2h", r.cpu, r.steps,
                    case_a_metrics(ref, r.t, r.cols["u_c"], r.cols["contact_force"]))
    return {"reference_cpu": ref_sum["cpu_seconds"]}


# --------------------------------------------------------------------------- output
def g3(x):
    if isinstance(x, str):
        return x
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "–"
    return f"{x:.3g}"


def cheapest(rows, scene, method, key, target):
    ok = [r for r in rows if r["scene"] == scene and r["method"] == method and r[key] <= target]
    return min(ok, key=lambda r: r["cpu_s"]) if ok else None


def write_outputs(out, rows, info, stamp, say):
    cols = ["scene", "method", "setting", "cpu_s", "steps", "err_u", "err_F", "t_imp", "v_imp", "n_imp",
            "n_imp_ref", "spurious", "sequence"]
    with open(os.path.join(out, "peers.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: r.get(k, "") for k in cols})
    md = ["---", "orphan: true", "---", "", f"<!-- {stamp} -->", "",
          "# Peers side by side: camdyn, Siconos, MuJoCo on the same scenes", "",
          stamp, "", "Regenerate: `/usr/bin/python3 bench/peers/peers.py` (install the peers with "
          "`scripts/setup.sh --peers`). Models and metrics: bench/peers/peers.py and peer_models.py. "
          "CPU seconds, best of the repeats; on a loaded machine compare ratios.", ""]
    md += [f"- {x}" for x in info.get("skipped", [])] + ([""] if info.get("skipped") else [])
    if any(r["scene"] == "two_mass" for r in rows):
        i = info["two_mass"]
        md += ["## Two-mass valve train (seat restitution 0.3)", "",
               f"Reference: camdyn event method, arkode-erk rtol {REF_RTOL:g}, {g3(i['reference_cpu'])} s; "
               f"the seat opens at {i['t_open']:.6g} s; seat impacts faster than {IMPACT_FRACTION:.0%} of the "
               f"first: " + ", ".join(f"{b:.3g} m/s at {a:.6f} s" for a, b in i["impacts"]) + ".", "",
               "| method | setting | cpu s | steps | err_u | t_imp s | v_imp | impacts (ref) | spurious | impact speeds m/s |",
               "|---|---|---|---|---|---|---|---|---|---|"]
        for r in rows:
            if r["scene"] == "two_mass":
                md.append(f"| {r['method']} | {r['setting']} | {g3(r['cpu_s'])} | {r['steps']} | {g3(r['err_u'])} | "
                          f"{g3(r['t_imp'])} | {g3(r['v_imp'])} | {r['n_imp']} ({r['n_imp_ref']}) | {r['spurious']} | "
                          f"{r['sequence']} |")
        md.append("")
        md += verdicts(rows, "two_mass", "err_u", [1e-2, 1e-3, 1e-4])
        md += ["![two-mass valve train: CPU against valve lift error](peers_two_mass.png)", ""]
    if any(r["scene"] == "A" for r in rows):
        md += ["## Case A (rigid follower, persistent contact)", "",
               f"Reference: camdyn event method, arkode-erk rtol {REF_RTOL:g}, {g3(info['A']['reference_cpu'])} s.", "",
               "| method | setting | cpu s | steps | err_F | err_u |", "|---|---|---|---|---|---|"]
        for r in rows:
            if r["scene"] == "A":
                md.append(f"| {r['method']} | {r['setting']} | {g3(r['cpu_s'])} | {r['steps']} | {g3(r['err_F'])} | "
                          f"{g3(r['err_u'])} |")
        md.append("")
        md += verdicts(rows, "A", "err_F", [1e-2, 1e-3, 1e-4])
        md += ["![case A: CPU against contact force error](peers_A.png)", ""]
    with open(os.path.join(out, "peers.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    plot(out, rows, say)


def verdicts(rows, scene, key, targets):
    methods = [m for m in ("camdyn lee", "camdyn event", "camdyn penalty", "Siconos", "MuJoCo")
               if m != "camdyn penalty" or any(r["scene"] == scene and r["method"] == m for r in rows)]
    out = [f"At equal accuracy ({key} ≤ target): the cheapest run of each" +
           (" (impacts: its seat impacts faster than 5 % of the first / the reference's; +N: spurious ones "
            "while the valve rests)" if scene == "two_mass" else "") + ".", "",
           "| target | " + " | ".join(methods) + " | best |", "|---|" + "---|" * len(methods) + "---|"]
    for t in targets:
        cells, best = [], None
        for m in methods:
            r = cheapest(rows, scene, m, key, t)
            seq = f", impacts {r['n_imp']}/{r['n_imp_ref']}" + (f" +{r['spurious']}" if r["spurious"] else "") \
                if r and scene == "two_mass" else ""
            cells.append(f"{g3(r['cpu_s'])} s ({r['setting']}{seq})" if r else "none")
            if r and (best is None or r["cpu_s"] < best["cpu_s"]):
                best = r
        out.append(f"| {t:g} | " + " | ".join(cells) + f" | {best['method'] if best else '–'} |")
    out.append("")
    return out


def plot(out, rows, say):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except Exception as ex:  # no matplotlib: the table only
        say(f"no figure: matplotlib ({ex})")
        return
    marks = {"camdyn lee": "o-", "camdyn event": "s-", "camdyn penalty": "^-", "Siconos": "D--", "MuJoCo": "v--"}
    for scene, key in (("two_mass", "err_u"), ("A", "err_F")):
        rs = [r for r in rows if r["scene"] == scene]
        if not rs:
            continue
        fig, ax = plt.subplots(figsize=(6.5, 4.5), constrained_layout=True)
        for m, style in marks.items():
            # in the order of cost (tolerance or step size), so a non-monotone error shows as such
            pts = sorted(((r[key], r["cpu_s"]) for r in rs if r["method"] == m and r[key] > 0), key=lambda p: p[1])
            if pts:
                ax.loglog([p[0] for p in pts], [max(p[1], 1e-5) for p in pts], style, label=m)
        ax.set_xlabel({"err_u": "valve lift error (max, relative)", "err_F": "contact force error (max, relative)"}[key])
        ax.set_ylabel("CPU [s]")
        exact = sorted({r["method"] for r in rs if r[key] == 0})
        if exact:
            ax.text(0.02, 0.02, "error 0 on the grid (not drawn): " + ", ".join(exact), transform=ax.transAxes, fontsize=7)
        ax.set_title(f"{scene}: work–precision, camdyn and its peers", fontsize=10)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
        fig.savefig(os.path.join(out, f"peers_{scene}.png"), dpi=110)
        plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--camdyn", default=os.path.join(ROOT, "build", "camdyn"), help="camdyn binary (default: %(default)s)")
    ap.add_argument("--build", default=None, help="build directory (MuJoCo driver; default: the camdyn binary's)")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "bench", "generated", "peers"),
                    help="output directory (default: %(default)s)")
    ap.add_argument("--scenes", default="two_mass,A", help="comma-separated: two_mass, A (default: %(default)s)")
    ap.add_argument("--peers", default="siconos,mujoco", help="comma-separated: siconos, mujoco (default: %(default)s)")
    ap.add_argument("--quick", action="store_true", help="fewer tolerances and step sizes")
    ap.add_argument("--repeats", type=int, default=3, help="timing repeats, best of (default: %(default)s)")
    args = ap.parse_args(argv)
    args.peers = [x.strip().lower() for x in args.peers.split(",") if x.strip()]
    for x in args.peers:
        if x not in ("siconos", "mujoco"):
            ap.error(f"--peers: unknown peer '{x}' (allowed: siconos, mujoco)")
    scenes = [x.strip() for x in args.scenes.split(",") if x.strip()]
    for s in scenes:
        if s not in ("two_mass", "A"):
            ap.error(f"--scenes: unknown scene '{s}' (allowed: two_mass, A)")
    if not os.access(args.camdyn, os.X_OK):
        ap.error(f"--camdyn: {args.camdyn} is not an executable (build camdyn_cli first)")
    args.build = args.build or os.path.dirname(os.path.abspath(args.camdyn))
    os.makedirs(args.out, exist_ok=True)
    work = os.path.join(args.build, "peers-work")
    try:
        commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short=12", "HEAD"], capture_output=True,
                                text=True).stdout.strip() or "unknown"
    except OSError:
        commit = "unknown"
    stamp = (f"Generated by `bench/peers/peers.py{' --quick' if args.quick else ''}` at commit {commit} on "
             f"{time.strftime('%Y-%m-%dT%H:%M:%SZ', time.gmtime())}.")
    rows, info = [], {}

    def say(s):
        print(s, flush=True)
        if "skipped:" in s:
            info.setdefault("skipped", []).append(s.strip())

    t0 = time.time()
    if "two_mass" in scenes:
        info["two_mass"] = run_two_mass(args, os.path.join(work, "two_mass"), rows, say)
    if "A" in scenes:
        info["A"] = run_case_a(args, os.path.join(work, "A"), rows, say)
    write_outputs(args.out, rows, info, stamp, say)
    say(f"peers.py: wrote {args.out}/peers.md, peers.csv and the figures in {time.time() - t0:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
