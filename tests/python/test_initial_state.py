"""The start of a run from Python (issue 27; docs/initial_state.md).

* The issue's user follower (mass 1, r = −500 q − 3500, one cam contact, row [1], q0 = 0)
  on examples/case_A.toml starts 0.0193 below the cam: the paper's "points" cam has its
  knots at r = 2.0, but the spline dips below them, so its base X_base is 1.9807 and the
  lift at θ = 0 is 0.0193. That start raises SceneError naming the contact, the gap and
  initial_state(), for every contact method.
* cam_motion(..., lift=True) is the absolute X_C minus X_base (the same Ẋ_C, Ẍ_C); the
  base is checked against a brute-force support scan of the profile (C++ test).
* initial_state_on_cam() puts the follower on the cam: its q0 is the lift at t = 0 and
  the run starts held (no event, the contact carries the preload at once).
"""

import os

import numpy as np
import pytest

import camdyn

HERE = os.path.dirname(os.path.abspath(__file__))
CASE_A = os.path.join(HERE, "..", "..", "examples", "case_A.toml")


class OneMass:
    """The issue's follower: M = 1, r = −500 q − 3500, one cam contact with row [1]."""

    size = 1
    contacts = [camdyn.FollowerContact(name="cam", row=[1.0])]
    mass = 1.0
    linear = True

    def force(self, t, q, v):
        return [-500.0 * q[0] - 3500.0]


@pytest.mark.parametrize("model", ["lee", "event", "penalty", "holonomic"])
def test_user_follower_below_the_cam_is_scene_error(model):
    with pytest.raises(camdyn.SceneError) as ei:
        camdyn.run(CASE_A, follower=OneMass(), **{"contact.model": model, "run.t_end": 0.01})
    e = ei.value
    msg = str(e)
    assert e.file == "<follower>"
    assert e.key == "initial_state()"
    assert "the start penetrates contact 'cam': its gap at t = 0 is -0.019" in msg
    assert "set by row · q0 = 0 from initial_state(), contacts()[0].clearance = 0 and the cam's lift" in msg
    assert "X_base = 1.98" in msg
    gap = float(msg.split("its gap at t = 0 is ")[1].split(" ")[0])
    assert gap == pytest.approx(-0.0193, abs=1e-4)


def test_cam_motion_lift_is_absolute_minus_base():
    t = np.linspace(0.0, 0.5, 7)
    X, Xd, Xdd = camdyn.cam_motion(CASE_A, t)
    L, Ld, Ldd = camdyn.cam_motion(CASE_A, t, lift=True)
    base = X - L
    assert np.allclose(base, base[0], rtol=0, atol=1e-15)  # one constant offset
    assert base[0] == pytest.approx(1.9807, abs=1e-4)
    assert X[0] == pytest.approx(2.0, abs=1e-12)  # θ = 0 is a knot at r = 2.0
    assert np.array_equal(Xd, Ld) and np.array_equal(Xdd, Ldd)
    assert L.min() >= -1e-12  # nothing below the base


@pytest.mark.parametrize("model", ["lee", "event", "penalty", "holonomic"])
def test_initial_state_on_cam_starts_held(model):
    f = OneMass()
    q0, v0 = camdyn.initial_state_on_cam(CASE_A, f)
    X, Xd, _ = camdyn.cam_motion(CASE_A, 0.0, lift=True)
    assert q0[0] == pytest.approx(X, abs=1e-15)
    assert v0[0] == pytest.approx(Xd, abs=1e-15)
    f.initial_state = (q0, v0)  # an attribute works as well as a method
    over = {"contact.model": model, "run.t_end": 2e-3, "run.output_dt": 2e-4}
    if model == "penalty":
        over["contact.penalty_stiffness"] = 1e8
    r = camdyn.run(CASE_A, follower=f, **over)
    assert r.summary["finished"], r.summary["message"]
    assert r.events == []
    assert np.all(r.history["in_contact"] == 1)
    # The preload (3500 + 500 q0) is carried from t = 0 (less m Ẍ_C's share: |Ẍ_C| ≪ it).
    assert r.history["contact_force"][0] > 3000.0
