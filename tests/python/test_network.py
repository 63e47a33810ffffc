"""camdyn's Python bindings on follower networks (valve trains, issue 17): network scenes
from files, TOML text, dicts and camdyn.network_scene; the extra history columns, the
events' contact, the model description; the library's error messages.

Run by ctest (label "python") like test_camdyn.py.
"""

import json
import math
import os
import pathlib
import subprocess
import tomllib

import numpy as np
import pytest

import camdyn

SRC = pathlib.Path(os.environ.get("CAMDYN_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
CLI = os.environ.get("CAMDYN_CLI") or str(SRC / "build" / "camdyn")
OHC = SRC / "examples" / "ohc_bucket_tappet.toml"
OHV = SRC / "examples" / "ohv_pushrod_train.toml"


def cli(*args):
    if not os.access(CLI, os.X_OK):
        pytest.skip(f"camdyn CLI not found at {CLI} (set CAMDYN_CLI)")
    return subprocess.run([CLI, *args], capture_output=True, text=True, timeout=300)


# ---- (a) a valve bouncing on its seat: closed form --------------------------------------

M, K, P, X0, E = 0.05, 3e4, 300.0, 2e-3, 0.7


def valve_on_seat(**run):
    """One valve (mass M, lifted X0) on a spring to ground (k K, preload P) above a seat
    with restitution E; the cam stands still (no cam contact)."""
    return camdyn.network_scene(
        nodes=[camdyn.Node("valve", mass=M, initial_displacement=X0)],
        elements=[camdyn.Element("spring", ["valve", "ground"], name="valve_spring",
                                 stiffness=K, preload=P)],
        contacts=[camdyn.Contact("seat", "stop", ["valve"], side="below", restitution=E)],
        cam={"speed_rev_s": 0.0},
        contact={"model": "lee", "tol_u": 1e-10},
        solver={"rtol": 1e-9},
        run={"t_end": 0.003, "output_dt": 1e-5, **run},
        title="valve on its seat")


def test_valve_bouncing_on_its_seat_closed_form():
    """x = q + d (d = P/k) is harmonic, x(0) = x₀ + d at rest: the first impact (x = d) at
    t₁ = acos(d/(x₀+d))/ω with speed (x₀+d)ω sin(ωt₁); each impact returns e times the
    speed, and a flight that leaves the seat at speed v lands after 2·atan2(v/ω, d)/ω
    with speed v (no damping)."""
    r = camdyn.run(valve_on_seat())
    assert r.finished, r.summary["message"]
    w = math.sqrt(K / M)
    d = P / K
    t = [math.acos(d / (X0 + d)) / w]
    v = [(X0 + d) * w * math.sin(w * t[0])]
    for _ in range(2):
        v.append(E * v[-1])
        t.append(t[-1] + 2 * math.atan2(v[-1] / w, d) / w)
    impacts = [e for e in r.events if e["kind"] == "impact"]
    assert len(impacts) >= 3
    for e, ti, vi in zip(impacts, t, v):
        assert e["contact"] == "seat"
        assert e["impact_velocity"] == pytest.approx(vi, rel=1e-6)
        assert e["t"] == pytest.approx(ti, rel=1e-6)
        assert e["impulse"] == pytest.approx(M * (1 + E) * vi, rel=1e-6)
    # the valve never goes through its seat; F_seat is 0 in flight
    h = r.history
    assert np.all(h["u_valve"] >= -1e-9)
    assert h["u_valve"][0] == X0 and h["v_valve"][0] == 0.0
    np.testing.assert_array_equal(h["gap_seat"], h["u_valve"])  # g = q + clearance (0)
    flying = (h["t"] > 0) & (h["t"] < 0.99 * t[0])
    assert np.all(h["F_seat"][flying] == 0.0) and np.all(h["in_seat"][flying] == 0.0)


def test_network_scene_equals_the_toml_file_it_describes(tmp_path):
    sc = valve_on_seat()
    path = tmp_path / "valve.toml"
    path.write_text(camdyn.to_toml(sc))
    assert camdyn.resolved_scene(sc) == camdyn.resolved_scene(path)
    text = camdyn.resolved_scene(sc)
    assert text.count("[[nodes]]") == 1 and text.count("[[elements]]") == 1
    assert text.count("[[contacts]]") == 1
    # dicts and the dataclasses give the same scene
    d = camdyn.network_scene(
        nodes=[{"name": "valve", "mass": M, "initial_displacement": X0}],
        elements=[{"name": "valve_spring", "type": "spring", "nodes": ["valve", "ground"],
                   "stiffness": K, "preload": P}],
        contacts=[{"name": "seat", "type": "stop", "nodes": ["valve"], "side": "below",
                   "restitution": E}],
        cam={"speed_rev_s": 0.0}, contact={"model": "lee", "tol_u": 1e-10},
        solver={"rtol": 1e-9}, run={"t_end": 0.003, "output_dt": 1e-5},
        title="valve on its seat")
    assert d == sc


# ---- (b) the example files -------------------------------------------------------------

def test_ohc_example_columns_and_events():
    r = camdyn.run(OHC, **{"run.t_end": 0.02, "run.output_dt": 2e-4})  # half a revolution
    assert r.finished, r.summary["message"]
    n = len(r.history["t"])
    assert n == 101
    std = list(camdyn.history_columns)
    assert list(r.history)[:len(std)] == std
    extra = list(r.history)[len(std):]
    assert extra == ["F_cam", "gap_cam", "in_cam", "F_seat", "gap_seat", "in_seat",
                     "u_tappet", "v_tappet", "u_valve", "v_valve"]
    for name in ("F_cam", "F_seat", "u_valve"):
        a = r.history[name]
        assert isinstance(a, np.ndarray) and a.dtype == np.float64 and a.shape == (n,), name
        assert np.all(np.isfinite(a)), name
    # at rest on the base circle the seat carries the preload; the valve opens later
    assert r.history["F_seat"][0] == pytest.approx(250.0, rel=1e-9)
    assert r.history["u_valve"].max() > 7e-3  # 8 mm peak at 180° (t = 0.02 s)
    assert r.events and all(e["contact"] in ("cam", "seat") for e in r.events)
    net = r.summary["model"]["network"]
    assert any("valve_spring" in line for line in net)
    assert any(line.startswith("contact 'seat'") for line in net)


def test_observer_rows_have_the_extra_columns():
    rows = []
    r = camdyn.run(OHC, observer=rows.append, **{"run.t_end": 2e-3, "run.output_dt": 1e-4})
    assert len(rows) == len(r.history["t"])
    assert list(rows[0]) == list(r.history)
    np.testing.assert_array_equal([row["u_valve"] for row in rows], r.history["u_valve"])


def test_network_history_and_events_equal_cli(tmp_path):
    res = cli("run", str(OHV), "--set", "run.t_end=0.01", "--set", "run.output_dt=1e-4",
              "--out", str(tmp_path), "--quiet")
    assert res.returncode == 0, res.stderr
    r = camdyn.run(OHV, **{"run.t_end": 0.01, "run.output_dt": 1e-4})
    data = np.genfromtxt(tmp_path / "history.csv", delimiter=",", names=True)
    assert list(data.dtype.names) == list(r.history)
    for name in r.history:
        np.testing.assert_array_equal(r.history[name], data[name], err_msg=name)
    with open(tmp_path / "summary.json") as f:
        ref = json.load(f)
    assert list(r.summary) == list(ref)
    assert r.summary["model"] == ref["model"] and len(ref["model"]["network"]) == 7
    ev = (tmp_path / "events.csv").read_text().splitlines()
    assert ev[0].endswith(",contact")
    assert [line.rsplit(",", 1)[1] for line in ev[1:]] == [e["contact"] for e in r.events]


def test_dict_text_and_file_network_scenes_are_the_same():
    with open(OHV, "rb") as f:
        d = tomllib.load(f)
    assert isinstance(d["nodes"], list) and isinstance(d["nodes"][0], dict)
    over = {"run.t_end": 0.005, "run.output_dt": 1e-4}
    a = camdyn.run(OHV, **over)
    b = camdyn.run(d, **over)
    c = camdyn.run(camdyn.to_toml(d), **over)
    for x in (b, c):
        assert {k: v for k, v in x.summary["options"].items() if k != "source"} == \
            {k: v for k, v in a.summary["options"].items() if k != "source"}
        for name in a.history:
            np.testing.assert_array_equal(a.history[name], x.history[name], err_msg=name)
    assert camdyn.resolved_scene(d) == camdyn.resolved_scene(OHV)


def test_array_overrides_replace_the_whole_array():
    with open(OHC, "rb") as f:
        d = tomllib.load(f)
    contacts = [dict(c) for c in d["contacts"]]
    contacts[1]["restitution"] = 0.3
    from_dict = camdyn.resolved_scene(d, contacts=contacts)
    from_file = camdyn.resolved_scene(OHC, contacts=contacts)
    assert from_dict == from_file
    assert "restitution = 0.3" in from_file
    assert camdyn.resolved_scene(OHC) != from_file


# ---- (c) bad networks: the library's message -------------------------------------------

LEVER_0 = """
[follower]
kind = "network"

[[nodes]]
name = "a"
mass = 1.0

[[nodes]]
name = "b"

[[elements]]
type = "spring"
nodes = ["a", "ground"]
stiffness = 100.0

[[elements]]
name = "rocker"
type = "lever"
nodes = ["a", "b"]
ratio = 0

[[contacts]]
name = "cam"
type = "cam"
nodes = ["a"]
"""


def test_lever_ratio_zero_raises_with_the_library_message(tmp_path):
    path = tmp_path / "lever0.toml"
    path.write_text(LEVER_0)
    with pytest.raises(camdyn.SceneError) as exc:
        camdyn.run(path)
    assert "key 'elements[1].ratio' = 0: must be finite and > 0 (the output moves ratio times the input, in the same direction) (lever 'rocker')" in str(exc.value)
    res = cli("run", str(path), "--quiet", "--out", str(tmp_path / "out"))
    assert res.returncode != 0
    assert str(exc.value) == res.stderr[len("camdyn: "):].rstrip("\n")
    assert exc.value.key == "elements[1].ratio" and exc.value.value == "0"

    # the same network built in Python: same rule, source <dict>
    with pytest.raises(camdyn.SceneError) as exc2:
        camdyn.network_scene(
            nodes=[camdyn.Node("a", mass=1.0), camdyn.Node("b")],
            elements=[camdyn.Element("spring", ["a", "ground"], stiffness=100.0),
                      camdyn.Element("lever", ["a", "b"], name="rocker", ratio=0.0)],
            contacts=[camdyn.Contact("cam", "cam", ["a"])])
    assert str(exc2.value).startswith("<dict>:")
    assert str(exc2.value).endswith(
        "key 'elements[1].ratio' = 0: must be finite and > 0 (the output moves ratio times the input, in the same direction) (lever 'rocker')")
    assert isinstance(exc2.value, ValueError)


def test_whole_network_rules_raise_scene_error():
    with pytest.raises(camdyn.SceneError, match="node 'b' floats"):
        camdyn.network_scene(
            nodes=[camdyn.Node("a", mass=1.0), camdyn.Node("b", mass=1.0)],
            elements=[camdyn.Element("spring", ["a", "ground"], stiffness=100.0)],
            contacts=[camdyn.Contact("cam", "cam", ["a"]),
                      camdyn.Contact("lash", "lash", ["a", "b"])])
    # not validated until used
    sc = camdyn.network_scene(nodes=[camdyn.Node("a")], validate=False)
    with pytest.raises(camdyn.SceneError):
        camdyn.run(sc)
    with pytest.raises(TypeError):
        camdyn.network_scene(nodes=["a"])


def test_verdict_seat_bounce_in_python():
    """The verdict (issue 28) in Python's summary: the valve above released onto its seat
    (restitution E, nothing lifts it again) re-impacts after its first, closing, impact
    every time: one seat_bounce item counting every impact but the first."""
    r = camdyn.run(valve_on_seat())
    assert r.finished, r.summary["message"]
    impacts = [e for e in r.events if e["kind"] == "impact"]
    assert len(impacts) >= 3
    v = r.summary["verdict"]
    assert [x["kind"] for x in v] == ["seat_bounce"]
    assert v[0]["contact"] == "seat"
    assert v[0]["count"] == len(impacts) - 1
    assert v[0]["speed_rev_s"] == 0.0
    assert r.summary["verdict_text"].startswith("seat bounce: contact 'seat' at ")
