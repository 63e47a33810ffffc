"""Acceptance criteria through the Python API (issue 38): summary["criteria"] and the
sweep's criterion arrays, on a valve landing through a lash. The numbers are checked against
closed forms in tests/results/test_criteria.cpp; here: the same criteria reach Python, and a
limit between two speeds' seating velocities passes one and fails the other.

Run by ctest (label "python") like test_camdyn.py.
"""

import math

import numpy as np

import camdyn

SCENE = """title = "landing valve"
[cam]
profile = "law"
law = "dwell 100; cycloidal 80 0.008; poly345 80 -0.008; dwell 100"
base_radius = 0.02
follower_face = "point"
speed_rev_s = 6.0
[follower]
kind = "network"
[contact]
tol_u = 1e-10
[solver]
rtol = 1e-9
atol = 1e-13
[run]
t_end = 0.12
output_dt = 1e-5
[criteria]
max_seating_velocity = 0.18
max_bounce_count = 100
[[nodes]]
name = "valve"
mass = 0.05
[[elements]]
type = "spring"
nodes = ["valve", "ground"]
stiffness = 30000.0
preload = 200.0
[[contacts]]
name = "cam"
type = "cam"
nodes = ["valve"]
clearance = 0.0002
[[contacts]]
name = "seat"
type = "stop"
nodes = ["valve"]
side = "below"
restitution = 0.6
"""


def closing_speed(c, speed):
    """|ds/dt| where the 3-4-5 closing flank (8 mm over 80°) passes s = c."""
    L, beta = 0.008, math.radians(80)
    lo, hi = 0.0, 1.0
    for _ in range(200):
        x = 0.5 * (lo + hi)
        if L * (1 - (10 * x**3 - 15 * x**4 + 6 * x**5)) > c:
            lo = x
        else:
            hi = x
    return L * (30 * x**2 - 60 * x**3 + 30 * x**4) / beta * 2 * math.pi * speed


def test_criteria_reach_the_summary_and_the_sweep():
    r = camdyn.run(SCENE)
    assert r.finished, r.summary["message"]
    crit = {c["name"]: c for c in r.summary["criteria"]}
    assert set(crit) == {"seating_velocity", "bounce_count"}
    v6 = closing_speed(2e-4, 6.0)  # 0.101 m/s
    assert abs(crit["seating_velocity"]["value"] - v6) < 1e-5 * v6
    assert crit["seating_velocity"]["pass"] is True
    assert r.summary["criteria_pass"] is True
    assert r.summary["landings"][0]["bounces"] == crit["bounce_count"]["value"]
    s = camdyn.sweep(SCENE, "cam.speed_rev_s", [6.0, 12.0], threads=2)
    assert list(s["criterion_seating_velocity_pass"]) == [1.0, 0.0]  # 0.203 m/s > 0.18 at 12 rev/s
    assert np.allclose(s["criterion_seating_velocity_value"], [v6, closing_speed(2e-4, 12.0)], rtol=1e-5)
