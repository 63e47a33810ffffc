#!/usr/bin/env python3
"""Figures of `camdyn sweep`.

Usage: camdyn_sweep_plot.py DIR [--quiet]

Reads DIR/sweep.csv and DIR/poincare.csv (first column: the swept key; with a grid of two
keys, one line per value of the second key) and writes
  DIR/sweep_force.png        force margin (min contact force while in contact) and largest
                             contact force against the key; separating points marked
  DIR/sweep_bifurcation.png  bifurcation diagram: the Poincaré samples u_c and v_c (one per
                             revolution after the settling revolutions) against the key
  DIR/sweep_impacts.png      impact map: first-impact and largest-impact cam angle, and the
                             largest impact velocity, against the key
Failed points (finished = 0) are left out. Exit status: 0 ok, 2 bad input,
3 numpy/matplotlib missing.
"""
import csv
import math
import os
import sys


def num(s):
    try:
        return float(s)
    except (TypeError, ValueError):
        return math.nan


def legend(ax):
    """A legend only when something is labelled (all points failed: none)."""
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8)


def main(argv):
    args = [a for a in argv[1:] if not a.startswith("--")]
    quiet = "--quiet" in argv
    if len(args) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    d = args[0]
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("camdyn_sweep_plot: matplotlib is not installed", file=sys.stderr)
        return 3
    try:
        with open(os.path.join(d, "sweep.csv"), newline="") as f:
            reader = csv.reader(f)
            header = next(reader)
            rows = [dict(zip(header, r)) for r in reader]
    except (OSError, StopIteration) as e:
        print(f"camdyn_sweep_plot: cannot read {d}/sweep.csv: {e}", file=sys.stderr)
        return 2
    key = header[0]
    key2 = header[1] if header[1] != "finished" else None
    prows = []
    try:
        with open(os.path.join(d, "poincare.csv"), newline="") as f:
            prows = list(csv.DictReader(f))
    except OSError:
        pass
    rows = [r for r in rows if r.get("finished") == "1"]
    groups = {}
    for r in rows:
        groups.setdefault(r[key2] if key2 else "", []).append(r)

    def label(g):
        return f"{key2} = {g}" if key2 else None

    written = []
    # ---- force margin and max force
    fig, ax = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True)
    for g, rs in groups.items():
        x = [num(r[key]) for r in rs]
        ax[0].plot(x, [num(r["min_contact_force"]) for r in rs], ".-", label=label(g))
        if "verdict" in rs[0]:
            # the verdict (docs/contacts.md): the lash opening of a valve train is no separation
            sep = [r for r in rs if r["verdict"] not in ("", "no_separation")]
            what = "float/bounce (verdict)"
        else:
            sep = [r for r in rs if num(r["separations"]) > 0 or num(r["impacts"]) > 0]
            what = "separates"
        ax[0].plot([num(r[key]) for r in sep], [num(r["min_contact_force"]) for r in sep], "rx",
                   ms=5, label=what if g == list(groups)[0] else None)
        ax[1].plot(x, [num(r["max_contact_force"]) for r in rs], ".-", label=label(g))
    ax[0].axhline(0, color="k", lw=0.6)
    ax[0].set_ylabel("min contact force (margin)")
    ax[1].set_ylabel("max contact force")
    ax[1].set_xlabel(key)
    legend(ax[0])
    if key2:
        legend(ax[1])
    ax[0].set_title("Force margin and peak force")
    fig.tight_layout()
    p = os.path.join(d, "sweep_force.png")
    fig.savefig(p, dpi=120)
    plt.close(fig)
    written.append(p)

    # ---- bifurcation diagram
    fig, ax = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True)
    ok = {r[key] + "|" + (r[key2] if key2 else "") for r in rows}
    ps = [q for q in prows if q[key] + "|" + (q[key2] if key2 else "") in ok]
    ax[0].plot([num(q[key]) for q in ps], [num(q["u_c"]) for q in ps], ",k" if len(ps) > 2000 else ".k",
               ms=2)
    ax[1].plot([num(q[key]) for q in ps], [num(q["v_c"]) for q in ps], ",k" if len(ps) > 2000 else ".k",
               ms=2)
    ax[0].set_ylabel("u_c at the section")
    ax[1].set_ylabel("v_c at the section")
    ax[1].set_xlabel(key)
    ax[0].set_title("Bifurcation diagram (one Poincaré sample per revolution)")
    fig.tight_layout()
    p = os.path.join(d, "sweep_bifurcation.png")
    fig.savefig(p, dpi=120)
    plt.close(fig)
    written.append(p)

    # ---- impact map
    fig, ax = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True)
    for g, rs in groups.items():
        x = [num(r[key]) for r in rs]
        ax[0].plot(x, [num(r["first_impact_theta_deg"]) for r in rs], "o", ms=3,
                   label=("first impact" + (f", {label(g)}" if key2 else "")))
        ax[0].plot(x, [num(r["max_impact_theta_deg"]) for r in rs], "^", ms=3,
                   label=("largest impact" + (f", {label(g)}" if key2 else "")))
        ax[0].plot(x, [num(r["first_separation_theta_deg"]) for r in rs], "s", ms=3,
                   label=("first separation" + (f", {label(g)}" if key2 else "")))
        ax[1].plot(x, [num(r["max_impact_velocity"]) for r in rs], ".-", label=label(g))
    ax[0].set_ylabel("cam angle [deg]")
    ax[0].set_ylim(0, 360)
    legend(ax[0])
    ax[1].set_ylabel("largest impact velocity")
    ax[1].set_xlabel(key)
    ax[0].set_title("Impact map")
    fig.tight_layout()
    p = os.path.join(d, "sweep_impacts.png")
    fig.savefig(p, dpi=120)
    plt.close(fig)
    written.append(p)
    if not quiet:
        for p in written:
            print(p)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
