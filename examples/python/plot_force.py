#!/usr/bin/env python3
"""Contact force vs time of the paper's cases A and B2, through camdyn's Python bindings.

    PYTHONPATH=build/python python3 examples/python/plot_force.py [OUT_DIR]

Runs case A (rigid follower, 1.75 rev/s, one revolution) and case B2 (elastic bar at
5 rev/s, the first 0.1 s: the first separation is at 0.069 s, then
chatter: separations and impacts), and writes OUT_DIR/contact_force.png
(default OUT_DIR: the current directory).
"""
import os
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402

import camdyn  # noqa: E402

EXAMPLES = pathlib.Path(__file__).resolve().parents[1]


def main(out_dir: str) -> int:
    os.makedirs(out_dir, exist_ok=True)
    a = camdyn.run(EXAMPLES / "case_A.toml", **{"run.t_end": 1 / 1.75})
    b2 = camdyn.run(EXAMPLES / "case_B2.toml", **{"run.t_end": 0.1, "run.output_dt": 1e-5})
    for r in (a, b2):
        s = r.summary
        print(f"{s['scene']}: finished={s['finished']}, {s['steps']} steps, "
              f"{s['separations']} separations, {s['impacts']} impacts, "
              f"max force {s['max_contact_force']:.6g}, cpu {s['cpu_seconds']:.3g} s")
        if not s["finished"]:
            print(f"  not finished: {s['message']}", file=sys.stderr)
            return 1

    fig, axes = plt.subplots(2, 1, figsize=(8, 6.5), constrained_layout=True)
    for ax, r, name in ((axes[0], a, "case A (rigid follower)"),
                        (axes[1], b2, "case B2 (elastic bar)")):
        h = r.history
        ax.plot(h["t"], h["contact_force"], lw=0.8)
        impacts = [e["t"] for e in r.events if e["kind"] == "impact"]
        if impacts:
            ax.plot(impacts, [0.0] * len(impacts), "|", color="C3", ms=8,
                    label=f"impacts ({len(impacts)})")
            ax.legend(loc="upper right")
        ax.set_title(f"{name}: {r.summary['scene']}", fontsize=9)
        ax.set_xlabel("t")
        ax.set_ylabel("contact force")
        ax.grid(alpha=0.3)
    path = os.path.join(out_dir, "contact_force.png")
    fig.savefig(path, dpi=120)
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
