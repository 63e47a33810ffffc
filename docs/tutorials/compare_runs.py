"""Compare camdyn runs of one network scene (tutorial 3).

usage: compare_runs.py FIGURE.png DIR LABEL [DIR LABEL ...]
Prints one line per run (steps, rejected, impacts, CPU, largest valve-lift difference from
the first run) and draws valve lift and seat force against the cam angle.
"""
import csv
import json
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def load(d):
    with open(f"{d}/history.csv") as f:
        rows = list(csv.reader(f))
    cols = {name: np.array([float(r[i]) for r in rows[1:]]) for i, name in enumerate(rows[0])}
    with open(f"{d}/summary.json") as f:
        return cols, json.load(f)


figure, runs = sys.argv[1], list(zip(sys.argv[2::2], sys.argv[3::2]))
ref_hist, _ = load(runs[0][0])
fig, (ax_u, ax_f) = plt.subplots(2, 1, sharex=True, figsize=(7.0, 5.6))
print(f"{'run':32s} {'steps':>7s} {'rejected':>8s} {'impacts':>7s} {'cpu s':>7s} {'max |du_valve| [mm]':>20s}")
for d, label in runs:
    h, s = load(d)
    # Rows are on the same output grid (run.output_dt) in every run: compare row by row.
    n = min(len(h["t"]), len(ref_hist["t"]))
    du = np.max(np.abs(h["u_valve"][:n] - ref_hist["u_valve"][:n])) * 1e3
    print(f"{label:32s} {s['steps']:7d} {s['rejected_steps']:8d} {s['impacts']:7d} "
          f"{s['cpu_seconds']:7.3f} {du:20.2e}")
    deg = np.degrees(h["theta"])
    ax_u.plot(deg, h["u_valve"] * 1e3, lw=1, label=label)
    ax_f.plot(deg, h["F_seat"], lw=1, label=label)
ax_u.set_ylabel("valve lift [mm]")
ax_f.set_ylabel("seat force [N]")
ax_f.set_xlabel("cam angle [deg]")
ax_u.legend(fontsize=8)
for ax in (ax_u, ax_f):
    ax.grid(True, alpha=0.3)
fig.suptitle("OHV pushrod train, one revolution at 25 rev/s")
fig.tight_layout()
fig.savefig(figure, dpi=110)
print("figure:", figure)
