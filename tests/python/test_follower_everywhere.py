"""A user follower in jump_speed, run_batch and sweep, and the plausibility warnings, from
Python (issue 28).

The follower is a rigid valve (m, k, P) on a linear spring, written in Python; the scene's
own follower is a different network valve. Checks against a second formulation (the same
valve as a network scene) and the closed form of the jump speed on the eccentric circle cam
(flat face, X = e (1 + cos θ) above the base circle): ω_f² = (2 k e + P) / (m e).

Run by ctest (label "python") like test_camdyn.py.
"""

import math
import os
import pathlib

import pytest

import camdyn

SRC = pathlib.Path(os.environ.get("CAMDYN_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
OHC = str(SRC / "examples" / "ohc_bucket_tappet.toml")
E = 0.004
SCENE_VALVE = (0.05, 3e4, 250.0)  # the scene's own valve: jumps at 249 rev/s
USER_VALVE = (0.1, 2e4, 150.0)  # the user's: 140.1 rev/s


def valve_scene(m, k, P):
    return f"""title = "valve"
[cam]
profile = "circle"
radius = 0.02
eccentricity = 0.004
theta0_deg = 180
speed_rev_s = 100
[follower]
kind = "network"
[contact]
model = "lee"
tol_u = 1e-10
[solver]
rtol = 1e-9
atol = 1e-13
[run]
t_end = 0.014
output_dt = 0
[[nodes]]
name = "valve"
mass = {m!r}
[[elements]]
name = "spring"
type = "spring"
nodes = ["valve", "ground"]
stiffness = {k!r}
preload = {P!r}
[[contacts]]
name = "cam"
type = "cam"
nodes = ["valve"]
"""


class LinearValve:
    """M q̈ = −(P + k q) + F on one cam contact."""

    size = 1
    contacts = [camdyn.FollowerContact(name="cam", row=[1.0])]
    linear = True
    name = "linear valve (Python)"

    def __init__(self, m, k, P):
        self.mass, self.k, self.P = m, k, P

    def force(self, t, q, v):
        return [-(self.P + self.k * q[0])]


def closed_form(m, k, P):
    return math.sqrt((2 * k * E + P) / (m * E)) / (2 * math.pi)


def test_jump_speed_uses_the_user_follower():
    opts = {"rel_tol": 1e-3}
    user = camdyn.jump_speed(valve_scene(*SCENE_VALVE), opts, follower=LinearValve(*USER_VALVE))
    net = camdyn.jump_speed(valve_scene(*USER_VALVE), opts)
    width = user["hi_rev_s"] - user["lo_rev_s"]
    assert user["method"] == "simulation"
    assert abs(user["jump_speed_rev_s"] - net["jump_speed_rev_s"]) <= width
    truth = closed_form(*USER_VALVE)
    assert abs(user["jump_speed_rev_s"] - truth) <= 2e-3 * truth
    assert abs(truth - closed_form(*SCENE_VALVE)) > 100  # the scene's follower would say 249


def test_batch_and_sweep_use_the_user_follower():
    speeds = [60.0, 100.0]
    user = camdyn.run_batch([(valve_scene(*SCENE_VALVE), {"cam.speed_rev_s": s}) for s in speeds],
                            threads=1, follower=LinearValve(*USER_VALVE))
    net = camdyn.run_batch([(valve_scene(*USER_VALVE), {"cam.speed_rev_s": s}) for s in speeds])
    own = camdyn.run_batch([(valve_scene(*SCENE_VALVE), {"cam.speed_rev_s": s}) for s in speeds])
    for u, n, o in zip(user, net, own):
        assert u["finished"] and u["separations"] == 0
        assert u["max_contact_force"] == pytest.approx(n["max_contact_force"], rel=1e-6)
        assert abs(u["max_contact_force"] - o["max_contact_force"]) > 10
    sw = camdyn.sweep(valve_scene(*SCENE_VALVE), "cam.speed_rev_s", [100.0, 160.0],
                      follower=LinearValve(*USER_VALVE))
    assert list(sw["separations"] > 0) == [False, True]  # floats above 140 rev/s, not at 100


def test_refusals_have_exact_messages():
    with pytest.raises(camdyn.SceneError) as e:
        camdyn.run_batch([valve_scene(*SCENE_VALVE)], threads=2, follower=LinearValve(*USER_VALVE))
    assert str(e.value) == ("camdyn.run_batch: key 'threads' = 2: a user follower runs on one thread (its "
                            "methods are called with the GIL held): must be 0 or 1")
    with pytest.raises(camdyn.SceneError) as e:
        camdyn.sweep(valve_scene(*SCENE_VALVE), "elements.spring.preload", [100.0],
                     follower=LinearValve(*USER_VALVE))
    assert str(e.value) == ("--key: key 'key' = elements.spring.preload: is replaced by the user follower "
                            "(follower.*, [spring] and the network tables are not used): sweeping it would "
                            "change nothing")


def test_warnings_in_the_summary():
    r = camdyn.run(OHC, **{"contacts.cam.clearance": 0.2, "run.t_end": 0.005})
    assert r.finished
    (w,) = r.summary["warnings"]
    assert w.startswith("contact 'cam': clearance 0.2 m is not smaller than the cam's lift 0.008")
    assert w.endswith(" m: the valve never opens (lengths are in metres: 0.2 mm is 0.0002 m)")
    assert camdyn.run(OHC, **{"run.t_end": 0.005}).summary["warnings"] == []
    # designer units through overrides: the same scene as rev/s and seconds
    a = camdyn.resolved_scene(OHC, **{"cam.speed_rpm": 3000, "cam.rpm_of": "engine", "run.revolutions": 1})
    assert a == camdyn.resolved_scene(OHC)
