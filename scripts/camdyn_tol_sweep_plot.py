#!/usr/bin/env python3
"""Work-precision figures of `camdyn bench --tolerance-sweep`.

Usage: camdyn_tol_sweep_plot.py DIR [--quiet]

Reads DIR/tol_sweep.csv and writes, per scene, DIR/tol_sweep_<scene>.png: error against
CPU time (log-log), left err_u, right err_force, one line per method x engine in rtol
order (colour: method; marker: engine). Only finished runs with a positive error are
drawn; each line's loosest point is labelled with its rtol. Exit status: 0 ok, 2 bad
input, 3 matplotlib missing.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from camdyn_bench_plot import load_rows  # noqa: E402  (installed next to this script)

ENGINE_MARK = {"arkode-erk": "o", "arkode-dirk": "s", "cvode-bdf": "^", "ida": "D"}
METHOD_COLOUR = {"lee": "C0", "event": "C1", "holonomic": "C2", "penalty": "C3"}


def main(argv):
    loaded = load_rows(argv, "tol_sweep.csv", "camdyn_tol_sweep_plot", __doc__)
    if isinstance(loaded, int):
        return loaded
    d, quiet, plt, rows = loaded
    scenes = []
    for r in rows:
        if r["scene"] not in scenes:
            scenes.append(r["scene"])
    for sc in scenes:
        series = {}
        for r in rows:
            if r["scene"] != sc or r["status"] != "finished":
                continue
            series.setdefault((r["method"], r["engine"]), []).append(r)
        if not series:
            continue
        fig, axes = plt.subplots(1, 2, figsize=(12, 5))
        for ax, q, lab in ((axes[0], "err_u", "max |u_c - u_ref| [m]"),
                           (axes[1], "err_force", "contact force / impulse error (relative)")):
            for (m, e), rs in sorted(series.items()):
                pts = [(float(r["cpu_s"]), float(r[q]), float(r["rtol"])) for r in rs
                       if r[q] not in ("", "nan") and float(r[q]) > 0 and float(r["cpu_s"]) > 0]
                if not pts:
                    continue
                ax.plot([p[0] for p in pts], [p[1] for p in pts], marker=ENGINE_MARK.get(e, "x"),
                        color=METHOD_COLOUR.get(m, "k"), label=f"{m} {e}", ms=4, lw=1)
                ax.annotate(f"{pts[0][2]:.0e}", (pts[0][0], pts[0][1]), fontsize=6)
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("CPU time [s]")
            ax.set_ylabel(lab)
            ax.grid(True, which="both", alpha=0.3)
        axes[1].legend(fontsize=7, ncol=2)
        fig.suptitle(f"Tolerance sweep, scene {sc}: rtol 1e-2 ... 1e-12 (loosest labelled)")
        fig.tight_layout()
        out = os.path.join(d, f"tol_sweep_{sc}.png")
        fig.savefig(out, dpi=110)
        plt.close(fig)
        if not quiet:
            print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
