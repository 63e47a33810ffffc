"""Bring your own follower from Python (issue 17): camdyn.run(scene, follower=obj).

The follower is the one of tests/mechanism/test_follower_system.cpp — a rigid follower (m) on a
progressive (cubic hardening) valve spring, r = −(P + k q + k₃ q³) — written as a plain
Python class, against independent solutions from the circle cam's closed form
(flat-faced follower, constant speed: X = e (1 + cos θ), θ = π + 2π f t, the lift above the
base circle R − e):

* held at 5 rev/s the contact force is m Ẍ + P + k X + k₃ X³ (to 1e-8 of its maximum);
* at 220 rev/s the follower separates at the first root of that force (bisection here, to
  1e-9 relative) and lands where m q̈ = −(P + k q + k₃ q³) from there meets the cam again
  (scipy's DOP853, to 1e-8 relative);
* a Python exception in a callback ends the run cleanly with its text in the summary;
* the Python follower's cost against the same follower in C++ (camdyn.CubicSpringFollower)
  is measured and printed (README "Bring your own follower").

Run by ctest (label "python") like test_camdyn.py.
"""

import math
import threading
import time

import numpy as np
import pytest

import camdyn

M, K, K3, P = 0.1, 2e4, 5e8, 150.0  # kg, N/m, N/m³, N
R, E = 0.02, 0.004  # circle cam: radius, eccentricity [m]


class CubicSpring:
    """A rigid follower on a cubic hardening spring: M q̈ = −(P + K q + K3 q³) + F."""

    size = 1
    contacts = [camdyn.FollowerContact(name="cam", row=[1.0])]
    mass = M
    name = "cubic valve spring (Python)"

    @staticmethod
    def spring(q):
        return P + K * q + K3 * q ** 3

    def force(self, t, q, v):
        return [-(P + K * q[0] + K3 * q[0] ** 3)]

    def jacobian(self, t, q, v):
        return [[-(K + 3 * K3 * q[0] ** 2)]], None

    def kinetic_energy(self, v):
        return 0.5 * M * v[0] ** 2

    def potential_energy(self, q):
        return P * q[0] + 0.5 * K * q[0] ** 2 + 0.25 * K3 * q[0] ** 4


def scene(speed, model="lee", integrator="arkode-erk", t_end=None):
    s = {
        "title": "user follower",
        "cam": {"profile": "circle", "radius": R, "eccentricity": E, "theta0_deg": 180.0,
                "speed_rev_s": speed},
        "follower": {"kind": "rigid"},  # not used: the follower object replaces it
        "contact": {"model": model, "tol_u": 1e-11},
        "solver": {"integrator": integrator, "rtol": 1e-10, "atol": 1e-14},
        "run": {"output_dt": 0.0},
    }
    if t_end is not None:
        s["run"]["t_end"] = t_end
    return s


def lift(f, t):
    """Closed form: X, Ẋ, Ẍ of the circle cam's lift above its base circle at time(s) t."""
    w = 2 * math.pi * f
    th = math.pi + w * np.asarray(t, dtype=np.float64)
    return E * (1 + np.cos(th)), -E * w * np.sin(th), -E * w * w * np.cos(th)


def held_force(f, t):
    X, _, Xdd = lift(f, t)
    return M * Xdd + P + K * X + K3 * X ** 3


METHODS = [("lee", "arkode-erk"), ("lee", "arkode-dirk"), ("event", "arkode-erk"),
           ("event", "cvode-bdf")]


@pytest.mark.parametrize("model,integrator", METHODS)
def test_held_force_is_the_closed_form(model, integrator):
    f = 5.0
    r = camdyn.run(scene(f, model, integrator, t_end=0.2), follower=CubicSpring())  # 1 rev
    s, h = r.summary, r.history
    assert s["finished"], s["message"]
    assert s["separations"] == 0
    assert list(h)[len(camdyn.history_columns):] == ["F_cam", "gap_cam", "in_cam", "u_q0", "v_q0"]
    assert h["t"][-1] == pytest.approx(0.2, rel=1e-12)
    assert len(h["t"]) > 100
    # the cam motion in the history is the closed form's: X = u_c − gap, θ = π + 2π f t
    X, _, _ = lift(f, h["t"])
    np.testing.assert_allclose(h["theta"], math.pi + 2 * math.pi * f * h["t"], rtol=1e-13)
    np.testing.assert_allclose(h["u_c"] - h["gap"], X, rtol=0, atol=1e-13)
    np.testing.assert_array_equal(h["u_q0"], h["u_c"])  # row [1], no clearance
    F = held_force(f, h["t"])
    err = np.max(np.abs(h["contact_force"] - F)) / np.max(F)
    print(f"{model}/{integrator}: held force error {err:.3g} of {np.max(F):.4g} N, "
          f"|gap| <= {np.max(np.abs(h['gap'])):.3g} m, {s['steps']} steps")
    assert err < 1e-8
    np.testing.assert_array_equal(h["F_cam"], h["contact_force"])
    assert np.all(h["in_cam"] == 1.0)
    assert np.max(np.abs(h["gap"])) < 1e-10
    # energy balance with the follower's energies, against the work scale F·lift
    assert s["energy_residual"] < 1e-8 * np.max(F) * 2 * E


def first_root(f):
    """The separation time: the first root of the closed-form held force (scan + bisection)."""
    T = 1.0 / f
    ts = np.linspace(0.0, T, 4001)
    i = int(np.argmax(held_force(f, ts) < 0))
    assert i > 0, "the closed form never separates"
    a, b = ts[i - 1], ts[i]
    for _ in range(200):
        mid = 0.5 * (a + b)
        if held_force(f, mid) >= 0:
            a = mid
        else:
            b = mid
    return 0.5 * (a + b)


@pytest.mark.parametrize("model,integrator", METHODS)
def test_separation_is_the_first_root(model, integrator):
    f = 220.0
    t_sep = first_root(f)
    r = camdyn.run(scene(f, model, integrator, t_end=1.0 / f), follower=CubicSpring())
    assert r.summary["finished"], r.summary["message"]
    ev = r.events
    assert ev[0]["kind"] == "separation" and ev[0]["contact"] == "cam"
    print(f"{model}/{integrator}: separation {ev[0]['t'] - t_sep:.3g} s off "
          f"(t_sep = {t_sep:.9g} s)")
    assert ev[0]["t"] == pytest.approx(t_sep, rel=1e-9)
    # free flight to the impact, independently (scipy), when scipy is there
    integrate = pytest.importorskip("scipy.integrate")
    gap = lambda t, y: y[0] - lift(f, t)[0]  # noqa: E731
    gap.terminal, gap.direction = True, -1
    sol = integrate.solve_ivp(lambda t, y: [y[1], -CubicSpring.spring(y[0]) / M],
                              (t_sep + 1e-7, t_sep + 1.0 / f),
                              # start just after the separation on the cam's path (the
                              # follower leaves it tangentially: 1e-7 s costs O(1e-21) m)
                              [float(lift(f, t_sep + 1e-7)[0]), float(lift(f, t_sep + 1e-7)[1])],
                              method="DOP853", rtol=1e-13, atol=1e-18, events=gap)
    t_imp = float(sol.t_events[0][0])
    imp = [e for e in ev if e["kind"] == "impact"]
    assert imp, "no impact"
    print(f"{model}/{integrator}: impact {imp[0]['t'] - t_imp:.3g} s off")
    assert imp[0]["t"] == pytest.approx(t_imp, rel=1e-8)


def test_python_follower_equals_the_cpp_one():
    """Same follower, same scene: the Python object and camdyn.CubicSpringFollower (C++)
    give the same run, step for step."""
    py = camdyn.run(scene(220.0, t_end=1.0 / 220), follower=CubicSpring())
    cc = camdyn.run(scene(220.0, t_end=1.0 / 220), follower=camdyn.CubicSpringFollower(M, K, K3, P))
    assert py.summary["steps"] == cc.summary["steps"]
    assert list(py.history) == list(cc.history)
    for c in py.history:
        np.testing.assert_allclose(py.history[c], cc.history[c], rtol=1e-12, atol=1e-15, err_msg=c)
    assert [e["kind"] for e in py.events] == [e["kind"] for e in cc.events]
    assert py.summary["model"] != cc.summary["model"]  # names differ: the user's name shows


def test_contracts_dicts_matrices_and_defaults():
    """contacts as dicts, mass as a 1×1 matrix, no energies (kinetic defaults to ½ vᵀ M v),
    methods instead of attributes, an observer with the extra columns."""

    class Plain:
        def size(self):
            return 1

        def contacts(self):
            return [{"name": "cam", "row": [1.0]}]

        def mass(self):
            return [[M]]

        def force(self, t, q, v):
            return np.array([-(P + K * q[0] + K3 * q[0] ** 3)])

    rows = []
    r = camdyn.run(scene(5.0, t_end=0.01), follower=Plain(), observer=rows.append)
    assert r.summary["finished"], r.summary["message"]
    assert rows[-1]["F_cam"] == r.history["F_cam"][-1]
    np.testing.assert_allclose(r.history["kinetic"], 0.5 * M * r.history["v_q0"] ** 2, rtol=1e-14)
    ref = camdyn.run(scene(5.0, t_end=0.01), follower=CubicSpring())
    np.testing.assert_allclose(r.history["contact_force"], ref.history["contact_force"], rtol=1e-12)
    # a follower.* mapping is still the override it always was
    assert camdyn.run(scene(5.0, t_end=0.001), follower={"mass": 0.2}).summary["finished"]


class Raises(CubicSpring):
    def __init__(self, where, t_fail, exc=ValueError):
        self.where, self.t_fail, self.exc = where, t_fail, exc
        self.calls_after = 0

    def _check(self, t):
        if t > self.t_fail:
            self.calls_after += 1
            raise self.exc(f"spring broke at t = {t:.6g}")

    def force(self, t, q, v):
        if self.where == "force":
            self._check(t)
        return super().force(t, q, v)

    def jacobian(self, t, q, v):
        if self.where == "jacobian":
            self._check(t)
        return super().jacobian(t, q, v)


@pytest.mark.parametrize("model,integrator,where", [
    ("lee", "arkode-erk", "force"), ("event", "arkode-erk", "force"),
    ("penalty", "arkode-erk", "force"), ("lee", "arkode-dirk", "jacobian"),
    ("lee", "cvode-bdf", "force"), ("event", "cvode-bdf", "force")])
def test_exception_in_a_callback_ends_the_run(model, integrator, where):
    fol = Raises(where, 0.05)
    r = camdyn.run(scene(5.0, model, integrator, t_end=0.2), follower=fol)
    s = r.summary
    assert not s["finished"]
    assert s["termination"] == "error"
    call = "force(t, q, v)" if where == "force" else "jacobian(t, q, v)"
    assert f"Python follower: {call} raised ValueError: spring broke at t = " in s["message"]
    assert s["message"].startswith("at t = ")
    assert 0.04 < s["t_end"] <= 0.05 + 1e-3
    assert fol.calls_after == 1  # Python is not called again once it raised
    assert r.history["t"][-1] == pytest.approx(s["t_end"])  # what was computed is kept


def test_bad_return_values_are_named():
    class TwoForces(CubicSpring):
        def force(self, t, q, v):
            return [0.0, 0.0] if t > 0.01 else super().force(t, q, v)

    r = camdyn.run(scene(5.0, t_end=0.02), follower=TwoForces())
    assert not r.summary["finished"]
    assert r.summary["message"].endswith(
        "Python follower: force(t, q, v) returned shape (2,); expected size() = 1 values")

    class NotNumbers(CubicSpring):
        def potential_energy(self, q):
            return "lots"

    r = camdyn.run(scene(5.0, t_end=0.02), follower=NotNumbers())
    assert not r.summary["finished"]
    assert "potential_energy(q) returned a value that is not a number" in r.summary["message"]

    class BadRow(CubicSpring):
        contacts = [{"name": "cam", "row": [1.0, 0.0]}]

    with pytest.raises(camdyn.SceneError, match=r"contacts\(\)\[0\]\.row"):
        camdyn.run(scene(5.0, t_end=0.02), follower=BadRow())

    class NotSpd(CubicSpring):
        mass = -1.0

    with pytest.raises(camdyn.SceneError, match="positive definite"):
        camdyn.run(scene(5.0, t_end=0.02), follower=NotSpd())

    class NoForce:
        size, contacts, mass = 1, [{"name": "cam", "row": [1.0]}], 1.0

    with pytest.raises(TypeError, match="force"):
        camdyn.run(scene(5.0, t_end=0.02), follower=NoForce())

    class Unknown(CubicSpring):
        contacts = [{"name": "cam", "row": [1.0], "stiffness": 1.0}]

    with pytest.raises(TypeError, match="unknown keys"):
        camdyn.run(scene(5.0, t_end=0.02), follower=Unknown())


def test_exception_while_building_propagates():
    """force() is called once when the model is built (before the run): raised as is."""
    class Early(CubicSpring):
        def force(self, t, q, v):
            raise RuntimeError("not ready")

    with pytest.raises(RuntimeError, match="not ready"):
        camdyn.run(scene(5.0, t_end=0.02), follower=Early())


def test_keyboard_interrupt_propagates():
    fol = Raises("force", 0.01, KeyboardInterrupt)
    with pytest.raises(KeyboardInterrupt):
        camdyn.run(scene(5.0, t_end=0.2), follower=fol)


def test_gil_is_released_between_callbacks():
    """Another Python thread runs while a Python follower integrates (the adapter holds the
    GIL only inside its callbacks)."""
    ticks = []
    done = threading.Event()

    def other():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    th = threading.Thread(target=other)
    th.start()
    try:
        r = camdyn.run(scene(5.0, t_end=0.2), follower=camdyn.CubicSpringFollower(M, K, K3, P))
        r2 = camdyn.run(scene(5.0, t_end=0.2), follower=CubicSpring())
    finally:
        done.set()
        th.join()
    assert r.summary["finished"] and r2.summary["finished"]
    assert len(ticks) > 5


def best_of(n, fn):
    best = math.inf
    out = None
    for _ in range(n):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


@pytest.mark.parametrize("model,integrator", [("lee", "arkode-erk"), ("event", "cvode-bdf")])
def test_python_follower_cost(model, integrator, capsys):
    """How slow the Python callable is: one revolution at 5 rev/s (held, rtol 1e-10) with
    the Python follower and with the same follower in C++; printed, and in the README."""
    sc = scene(5.0, model, integrator, t_end=0.2)
    t_py, r_py = best_of(3, lambda: camdyn.run(sc, follower=CubicSpring()))
    t_cc, r_cc = best_of(3, lambda: camdyn.run(sc, follower=camdyn.CubicSpringFollower(M, K, K3, P)))
    assert r_py.summary["finished"] and r_cc.summary["finished"]
    # The same work within 10 %: since the event method projects its held contact every
    # step (issue 23), the Python and C++ followers' round-off-level differences reach
    # CVODE's step-size choices on this fully held one-unknown follower (339 against 316
    # steps measured; Lee on arkode-erk: equal).
    assert abs(r_py.summary["steps"] - r_cc.summary["steps"]) <= 0.1 * r_cc.summary["steps"]
    calls = [0]

    class Counted(CubicSpring):
        def force(self, t, q, v):
            calls[0] += 1
            return super().force(t, q, v)

    camdyn.run(sc, follower=Counted())  # how many times the run calls force()
    steps = r_py.summary["steps"]
    with capsys.disabled():
        print(f"\n[python follower cost] {model}/{integrator}, 1 rev at 5 rev/s: {steps} steps, "
              f"{calls[0]} calls of force(); Python {t_py * 1e3:.1f} ms ({steps / t_py:.0f} steps/s), "
              f"C++ {t_cc * 1e3:.1f} ms ({r_cc.summary['steps'] / t_cc:.0f} steps/s): "
              f"{t_py / t_cc:.1f}x slower, {(t_py - t_cc) / calls[0] * 1e6:.2f} us more per call")
    assert t_py > 0 and t_cc > 0
