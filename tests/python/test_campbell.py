"""camdyn.campbell (camdyn/campbell.hpp) from Python: the eccentric cam's one order against
its closed form |m e ω² − k e|, the surge lines of a coil-mass spring, bad options named."""
import math
import os

import pytest

import camdyn

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")


def test_eccentric_cam_order_one_is_the_closed_form():
    d = camdyn.campbell(os.path.join(ROOT, "examples", "circle_cam.toml"), [1.0, 2.0], settle_revolutions=0,
                        revolutions=1, samples_per_revolution=128, max_order=4, threads=1,
                        **{"contact.model": "event", "solver.rtol": 1e-10, "solver.atol": 1e-12})
    j = d["order"].index(1.0)
    for v, amp in zip(d["speed_rev_s"], d["amplitude"]):
        w = 2 * math.pi * v
        exact = abs(1.0 * 0.5 * w * w - 500.0 * 0.5)
        assert amp[j] == pytest.approx(exact, rel=1e-12)
    assert d["lines"] == []


def test_surge_lines_of_the_ohc_valve_spring():
    d = camdyn.campbell(os.path.join(ROOT, "examples", "ohc_bucket_tappet.toml"), [20.0, 25.0],
                        column="F_cam", settle_revolutions=0, revolutions=1, samples_per_revolution=64,
                        max_order=8, threads=2)
    names = [l["name"] for l in d["lines"]]
    assert names[0] == "valve_spring surge 1"
    # 6 coil masses: the chain's closed form ((N+1)/π)√(k/m_s) sin(π/(2(N+1)))
    k, ms, n = 35000.0, 0.030, 6
    f1 = (n + 1) / math.pi * math.sqrt(k / ms) * math.sin(math.pi / (2 * (n + 1)))
    assert d["lines"][0]["frequency_hz"] == pytest.approx(f1, rel=1e-9)


def test_bad_option_is_named():
    with pytest.raises(camdyn.SceneError) as e:
        camdyn.campbell(os.path.join(ROOT, "examples", "circle_cam.toml"), [2.0, 1.0])
    assert e.value.key == "speeds_rev_s"
