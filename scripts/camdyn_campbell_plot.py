#!/usr/bin/env python3
"""Figure of `camdyn campbell`.

Usage: camdyn_campbell_plot.py DIR [--quiet]

Reads DIR/campbell.csv (speed_rev_s[, speed_rpm], order, amplitude) and
DIR/campbell_lines.csv (name, frequency_hz) and writes DIR/campbell.png: cam order against
camshaft speed, each (speed, order) bin a marker whose area and colour grow with its
amplitude (order 0, the mean, left out), and every line order = frequency / speed (a
spring's surge frequencies): where a line crosses an order with a large amplitude, the cam
excites that mode. Exit status: 0 ok, 2 bad input, 3 matplotlib missing.
"""
import csv
import math
import os
import sys


def main(argv):
    args = [a for a in argv[1:] if not a.startswith("--")]
    quiet = "--quiet" in argv
    if len(args) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    d = args[0]
    try:
        with open(os.path.join(d, "campbell.csv"), newline="") as f:
            rows = list(csv.DictReader(f))
        with open(os.path.join(d, "campbell_lines.csv"), newline="") as f:
            lines = list(csv.DictReader(f))
        pts = [(float(r["speed_rev_s"]), float(r["order"]), float(r["amplitude"])) for r in rows]
        ln = [(r["name"], float(r["frequency_hz"])) for r in lines]
    except (OSError, KeyError, ValueError) as e:
        print(f"camdyn_campbell_plot: {d}: {e}", file=sys.stderr)
        return 2
    pts = [p for p in pts if p[1] > 0 and math.isfinite(p[2])]
    if not pts:
        print(f"camdyn_campbell_plot: {d}/campbell.csv has no order > 0", file=sys.stderr)
        return 2
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("camdyn_campbell_plot: matplotlib is not installed", file=sys.stderr)
        return 3
    amax = max(p[2] for p in pts) or 1.0
    fig, ax = plt.subplots(figsize=(8, 5.5))
    sc = ax.scatter([p[0] for p in pts], [p[1] for p in pts], s=[4 + 200 * p[2] / amax for p in pts],
                    c=[p[2] for p in pts], cmap="viridis", edgecolors="none")
    fig.colorbar(sc, ax=ax, label="amplitude")
    speeds = sorted({p[0] for p in pts})
    omax = max(p[1] for p in pts)
    grid = [speeds[0] + (speeds[-1] - speeds[0]) * i / 400 for i in range(401)]
    for name, f in ln:
        xs = [v for v in grid if f / v <= omax]
        if xs:
            ax.plot(xs, [f / v for v in xs], lw=1.2, label=f"{name} ({f:.4g} Hz)")
    ax.set_xlabel("camshaft speed [rev/s]")
    ax.set_ylabel("cam order")
    ax.set_ylim(0, omax)
    ax.set_title("Campbell diagram")
    if ln:
        ax.legend(fontsize=8, loc="upper right")
    out = os.path.join(d, "campbell.png")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    if not quiet:
        print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
