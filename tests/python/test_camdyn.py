"""camdyn's Python bindings (issue 17), against closed forms and against the CLI.

Run by ctest (label "python") with PYTHONPATH=build/python, CAMDYN_CLI (the camdyn
binary) and CAMDYN_SOURCE_DIR set; by hand:

    PYTHONPATH=build/python CAMDYN_CLI=build/camdyn python3 -m pytest -q tests/python
"""

import json
import math
import os
import pathlib
import signal
import subprocess
import threading
import time
import tomllib

import numpy as np
import pytest

import camdyn

SRC = pathlib.Path(os.environ.get("CAMDYN_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
CLI = os.environ.get("CAMDYN_CLI") or str(SRC / "build" / "camdyn")
CASE_A = str(SRC / "examples" / "case_A.toml")
CASE_A7 = str(SRC / "examples" / "case_A7.toml")
CIRCLE = str(SRC / "examples" / "circle_cam.toml")


def need_cli():
    if not os.access(CLI, os.X_OK):
        pytest.skip(f"camdyn CLI not found at {CLI} (set CAMDYN_CLI)")


def cli(*args, cwd=None):
    need_cli()
    return subprocess.run([CLI, *args], capture_output=True, text=True, cwd=cwd, timeout=300)


# ---- closed forms ------------------------------------------------------------------------

def test_case_a_against_closed_form():
    """Case A (rigid follower riding the cam at 1.75 rev/s, one revolution and a bit):
    u_c = X_C(θ(t)) and F = m Ẍ_C + k δ₀ + k (X_C − X_C(0))."""
    r = camdyn.run(CASE_A, **{"run.t_end": 0.6})
    assert r.finished, r.summary["message"]
    assert r.summary["separations"] == 0 and r.events == []
    sc = tomllib.loads(camdyn.resolved_scene(CASE_A))
    m, k, d0 = sc["follower"]["mass"], sc["spring"]["stiffness"], sc["spring"]["precompression"]
    t = r.history["t"]
    X, _, Xdd = camdyn.cam_motion(CASE_A, t)
    X0, _, _ = camdyn.cam_motion(CASE_A, 0.0)
    F = m * Xdd + k * d0 + k * (X - X0)
    assert np.max(np.abs(r.history["u_c"] - X)) <= 1e-9
    assert np.max(np.abs(r.history["contact_force"] - F)) <= 1e-9 * np.max(np.abs(F))
    assert np.all(r.history["in_contact"] == 1.0)


def test_cam_motion_of_circle_cam_is_harmonic():
    """The eccentric circle: X_C = R + e cos θ, Ẋ_C = −e ω sin θ, Ẍ_C = −e ω² cos θ."""
    R, e, n = 2.0, 0.5, 1.75
    w = 2 * math.pi * n
    t = np.linspace(0.0, 1.0, 1001)
    X, Xd, Xdd = camdyn.cam_motion(CIRCLE, t)
    th = w * t
    assert X.shape == t.shape and X.dtype == np.float64
    np.testing.assert_allclose(X, R + e * np.cos(th), rtol=0, atol=1e-12)
    np.testing.assert_allclose(Xd, -e * w * np.sin(th), rtol=0, atol=1e-9)
    np.testing.assert_allclose(Xdd, -e * w * w * np.cos(th), rtol=0, atol=1e-7)


def test_jump_speed_of_circle_cam():
    """F_req = kδ₀ + k e (cos θ − 1) − m e ω² cos θ first reaches 0 at θ = 0:
    ω_jump = √(k δ₀ / (m e))."""
    j = camdyn.jump_speed(CIRCLE)
    k, d0, m, e = 500.0, 7.0, 1.0, 0.5
    exact = math.sqrt(k * d0 / (m * e)) / (2 * math.pi)
    assert j["method"] == "closed-form"
    assert abs(j["jump_speed_rev_s"] - exact) <= 1e-10 * exact
    # and through an override: 4x the preload doubles the jump speed
    j2 = camdyn.jump_speed(CIRCLE, **{"spring.precompression": 28.0})
    assert abs(j2["jump_speed_rev_s"] - 2 * exact) <= 1e-10 * exact


def test_events_of_separating_case_a7():
    """Case A at 7 rev/s (above its jump speed): one separation then one impact in every
    revolution, at the same cam angle each time (a period-1 motion)."""
    revs = 3
    r = camdyn.run(CASE_A7, **{"run.t_end": revs / 7.0})
    assert r.finished, r.summary["message"]
    kinds = [e["kind"] for e in r.events]
    assert kinds == ["separation", "impact"] * revs
    assert r.summary["separations"] == revs and r.summary["impacts"] == revs
    for i, e in enumerate(r.events):
        assert set(e) == {"t", "kind", "impact_velocity", "theta", "impulse"}
        assert int(e["theta"] // (2 * math.pi)) == i // 2  # each pair inside revolution i//2
        assert e["theta"] == pytest.approx(7.0 * 2 * math.pi * e["t"], rel=1e-12)
    imp = [e for e in r.events if e["kind"] == "impact"]
    assert all(e["impact_velocity"] > 0 for e in imp)
    sep_angle = [math.fmod(e["theta"], 2 * math.pi) for e in r.events if e["kind"] == "separation"]
    assert max(sep_angle) - min(sep_angle) < 1e-6
    # the jump speed of case A lies between 1.75 and 7 rev/s
    j = camdyn.jump_speed(CASE_A)["jump_speed_rev_s"]
    assert 1.75 < j < 7.0


# ---- scenes: file, string, dict, overrides --------------------------------------------

def test_dict_scene_equals_toml_scene():
    with open(CASE_A, "rb") as f:
        d = tomllib.load(f)
    d["run"]["t_end"] = 0.05
    a = camdyn.run(CASE_A, **{"run.t_end": 0.05})
    b = camdyn.run(d)
    s = camdyn.run(pathlib.Path(CASE_A).read_text(), **{"run.t_end": 0.05})
    opts = [{k: v for k, v in x.summary["options"].items() if k != "source"} for x in (a, b, s)]
    assert opts[0] == opts[1] == opts[2]
    assert b.summary["options"]["source"] == "<dict>"
    assert s.summary["options"]["source"] == "<string>"
    for name in camdyn.history_columns:
        np.testing.assert_array_equal(a.history[name], b.history[name])
        np.testing.assert_array_equal(a.history[name], s.history[name])
    assert camdyn.resolved_scene(d) == camdyn.resolved_scene(CASE_A, **{"run.t_end": 0.05})


def test_overrides_in_either_order():
    """Overrides are validated once, after all are applied: output_dt ≤ t_end holds only
    at the end, whichever is given first."""
    o1 = {"run.t_end": 5e-7, "run.output_dt": 5e-7}
    o2 = {"run.output_dt": 5e-7, "run.t_end": 5e-7}
    assert list(o1) != list(o2)
    a = camdyn.run(CASE_A, **o1)
    b = camdyn.run(CASE_A, **o2)
    assert a.finished and b.finished
    assert a.summary["options"]["run"]["t_end"] == 5e-7
    assert a.summary["options"] == b.summary["options"]
    np.testing.assert_array_equal(a.history["t"], [0.0, 5e-7])
    # nested-dict overrides are the same as dotted ones
    assert camdyn.resolved_scene(CASE_A, run={"t_end": 5e-7, "output_dt": 5e-7}) == \
        camdyn.resolved_scene(CASE_A, **o1)


def test_cli_overrides_in_either_order_equal_bindings():
    for order in (("run.t_end=5e-7", "run.output_dt=5e-7"), ("run.output_dt=5e-7", "run.t_end=5e-7")):
        r = cli("scene", CASE_A, "--resolved", "--set", order[0], "--set", order[1])
        assert r.returncode == 0, r.stderr
        assert r.stdout == camdyn.resolved_scene(CASE_A, **{"run.t_end": 5e-7, "run.output_dt": 5e-7})


def test_resolved_scene_equals_cli():
    r = cli("scene", CASE_A, "--resolved", "--set", "cam.speed_rev_s=3")
    assert r.returncode == 0, r.stderr
    assert camdyn.resolved_scene(CASE_A, **{"cam.speed_rev_s": 3}) == r.stdout


# ---- errors: the CLI's message -----------------------------------------------------------

BAD_SCENES = {
    "unknown_key": 'title = "x"\n[spring]\nstifness = 500.0\n',
    "negative_stiffness": '[spring]\nstiffness = -1.0\n',
    "wrong_type": '[cam]\nspeed_rev_s = "fast"\n',
    "bad_enum": '[contact]\nmodel = "lagrange"\n',
    "non_convex_cam": '[cam]\nradii = [2.0, 2.0, 2.0, 0.5, 3.0, 2.1, 2.0, 2.0]\n',
    "toml_syntax": '[cam\nspeed_rev_s = 1\n',
}


@pytest.mark.parametrize("name", sorted(BAD_SCENES))
def test_bad_scene_file_raises_scene_error_with_cli_message(name, tmp_path):
    path = tmp_path / f"{name}.toml"
    path.write_text(BAD_SCENES[name])
    r = cli("run", str(path), "--out", str(tmp_path / "out"), "--quiet")
    assert r.returncode == 2, r.stderr
    assert r.stderr.startswith("camdyn: ")
    cli_message = r.stderr[len("camdyn: "):].rstrip("\n")
    with pytest.raises(camdyn.SceneError) as exc:
        camdyn.run(str(path))
    assert str(exc.value) == cli_message
    assert isinstance(exc.value, ValueError)


@pytest.mark.parametrize("key,value,cli_text", [
    ("contact.model", "lagrange", "lagrange"),
    ("spring.stiffness", -5.0, "-5.0"),
    ("cam.no_such_key", 1, "1"),
    ("nosuchtable.x", 1, "1"),
    ("run.output_dt", 2.0, "2.0"),
])
def test_bad_override_raises_scene_error_with_cli_message(key, value, cli_text, tmp_path):
    r = cli("run", CASE_A, "--set", f"{key}={cli_text}", "--out", str(tmp_path), "--quiet")
    assert r.returncode == 2, r.stderr
    cli_message = r.stderr[len("camdyn: "):].rstrip("\n")
    with pytest.raises(camdyn.SceneError) as exc:
        camdyn.run(CASE_A, **{key: value})
    assert str(exc.value) == cli_message
    assert exc.value.file == "--set"


def test_missing_file_raises_scene_error_with_cli_message(tmp_path):
    path = str(tmp_path / "nope.toml")
    r = cli("run", path, "--out", str(tmp_path / "out"), "--quiet")
    assert r.returncode == 2
    with pytest.raises(camdyn.SceneError) as exc:
        camdyn.run(path)
    assert str(exc.value) == r.stderr[len("camdyn: "):].rstrip("\n")


# ---- results: arrays, summary ------------------------------------------------------------

def test_history_shapes_and_dtypes():
    r = camdyn.run(CASE_A, **{"run.t_end": 0.01, "run.output_dt": 1e-3})
    assert list(r.history) == list(camdyn.history_columns)
    assert {"kinetic", "potential", "work_cam", "dissipated"} <= set(r.history)
    n = len(r.history["t"])
    assert n == 11
    for name, a in r.history.items():
        assert isinstance(a, np.ndarray), name
        assert a.dtype == np.float64 and a.ndim == 1 and a.shape == (n,), name
        assert np.all(np.isfinite(a)), name
    np.testing.assert_allclose(r.history["t"], np.arange(11) * 1e-3, rtol=0, atol=1e-15)


def test_summary_keys_equal_cli_summary_json(tmp_path):
    r = cli("run", CASE_A, "--set", "run.t_end=0.01", "--out", str(tmp_path), "--quiet")
    assert r.returncode == 0, r.stderr
    with open(tmp_path / "summary.json") as f:
        ref = json.load(f)
    res = camdyn.run(CASE_A, **{"run.t_end": 0.01})
    assert list(res.summary) == list(ref)
    assert res.summary["options"] == ref["options"]
    for k in ("finished", "message", "steps", "separations", "impacts", "max_contact_force"):
        assert res.summary[k] == ref[k], k
    # history.csv holds the same numbers (shortest round-trip text)
    data = np.genfromtxt(tmp_path / "history.csv", delimiter=",", names=True)
    for name in camdyn.history_columns:
        np.testing.assert_array_equal(res.history[name], data[name])


# ---- observers, stopping, signals --------------------------------------------------------

def test_observer_sees_every_row():
    rows = []
    r = camdyn.run(CASE_A, observer=rows.append, **{"run.t_end": 0.02})
    assert len(rows) == len(r.history["t"]) > 0
    assert list(rows[0]) == list(camdyn.history_columns)
    for name in camdyn.history_columns:
        np.testing.assert_array_equal(np.array([row[name] for row in rows]), r.history[name])
    assert all(type(v) is float for v in rows[-1].values())


def test_observer_returning_false_stops_the_run():
    seen = []

    def obs(row):
        seen.append(row["t"])
        return len(seen) < 10

    r = camdyn.run(CASE_A, observer=obs)
    assert r.summary["finished"] is False
    assert "stopped by caller" in r.summary["message"]
    assert 10 <= len(seen) == len(r.history["t"])
    assert r.summary["t_end"] < 0.01


def test_observer_exception_propagates():
    def obs(row):
        if row["t"] > 1e-3:
            raise RuntimeError("observer says no")

    with pytest.raises(RuntimeError, match="observer says no"):
        camdyn.run(CASE_A, observer=obs)


def test_keyboard_interrupt_stops_a_long_run():
    """SIGINT during a long run (case B2 for 1 s, ~15 s of CPU) raises KeyboardInterrupt
    within about the progress interval (0.2 s), with no observer."""
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    t0 = time.monotonic()
    try:
        with pytest.raises(KeyboardInterrupt):
            camdyn.run(None)
    finally:
        timer.cancel()
    assert time.monotonic() - t0 < 5.0


def test_version_and_columns():
    assert camdyn.__version__.count(".") == 2
    assert camdyn.history_columns[:8] == ("t", "theta", "u_c", "v_c", "a_c", "contact_force",
                                          "gap", "in_contact")
    assert issubclass(camdyn.SceneError, ValueError)


# ---- batches and sweeps ------------------------------------------------------------------

def test_sweep_separates_exactly_above_the_closed_form_jump_speed():
    """Case A over cam speeds around its closed-form jump speed: no separation below it,
    separations above it; 1 and 2 threads give the same results."""
    j = camdyn.jump_speed(CASE_A)["jump_speed_rev_s"]
    speeds = [0.5 * j, 0.9 * j, 0.99 * j, 1.01 * j, 1.1 * j]
    ov = {"run.t_end": 1.0 / j * 1.2}  # more than one revolution at every speed
    s2 = camdyn.sweep(CASE_A, "cam.speed_rev_s", speeds, threads=2, **ov)
    s1 = camdyn.sweep(CASE_A, "cam.speed_rev_s", speeds, threads=1, **ov)
    np.testing.assert_array_equal(s2["cam.speed_rev_s"], speeds)
    assert list(s2["finished"]) == [1.0] * 5
    assert list(s2["separations"] > 0) == [False, False, False, True, True]
    for c in camdyn.SWEEP_COLUMNS:
        if c != "cpu_seconds":
            np.testing.assert_array_equal(s1[c], s2[c], err_msg=c)
    # run_batch: the same summaries as run() one by one
    r = camdyn.run(CASE_A, **ov, **{"cam.speed_rev_s": speeds[3]})
    assert s2["summaries"][3]["options"] == r.summary["options"]
    assert s2["summaries"][3]["max_contact_force"] == r.summary["max_contact_force"]


def test_run_batch_checks_every_scene_first():
    with pytest.raises(camdyn.SceneError, match="spring.stiffness"):
        camdyn.run_batch([CASE_A, (CASE_A, {"spring.stiffness": -1.0})])


def test_gil_is_released_while_cpp_integrates():
    """Another Python thread keeps running in the middle of a run without observer."""
    stamps, stop = [], threading.Event()

    def tick():
        while not stop.is_set():
            stamps.append(time.monotonic())
            time.sleep(0.001)

    th = threading.Thread(target=tick)
    th.start()
    try:
        t0 = time.monotonic()
        camdyn.run(str(SRC / "examples" / "case_B2.toml"), **{"run.t_end": 0.03})
        t1 = time.monotonic()
    finally:
        stop.set()
        th.join()
    mid = [s for s in stamps if t0 + 0.25 * (t1 - t0) < s < t0 + 0.75 * (t1 - t0)]
    assert t1 - t0 > 0.02 and len(mid) > 0
