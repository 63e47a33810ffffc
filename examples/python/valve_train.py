#!/usr/bin/env python3
"""Valve lift and seat force of the OHC bucket-tappet valve train at two cam speeds,
through camdyn's Python bindings (a follower network: examples/ohc_bucket_tappet.toml).

    PYTHONPATH=build/python python3 examples/python/valve_train.py [--out valve_train.png]

Runs one camshaft revolution at 25 rev/s (the tappet stays on the cam) and at 75 rev/s,
over-speed: above ~67.8 rev/s the valve train floats (the tappet leaves the cam on the
nose and the valve bounces on its seat when it closes). Plots the valve lift u_valve [mm]
and the seat force F_seat [N] against the cam angle [deg], both speeds overlaid, and
writes the PNG given by --out.
"""
import argparse
import math
import os
import pathlib
import sys
from collections import Counter

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402

import camdyn  # noqa: E402

SCENE = pathlib.Path(__file__).resolve().parents[1] / "ohc_bucket_tappet.toml"
SPEEDS = (25.0, 75.0)  # rev/s


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="valve_train.png", help="PNG to write (default: %(default)s)")
    ap.add_argument("--scene", default=str(SCENE),
                    help="network scene with a node 'valve' and a contact 'seat' (default: the OHC example)")
    ap.add_argument("--speeds", type=float, nargs="+", default=list(SPEEDS),
                    help="cam speeds [rev/s] (default: %(default)s)")
    args = ap.parse_args(argv)

    runs = []
    for speed in args.speeds:
        # one revolution; the cam contact and the seat are contacts 'cam' and 'seat'
        r = camdyn.run(args.scene, **{"cam.speed_rev_s": speed, "run.t_end": 1.0 / speed})
        s = r.summary
        counts = Counter((e["contact"], e["kind"]) for e in r.events)
        print(f"{speed:g} rev/s: finished={s['finished']}, {s['steps']} steps, "
              f"max valve lift {1e3 * r.history['u_valve'].max():.4g} mm, "
              f"max seat force {r.history['F_seat'].max():.6g} N, events "
              + (", ".join(f"{c} {k} ×{n}" for (c, k), n in sorted(counts.items())) or "none"))
        if not s["finished"]:
            print(f"  not finished: {s['message']}", file=sys.stderr)
            return 1
        runs.append((speed, r))

    fig, (ax_u, ax_f) = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True,
                                     constrained_layout=True)
    for speed, r in runs:
        h = r.history
        deg = h["theta"] * (180.0 / math.pi)
        ax_u.plot(deg, 1e3 * h["u_valve"], lw=0.9, label=f"{speed:g} rev/s")
        ax_f.plot(deg, h["F_seat"], lw=0.9, label=f"{speed:g} rev/s")
        seat = [e["theta"] * 180.0 / math.pi for e in r.events
                if e["kind"] == "impact" and e["contact"] == "seat"]
        if seat:
            ax_u.plot(seat, [0.0] * len(seat), "|", ms=8,
                      color=ax_u.lines[-1].get_color())
    ax_u.set_ylabel("valve lift u_valve [mm]")
    ax_u.set_title(f"{runs[0][1].summary['scene']}: one camshaft revolution "
                   "(| : seat impacts)", fontsize=9)
    ax_f.set_ylabel("seat force F_seat [N]")
    ax_f.set_xlabel("cam angle [deg]")
    ax_f.set_xlim(0.0, 360.0)
    for ax in (ax_u, ax_f):
        ax.grid(alpha=0.3)
        ax.legend(loc="upper right")
    out = os.path.abspath(args.out)
    os.makedirs(os.path.dirname(out), exist_ok=True)
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
