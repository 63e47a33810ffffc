"""The speed-range map and order spectra from Python (issue 38; docs/guide/sweeps.md)."""
import math
import os
import pathlib

import pytest

import camdyn

SRC = pathlib.Path(os.environ.get("CAMDYN_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


def test_order_spectrum_recovers_known_sinusoids():
    """y = 1 + 0.5 cos(3φ) + 0.2 cos(8φ + 0.4) over 3 revolutions, sampled on the resampling
    grid: the amplitudes come back to 1e-9 (measured ≈ 1e-14)."""
    n = 256
    th = [2 * math.pi * i / n for i in range(3 * n + 1)]
    y = [1 + 0.5 * math.cos(3 * p) + 0.2 * math.cos(8 * p + 0.4) for p in th]
    s = camdyn.order_spectrum(th, y, samples_per_revolution=n, max_order=10)
    assert s["revolutions"] == 3
    want = {0.0: 1.0, 3.0: 0.5, 8.0: 0.2}
    for o, a in zip(s["order"], s["amplitude"]):
        assert abs(a - want.get(o, 0.0)) < 1e-9, (o, a)
    with pytest.raises(camdyn.SceneError):
        camdyn.order_spectrum([0.0, 1.0], [1.0, 2.0])  # less than one revolution


def test_jump_map_returns_bands_and_trials():
    """The OHC example's map over 60–75 rev/s on 4 trial speeds, coarse (rel_tol 0.05): the
    dict carries the bands and trials, the lowest separation speed lies in its bracket, and
    each band's ends are trial speeds of the map."""
    ohc = str(SRC / "examples" / "ohc_bucket_tappet.toml")
    j = camdyn.jump_speed(ohc, {"lo_rev_s": 60.0, "hi_rev_s": 75.0, "grid_points": 4, "jobs": 2,
                                "rel_tol": 0.05})
    assert j["method"] == "simulation"
    assert j["grid_simulations"] == 4 and j["simulations"] >= 4
    assert j["lo_rev_s"] <= j["jump_speed_rev_s"] <= j["hi_rev_s"]
    speeds = {t["speed_rev_s"] for t in j["trials"]}
    for b in j["bands"]:
        assert b["from_in_rev_s"] in speeds and b["to_in_rev_s"] in speeds
        assert b["kind"] in ("opening_liftoff", "nose_float", "closing_bounce", "seat_bounce")
    assert "lowest separation speed" in j["text"]
    with pytest.raises(camdyn.SceneError):
        camdyn.jump_speed(ohc, {"grid_points": 1})
