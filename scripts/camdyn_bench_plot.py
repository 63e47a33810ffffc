#!/usr/bin/env python3
"""Work-precision figures of `camdyn bench`.

Usage: camdyn_bench_plot.py DIR [--quiet]

Reads DIR/work_precision.csv and writes, for each scene and each error kind
(err_u, err_force, impulse_err, event_err, err_force_pointwise, impact_speed_err, osc_index),
DIR/wp_<scene>_<kind>.png: error against CPU time, log-log: one line per Lee engine in
tolerance order, Lee with a step-size cap (max_step) in cap order, one line per penalty
setting (engine, law, k_p, c_p) in rtol order (colour: k_p; line style: damping; marker:
law). Only finished runs with a
positive error are drawn. Exit status: 0 ok, 2 bad input, 3 numpy/matplotlib missing.
"""
import csv
import math
import os
import re
import sys


def load_rows(argv, csv_name, prog, doc):
    """Parse `DIR [--quiet]`, import matplotlib (Agg) and read DIR/csv_name.

    Returns (dir, quiet, pyplot, rows), or an exit status (2 bad input, 3 no matplotlib).
    """
    args = [a for a in argv[1:] if not a.startswith("--")]
    quiet = "--quiet" in argv
    if len(args) != 1:
        print(doc, file=sys.stderr)
        return 2
    d = args[0]
    path = os.path.join(d, csv_name)
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print(f"{prog}: matplotlib is not installed", file=sys.stderr)
        return 3
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        print(f"{prog}: cannot read {path}: {e}", file=sys.stderr)
        return 2
    return d, quiet, plt, rows


def main(argv):
    loaded = load_rows(argv, "work_precision.csv", "camdyn_bench_plot", __doc__)
    if isinstance(loaded, int):
        return loaded
    d, quiet, plt, rows = loaded
    import matplotlib  # imported (Agg) by load_rows

    def num(s):
        try:
            x = float(s)
        except (TypeError, ValueError):
            return math.nan
        return x

    kinds = {
        "err_u": "max |u_c - u_ref|",
        "err_force": "contact-force error (rigid: pointwise / peak; elastic: 1 ms impulse)",
        "impulse_err": "impulse per revolution, relative error",
        "event_err": "separation/impact time error [s]",
        "err_force_pointwise": "contact force, max |F - F_ref| / max F_ref (pointwise)",
        "impact_speed_err": "impact speed, max relative error",
        "osc_index": "|TV(F) / TV(F_ref) - 1| (below: smoothing or ringing)",
    }
    scenes = []
    for r in rows:
        if r["scene"] not in scenes:
            scenes.append(r["scene"])
    written = []
    for sc in scenes:
        for kind, label in kinds.items():
            series = {}
            for r in rows:
                if r["scene"] != sc or r.get("finished") != "1":
                    continue
                if r["method"] == "reference-check":
                    continue
                cpu, err = num(r["cpu_seconds"]), num(r.get(kind))
                if kind == "osc_index":
                    err = abs(err - 1.0)
                if not (cpu > 0 and err > 0 and math.isfinite(err)):
                    continue
                if r["method"] == "lee" and math.isfinite(num(r.get("max_step"))):
                    key = f"lee {r['engine']} tol_u {num(r['tol']):g}, max_step swept"
                elif r["method"] == "lee":
                    key = f"lee {r['engine']}"
                elif r["method"] == "penalty":
                    # One curve per penalty setting (engine, law, k_p, c_p) over rtol: it
                    # flattens at the accuracy floor its k_p sets.
                    key = f"penalty {r['engine']} {r['variant']} k_p {num(r['kp']):.3g}"
                else:
                    key = f"{r['method']} {r['engine']}"
                series.setdefault(key, []).append((cpu, err, r))
            if not series:
                continue
            fig, ax = plt.subplots(figsize=(10.5, 5.6))
            kps = [num(p[2]["kp"]) for k, v in series.items() if k.startswith("penalty") for p in v]
            lo, hi = (math.log10(min(kps)), math.log10(max(kps))) if kps else (0.0, 1.0)
            cmap = plt.get_cmap("viridis")
            pen_styles = {"undamped": "--", "damped": "-.", "critical": ":"}
            shown = set()
            for key in sorted(series):
                pts = series[key]
                if key.startswith("penalty"):
                    # colour = k_p, line style = damping, points in rtol order
                    pts.sort(key=lambda p: -num(p[2]["tol"]))
                    r0 = pts[0][2]
                    x = (math.log10(num(r0["kp"])) - lo) / max(hi - lo, 1e-9)
                    damping = r0["variant"].split()[-1]
                    ls = pen_styles.get(damping, "--")
                    marker = "s" if r0["variant"].startswith("linear") else "v"
                    lab = None
                    if r0["variant"] not in shown:
                        shown.add(r0["variant"])
                        lab = f"penalty {r0['variant']} (each curve one k_p over rtol)"
                    ax.loglog([p[0] for p in pts], [p[1] for p in pts], ls, marker=marker, ms=3,
                              color=cmap(0.9 * x), lw=1.0, label=lab)
                    continue
                # Lee: in tolerance order
                elif "max_step" in key:
                    pts.sort(key=lambda p: -num(p[2]["max_step"]))
                else:
                    pts.sort(key=lambda p: -num(p[2]["tol"]))
                xs = [p[0] for p in pts]
                ys = [p[1] for p in pts]
                style = "-o" if key.startswith("lee") else "^"
                if "max_step" in key:
                    style = ":D"
                ax.loglog(xs, ys, style, label=key, ms=4)
            if kind == "err_force":
                ax.axhline(1e-3, ls=":", color="k", lw=0.8, label="headline accuracy 1e-3")
            if kps:
                sm = plt.cm.ScalarMappable(cmap=cmap, norm=matplotlib.colors.Normalize(lo, lo + (hi - lo) / 0.9))
                cb = fig.colorbar(sm, ax=ax, pad=0.01, fraction=0.04)
                cb.set_label("penalty log10 k_p")
            ax.set_xlabel("CPU time [s] (median)")
            ax.set_ylabel(label)
            ax.set_title(f"scene {sc}: work-precision ({kind})")
            ax.grid(True, which="both", alpha=0.3)
            # Outside the axes: the curves fill the plot.
            ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.12, 1.0), borderaxespad=0)
            fig.tight_layout()
            safe = re.sub(r"[^A-Za-z0-9_.-]", "_", sc)
            out = os.path.join(d, f"wp_{safe}_{kind}.png")
            fig.savefig(out, dpi=110)
            plt.close(fig)
            written.append(out)
    if not quiet:
        for w in written:
            print(w)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
