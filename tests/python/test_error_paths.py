"""Python's error paths (issue 35): bad arguments are camdyn.SceneError (naming the key and
the rule) or TypeError, never a run of something else, a pybind11 dump or an unrelated
Python error; Ctrl-C stops a run on any engine promptly.

    PYTHONPATH=build/python /usr/bin/python3 -m pytest -q tests/python/test_error_paths.py
"""

import os
import pathlib
import signal
import threading
import time

import pytest

import camdyn

SRC = pathlib.Path(os.environ.get("CAMDYN_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
CASE_A = str(SRC / "examples" / "case_A.toml")
OHC = str(SRC / "examples" / "ohc_bucket_tappet.toml")


def test_empty_scene_string_is_refused_not_the_default_scene():
    # Was: camdyn.run('') ran the built-in default scene.
    for s in ("", "   ", "\n"):
        with pytest.raises(camdyn.SceneError) as e:
            camdyn.run(s)
        assert e.value.key == "scene"
        assert "is empty" in e.value.rule


def test_path_with_nul_is_refused():
    # Was: the file before the NUL ran.
    with pytest.raises(camdyn.SceneError) as e:
        camdyn.run(CASE_A + "\0junk")
    assert e.value.key == "scene"
    assert "NUL" in e.value.rule


def test_lone_surrogate_is_refused_with_the_key():
    # Was: a pybind11 conversion dump.
    with pytest.raises(camdyn.SceneError) as e:
        camdyn.run(CASE_A + "\udc80")
    assert e.value.key == "scene" and "surrogate" in e.value.rule
    with pytest.raises(camdyn.SceneError) as e:
        camdyn.run(CASE_A, **{"title": "x\udc80"})
    assert e.value.key == "title" and "surrogate" in e.value.rule


def test_array_override_of_the_wrong_type_is_a_type_error():
    # Was: "'int' object is not iterable".
    with pytest.raises(TypeError) as e:
        camdyn.run(OHC, contacts=5)
    assert "contacts=5" in str(e.value) and "must be a list" in str(e.value)


def test_set_repairs_a_file_that_is_invalid_alone(tmp_path):
    # One validation after the overrides, as the CLI: the file alone breaks a rule.
    f = tmp_path / "s.toml"
    text = open(CASE_A).read()
    assert "output_dt = 1e-4" in text
    f.write_text(text.replace("output_dt = 1e-4", "output_dt = 10.0"))  # > t_end = 1
    with pytest.raises(camdyn.SceneError):
        camdyn.run(str(f))
    r = camdyn.run(str(f), **{"run.output_dt": 1e-3, "run.t_end": 0.01})
    assert r.summary["finished"]


def test_ctrl_c_stops_ida_at_tight_tolerance_promptly():
    # Was: seen only from the progress callback (31.8 s late, or never with a coarse output
    # grid). A SIGINT 0.5 s into a long ida run at rtol 1e-12 with one output row at the
    # end: KeyboardInterrupt within 2 s of the signal.
    # Python's own SIGINT handler (a test runner started in the background inherits SIGINT
    # ignored, and Python then installs none).
    signal.signal(signal.SIGINT, signal.default_int_handler)
    pid = os.getpid()
    sent = []

    def interrupt():
        time.sleep(0.5)
        sent.append(time.monotonic())
        os.kill(pid, signal.SIGINT)

    t = threading.Thread(target=interrupt)
    t.start()
    with pytest.raises(KeyboardInterrupt):
        camdyn.run(CASE_A, **{"contact.model": "holonomic", "solver.integrator": "ida",
                              "solver.rtol": 1e-12, "run.t_end": 5000.0, "run.output_dt": 5000.0})
    late = time.monotonic() - sent[0]
    t.join()
    assert late < 2.0, late


def test_resolved_scene_refuses_what_run_refuses():
    # One validation: a scene that only the run's start checks refuse (here a tolerance
    # larger than 1 % of the cam's lift) is refused by resolved_scene too, with the same key.
    with pytest.raises(camdyn.SceneError) as a:
        camdyn.resolved_scene(OHC, **{"contact.tol_u": 1})
    with pytest.raises(camdyn.SceneError) as b:
        camdyn.run(OHC, **{"contact.tol_u": 1})
    assert a.value.key == b.value.key == "contact.tol_u"
    assert str(a.value) == str(b.value)


@pytest.mark.parametrize("model", ["event", "lee", "penalty"])
def test_non_finite_follower_force_is_named(model):
    # Was: "step size underflow at t = 0.002" without naming the force. Lee's located step
    # still halves its step toward the force's discontinuity (a trial may fail for a reason
    # a smaller step removes) and ends in a step size underflow, which now names the last
    # failed trial's cause.
    class NanAfter:
        size = 1
        contacts = [camdyn.FollowerContact(name="cam", row=[1.0])]
        mass = 0.1

        def force(self, t, q, v):
            return [float("nan") if t > 0.002 else -(150.0 + 2e4 * q[0])]

    s = {"title": "nan force", "cam": {"profile": "circle", "radius": 0.02, "eccentricity": 0.004, "theta0_deg": 180.0,
                                        "speed_rev_s": 5.0},
         "contact": {"model": model}, "run": {"t_end": 0.01, "output_dt": 1e-3}}
    r = camdyn.run(s, follower=NanAfter())
    assert not r.summary["finished"]
    msg = r.summary["message"]
    assert "non-finite" in msg and "force" in msg, msg
    assert "[ARKODE" not in msg
