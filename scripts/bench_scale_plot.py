#!/usr/bin/env python3
"""Figure and table of `bench_scale sweep` (large elastic followers, issue #8).

Usage: bench_scale_plot.py SCALE.csv [OUT.png]

Reads the CSV of `build/bench/bench_scale sweep` and writes OUT.png (default: next to the
CSV, bench_scale.png): left, CPU per accepted Lee step against the number of elements N,
log-log, one line per configuration, with a slope-1 guide; middle, the same per
right-hand-side evaluation; right, peak memory per element.
Prints a Markdown table and, per configuration, the least-squares slope of log(CPU per
step) against log N over N >= 10^3 and the ratios CPU/step(10^5) / CPU/step(10^3) and
CPU/step(10^6) / CPU/step(10^5), also per right-hand-side evaluation (cvode-bdf's Lee
steps hold a varying number of internal steps).
Exit status: 0 ok, 2 bad input, 3 matplotlib missing.
"""
import csv
import math
import os
import sys


def label(row):
    s = " ".join(t for t in row["settings"].split() if not t.startswith("run.max_steps="))
    return row["engine"] + (f" ({s})" if s else "")


def slope(points):
    pts = [(math.log(n), math.log(c)) for n, c in points if n >= 1000 and c > 0]
    if len(pts) < 2:
        return float("nan")
    mx = sum(x for x, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    sxx = sum((x - mx) ** 2 for x, _ in pts)
    return sum((x - mx) * (y - my) for x, y in pts) / sxx


def main(argv):
    if len(argv) not in (2, 3):
        print(__doc__, file=sys.stderr)
        return 2
    path = argv[1]
    out = argv[2] if len(argv) == 3 else os.path.join(os.path.dirname(path) or ".", "bench_scale.png")
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        print(f"bench_scale_plot.py: {e}", file=sys.stderr)
        return 2
    series = {}
    print("| configuration | N | window s | t reached s | steps (rej.) | CPU s | ms / step | "
          "µs / rhs eval. | steps / sim. s | CPU s / sim. s | factorisations / analyses | peak MB | B / element |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        name = label(r)
        if not r["cpu_s"]:
            print(f"| {name} | {int(r['N']):.0e} | {float(r['t_window']):.1e} | | | | | | | | | | {r['note']} |")
            continue
        n = int(r["N"])
        per_rhs = 1e6 * float(r["cpu_s"]) / float(r["rhs_evals"])
        series.setdefault(name, []).append(
            (n, float(r["ms_per_step"]), float(r["bytes_per_element"]), per_rhs))
        fa = f"{r['lin_setups']} / {r['lin_analyses']}" if r["engine"] != "arkode-erk" else "–"
        note = " (stopped at run.max_steps)" if r["finished"] == "0" else ""
        if r["note"] and r["note"] != "stopped at run.max_steps":
            note += f" [{r['note']}]"
        print(f"| {name} | {n:.0e} | {float(r['t_window']):.1e} | {float(r['t_reached']):.2e}{note} | "
              f"{r['steps']} ({r['rejected']}) | {float(r['cpu_s']):.3g} | {float(r['ms_per_step']):.3g} | {per_rhs:.3g} | "
              f"{float(r['steps_per_sim_s']):.3g} | {float(r['cpu_s_per_sim_s']):.3g} | {fa} | "
              f"{float(r['rss_peak_mb']):.0f} | {float(r['bytes_per_element']):.0f} |")
    print()
    def ratio(d, a, b):
        return d[b] / d[a] if a in d and b in d else float("nan")

    for name, pts in series.items():
        step = {n: c for n, c, _, _ in pts}
        rhs = {n: c for n, _, _, c in pts}
        print(f"{name}: slope of log(ms/step) vs log N (N >= 1e3) = {slope([(n, c) for n, c, _, _ in pts]):.3f}; "
              f"ms/step ratio 1e5/1e3 = {ratio(step, 1000, 100000):.1f}, 1e6/1e5 = {ratio(step, 100000, 1000000):.1f}; "
              f"per rhs evaluation: 1e5/1e3 = {ratio(rhs, 1000, 100000):.1f}, 1e6/1e5 = {ratio(rhs, 100000, 1000000):.1f}")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("bench_scale_plot.py: matplotlib missing (python3-matplotlib): no figure", file=sys.stderr)
        return 3
    fig, (a1, a3, a2) = plt.subplots(1, 3, figsize=(16, 4.4))
    for name, pts in series.items():
        ns = [p[0] for p in pts]
        a1.loglog(ns, [p[1] for p in pts], "o-", label=name)
        a3.loglog(ns, [p[3] for p in pts], "o-", label=name)
        big = [p for p in pts if p[0] >= 10000]
        if big:
            a2.semilogx([p[0] for p in big], [p[2] for p in big], "o-", label=name)
    allpts = [p for pts in series.values() for p in pts]
    if allpts:
        n0 = min(p[0] for p in allpts)
        n1 = max(p[0] for p in allpts)
        c0 = min(p[1] for p in allpts if p[0] == n0)
        a1.loglog([n0, n1], [c0, c0 * n1 / n0], "k:", label="∝ N (slope 1)")
        r0 = min(p[3] for p in allpts if p[0] == n0)
        a3.loglog([n0, n1], [r0, r0 * n1 / n0], "k:", label="∝ N (slope 1)")
    a1.set_xlabel("elements N")
    a1.set_ylabel("CPU per accepted Lee step [ms]")
    a1.set_title("Case B1, N elements: cost per step")
    a1.grid(True, which="both", alpha=0.3)
    a1.legend(fontsize=8)
    a3.set_xlabel("elements N")
    a3.set_ylabel("CPU per right-hand-side evaluation [µs]")
    a3.set_title("Cost per rhs evaluation (all work included)")
    a3.grid(True, which="both", alpha=0.3)
    a3.legend(fontsize=8)
    a2.set_xlabel("elements N")
    a2.set_ylabel("peak RSS growth per element [bytes]")
    a2.set_title("Memory per element (N ≥ 10⁴)")
    a2.axhline(2048, color="r", ls="--", lw=1, label="2 kB goal")
    a2.set_ylim(bottom=0)
    a2.grid(True, which="both", alpha=0.3)
    a2.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"figure: {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
