"""Network entries addressed by name as Python overrides and sweep keys (issue 26): the
same scene, history and events as the change written into the TOML text.

Run by ctest (label "python") like test_camdyn.py.
"""

import os
import pathlib

import numpy as np
import pytest

import camdyn

SRC = pathlib.Path(os.environ.get("CAMDYN_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
OHC = SRC / "examples" / "ohc_bucket_tappet.toml"
SHORT = {"run.t_end": 0.02}


def edited(what, with_):
    text = OHC.read_text()
    assert what in text
    return text.replace(what, with_, 1)


def same_run(a, b):
    assert a.history.keys() == b.history.keys()
    for k in a.history:
        assert np.array_equal(a.history[k], b.history[k], equal_nan=True), k
    assert a.events == b.events


def test_override_by_name_equals_the_edited_file():
    text = edited('side = "below"', 'side = "below"\nrestitution = 0.3')
    by_file = camdyn.run(text)
    by_key = camdyn.run(str(OHC), **{"contacts.seat.restitution": 0.3})
    by_dict = camdyn.run(str(OHC), contacts={"seat": {"restitution": 0.3}})
    by_index = camdyn.run(str(OHC), **{"contacts[1].restitution": 0.3})
    same_run(by_key, by_file)
    same_run(by_dict, by_file)
    same_run(by_index, by_file)
    original = camdyn.run(str(OHC))
    seat = lambda r: sum(1 for e in r.events if e["contact"] == "seat" and e["kind"] == "impact")
    assert seat(by_key) > seat(original)  # the valve now bounces on its seat


def test_sweep_over_a_valve_spring_preload():
    s = camdyn.sweep(str(OHC), "elements.valve_spring.preload", [150.0, 350.0], threads=2, **SHORT)
    for i, p in enumerate((150, 350)):
        r = camdyn.run(edited("preload = 250.0", f"preload = {p}.0"), **SHORT)
        assert s["max_contact_force"][i] == r.summary["max_contact_force"]
        assert s["steps"][i] == r.summary["steps"]
    assert s["max_contact_force"][0] != s["max_contact_force"][1]


@pytest.mark.parametrize("key,message", [
    ("contacts.sat.restitution",
     "--set: key 'contacts.sat.restitution' = 0.3: no [[contacts]] entry named 'sat'; "
     "[[contacts]] has 2 entries: cam, seat"),
    ("contacts[2].restitution",
     "--set: key 'contacts[2].restitution' = 0.3: index 2 out of range; [[contacts]] has 2 entries: cam, seat"),
    ("nodes.valve.preload",
     "--set: key 'nodes.valve.preload' = 0.3: unknown key; allowed keys of a node: name, mass, "
     "initial_displacement, initial_velocity"),
])
def test_bad_network_keys(key, message):
    with pytest.raises(camdyn.SceneError) as e:
        camdyn.resolved_scene(str(OHC), **{key: 0.3})
    assert str(e.value) == message
