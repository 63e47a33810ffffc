"""Tutorial 2: the float speed against the valve-spring preload, in Python.

usage: python3 docs/tutorials/preload_study.py OUT   (from the repository root, build/python
on PYTHONPATH). Writes OUT/float_speed_vs_preload.png.
"""
import pathlib
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import camdyn

out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".")
out.mkdir(parents=True, exist_ok=True)
scene = "docs/tutorials/valve_train.toml"   # tutorial 1's valve train, rigid model
k = 35000.0                                 # N/m: spring.stiffness of that scene

# 1. The float speed for eleven preloads: closed form (rigid follower), no simulation.
preloads = np.linspace(150.0, 400.0, 11)    # N
floats = []
for P in preloads:
    j = camdyn.jump_speed(scene, **{"spring.precompression": P / k})
    floats.append(j["jump_speed_rev_s"])
    print(f"preload {P:5.0f} N: floats from {j['jump_speed_rev_s']:6.2f} rev/s "
          f"(margin reaches zero at {j['theta_deg']:.1f} deg cam)")
floats = np.array(floats)

# 2. Check three of them by simulation: two revolutions 2 % below and 2 % above, in C++
#    threads. Below the float speed the follower keeps contact; above it separates.
for P, J in zip(preloads[::5], floats[::5]):
    s = camdyn.sweep(scene, "cam.speed_rev_s", [0.98 * J, 1.02 * J],
                     **{"spring.precompression": P / k, "run.t_end": 2.0 / J})
    below, above = s["separations"]
    print(f"preload {P:5.0f} N, {J:6.2f} rev/s: separations at -2 %: {below:.0f}, at +2 %: {above:.0f}")
    assert below == 0 and above > 0, "the simulated float speed disagrees with the closed form"

# 3. The figure.
fig, ax = plt.subplots(figsize=(6.4, 4.0))
ax.plot(preloads, floats, "o-", label="float speed (closed form)")
ax.plot(preloads, floats[0] * np.sqrt(preloads / preloads[0]), "--", color="grey",
        label=r"$\propto\sqrt{\mathrm{preload}}$ (for comparison)")
ax.set_xlabel("valve-spring preload [N]")
ax.set_ylabel("camshaft float speed [rev/s]")
ax.set_title("Float speed against preload (rigid model)")
ax.grid(True, alpha=0.3)
ax.legend()
fig.tight_layout()
fig.savefig(out / "float_speed_vs_preload.png", dpi=110)
print("figure:", out / "float_speed_vs_preload.png")
