"""Figures of a valve train from the CLI (issue 28): `camdyn run --plot` on a network scene
writes network_motion.png (lift and every node against cam angle) and network_forces.png
(every contact's force, impacts marked), and the dashed cam curve is the cam's input to its
node: lift − clearance (scripts/camdyn_plot.py cam_curves), not u_c + gap.

Independent truths for the curve: on the base circle (the OHC table's lift is exactly 0 from
0° to 60°) it is −clearance; while the cam contact is closed (in_cam = 1, gap 0 to tol_u)
the tappet rides the cam, so the curve equals the tappet's displacement u_tappet; at the
peak (180°) it is the table's 8 mm minus the clearance.
"""

import math
import os
import pathlib
import subprocess

import numpy as np

import pytest

SRC = pathlib.Path(os.environ.get("CAMDYN_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
CLI = os.environ.get("CAMDYN_CLI") or str(SRC / "build" / "camdyn")
CLEARANCE = 0.0002  # the OHC example's cam contact


@pytest.fixture(scope="module")
def ohc_plot_run(tmp_path_factory, plot_module):
    if not os.access(CLI, os.X_OK):
        pytest.skip(f"camdyn CLI not found at {CLI} (set CAMDYN_CLI)")
    d = tmp_path_factory.mktemp("train") / "run"
    r = subprocess.run([CLI, "run", str(SRC / "examples" / "ohc_bucket_tappet.toml"), "--out", str(d),
                        "--set", "run.output_dt=1e-5", "--plot", "--quiet"],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    return d


def test_network_figures_written(ohc_plot_run):
    for name in ("network_motion.png", "network_forces.png"):
        p = ohc_plot_run / name
        assert p.is_file(), name
        assert p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", name
        assert p.stat().st_size > 10000, name  # a drawn figure, not an empty canvas


def test_cam_curve_is_lift_minus_clearance(ohc_plot_run, plot_module):
    cp = plot_module
    _, c = cp.read_csv(str(ohc_plot_run / "history.csv"))
    clear = cp.cam_contact_clearances(str(ohc_plot_run))
    assert clear == [("cam", CLEARANCE)]
    curves = cp.cam_curves(c, clear)
    assert len(curves) == 1
    curve = curves[0][1]
    deg = c["theta"] * 180.0 / math.pi
    base = deg < 59.0
    assert base.sum() > 100
    # −clearance on the base circle (the lift table's spline ripples by < 1e-8 m before the ramp)
    assert abs(curve[base] + CLEARANCE).max() < 1e-8
    held = c["in_cam"] > 0.5
    assert held.sum() > 1000
    assert abs(curve[held] - c["u_tappet"][held]).max() < 1e-8  # the tappet rides the cam (tol_u 1e-9)
    i = int(abs(deg - 180.0).argmin())
    assert abs(curve[i] - (0.008 - CLEARANCE)) < 1e-6


def test_cam_of_a_single_follower_history_is_u_minus_gap(tmp_path, plot_module):
    """displacement.png's dashed cam: X_C = u_c − gap (it was drawn as u_c + gap). The
    eccentric circle cam with a flat follower has X_C = R + e cos θ (R 2, e 0.5); at 16 rev/s
    the follower leaves it (event method), so the gap is open on many rows."""
    if not os.access(CLI, os.X_OK):
        pytest.skip(f"camdyn CLI not found at {CLI} (set CAMDYN_CLI)")
    d = tmp_path / "circle"
    r = subprocess.run([CLI, "run", str(SRC / "examples" / "circle_cam.toml"), "--out", str(d), "--set",
                        "cam.speed_rev_s=16", "--set", "contact.model=event", "--plot", "--quiet"],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    assert (d / "displacement.png").is_file()
    _, c = plot_module.read_csv(str(d / "history.csv"))
    apart = c["gap"] > 0.01
    assert apart.sum() > 100
    X = 2.0 + 0.5 * np.cos(c["theta"])
    assert abs(plot_module.cam_of_history(c) - X).max() < 1e-9
