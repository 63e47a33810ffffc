"""Tutorial 4 (Python): the follower of own_follower.cpp written as a Python class.

usage: python3 docs/tutorials/own_follower.py OUT CPP_RUN_DIR
Runs the follower at 25 and 80 rev/s, checks the 25 rev/s run against the C++ follower's
history (CPP_RUN_DIR/history.csv, same scene and speed) and draws OUT/own_follower.png.
"""
import csv
import pathlib
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import camdyn


class TappetValve:
    """Tappet and valve (q = their lifts [m]) on an elastic stem; progressive valve spring."""

    size = 2
    mass = [0.045, 0.065]                          # kg: the diagonal of M
    contacts = [camdyn.FollowerContact("cam", row=[1.0, 0.0], clearance=0.2e-3),
                camdyn.FollowerContact("seat", row=[0.0, 1.0], cam=False)]
    name = "tappet + valve, progressive spring (Python)"
    k_s, c_s = 5e7, 30.0                           # N/m, N·s/m: the stem
    P, k, k3 = 250.0, 35000.0, 2e8                 # N, N/m, N/m³: the valve spring

    def force(self, t, q, v):
        stem = self.k_s * (q[0] - q[1]) + self.c_s * (v[0] - v[1])
        return [-stem, stem - (self.P + self.k * q[1] + self.k3 * q[1] * q[1] * q[1])]

    def kinetic_energy(self, v):
        return 0.5 * (self.mass[0] * v[0] * v[0] + self.mass[1] * v[1] * v[1])

    def potential_energy(self, q):
        d = q[0] - q[1]
        return (0.5 * self.k_s * d * d + self.P * q[1] + 0.5 * self.k * q[1] * q[1]
                + 0.25 * self.k3 * q[1] * q[1] * q[1] * q[1])

    def damping_power(self, v):
        return self.c_s * (v[0] - v[1]) * (v[0] - v[1])


out = pathlib.Path(sys.argv[1])
cpp_dir = pathlib.Path(sys.argv[2])
scene = "docs/tutorials/valve_train.toml"          # the cam and the run of tutorial 1
runs = {speed: camdyn.run(scene, follower=TappetValve(),                  # one revolution each
                          **{"cam.speed_rev_s": speed, "run.t_end": 1.0 / speed})
        for speed in (25.0, 80.0)}
for speed, r in runs.items():
    s = r.summary
    print(f"{speed:4.0f} rev/s: {s['steps']} steps, {s['impacts']} impacts, "
          f"peak seat force {r.history['F_seat'].max():.0f} N, "
          f"events: {[(e['kind'], e['contact']) for e in r.events][:6]}")

# The same follower in C++ and in Python: the same equations, so the same valve motion.
with open(cpp_dir / "history.csv") as f:
    rows = list(csv.reader(f))
u_cpp = np.array([float(x[rows[0].index("u_q1")]) for x in rows[1:]])
u_py = runs[25.0].history["u_q1"]
diff = np.max(np.abs(u_cpp - u_py))
print(f"C++ and Python followers, valve lift: max difference {diff:.2e} m over {len(u_py)} rows")
# Two integrations of the same equations that meet the same tolerance (solver.rtol = 1e-7)
# agree to it, not bit for bit: their step sequences differ by round-off.
assert len(u_cpp) == len(u_py) and diff <= 1e-7 * np.max(np.abs(u_cpp)), "C++ and Python runs differ"

fig, (ax_u, ax_f) = plt.subplots(2, 1, sharex=True, figsize=(7.0, 5.6))
for speed, r in runs.items():
    h = r.history
    deg = np.degrees(h["theta"])
    ax_u.plot(deg, h["u_q0"] * 1e3, lw=1, label=f"tappet, {speed:.0f} rev/s")
    ax_u.plot(deg, h["u_q1"] * 1e3, lw=1, ls="--", label=f"valve, {speed:.0f} rev/s")
    ax_f.plot(deg, h["F_seat"], lw=1, label=f"{speed:.0f} rev/s")
ax_u.set_ylabel("lift [mm]")
ax_f.set_ylabel("seat force [N]")
ax_f.set_xlabel("cam angle [deg]")
ax_u.legend(fontsize=8)
ax_f.legend(fontsize=8)
for ax in (ax_u, ax_f):
    ax.grid(True, alpha=0.3)
fig.suptitle("Your own follower: tappet and valve on a progressive spring")
fig.tight_layout()
fig.savefig(out / "own_follower.png", dpi=110)
print("figure:", out / "own_follower.png")
