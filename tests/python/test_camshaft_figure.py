"""The camshaft figure of `camdyn plot` (issue 40 item 4): a [camshaft] run's DIR/camshaft.png,
the drive torque and every cam's wind-up against the cam angle θ(t) [cam] prescribes
(scripts/camdyn_plot.py camshaft_curves). Independent truths for the curves: the crank's angle
is θ(t) plus its 4th-order fluctuation of 0.2°, so θ − drive_twist is the drive station's angle
u_shaft_0 up to those 0.2°; each cam's wind-up is the drive station's angle − its station's angle (u_shaft_<s>), in mrad;
the example's cams 0 and 1 sit on station 1, cams 6 and 7 on station 4.
"""

import math
import os
import pathlib
import subprocess

import numpy as np

import pytest

SRC = pathlib.Path(os.environ.get("CAMDYN_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
CLI = os.environ.get("CAMDYN_CLI") or str(SRC / "build" / "camdyn")


@pytest.fixture(scope="module")
def i4_run(tmp_path_factory, plot_module):
    if not os.access(CLI, os.X_OK):
        pytest.skip(f"camdyn CLI not found at {CLI} (set CAMDYN_CLI)")
    d = tmp_path_factory.mktemp("camshaft") / "run"
    r = subprocess.run([CLI, "run", str(SRC / "examples" / "i4_dohc_intake_camshaft.toml"), "--out", str(d),
                        "--set", "run.t_end=0.01", "--quiet"],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    _, c = plot_module.read_csv(str(d / "history.csv"))
    plot_module.plot_camshaft(str(d), c)  # what `camdyn plot` draws for a history with drive_torque
    return d


def test_camshaft_figure_written(i4_run):
    p = i4_run / "camshaft.png"
    assert p.is_file()
    assert p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert p.stat().st_size > 10000  # a drawn figure, not an empty canvas


def test_camshaft_curves_are_the_stations_angles(i4_run, plot_module):
    _, c = plot_module.read_csv(str(i4_run / "history.csv"))
    deg, torque, windups = plot_module.camshaft_curves(c)
    assert abs(deg - np.degrees(c["theta"])).max() == 0.0
    fluct = 0.2 * np.sin(4.0 * c["theta"])  # the example's crank order 4, 0.2°, phase 0
    assert abs(np.degrees(c["theta"] - c["drive_twist"]) + fluct - np.degrees(c["u_shaft_0"])).max() < 1e-9
    assert [n for n, _ in windups] == ["cam%d" % i for i in range(8)]
    for name, station in (("cam0", 1), ("cam1", 1), ("cam6", 4), ("cam7", 4)):
        w = dict(windups)[name]
        assert abs(w - 1e3 * (c["u_shaft_0"] - c["u_shaft_%d" % station])).max() < 1e-9
    assert abs(torque).max() > 0.1  # the valve springs load the drive


def test_camshaft_report_section(i4_run, plot_module):
    """camdyn report's Camshaft section states the drive torque's range and each cam's largest
    wind-up as the history has them, and the frequencies with the trains attached."""
    import importlib.util as iu
    import json
    import sys

    sys.path.insert(0, str(SRC / "scripts"))
    spec = iu.spec_from_file_location("camdyn_report", SRC / "scripts" / "camdyn_report.py")
    rep = iu.module_from_spec(spec)
    spec.loader.exec_module(rep)
    _, c = plot_module.read_csv(str(i4_run / "history.csv"))
    s = json.load(open(i4_run / "summary.json"))
    h = rep.camshaft_html(s, c)
    assert "<h2>Camshaft</h2>" in h
    assert "drive torque %s … %s" % (rep.fmt(float(c["drive_torque"].min())), rep.fmt(float(c["drive_torque"].max()))) in h
    w = c["windup_cam7"]
    assert "cam7: largest wind-up %s mrad" % rep.fmt(1e3 * float(w[int(np.argmax(np.abs(w)))])) in h
    assert "natural frequencies with the trains attached" in h
    assert rep.camshaft_html(s, {"theta": c["theta"]}) == ""


def test_valve_timing_panel_and_table(i4_run, plot_module):
    """The timing panel of camshaft.png draws summary.json's valve_timing (camdyn_plot.py
    valve_timing_bars), one valve per train (the seat's node), and the report tabulates it.
    Independent truths for the kinematic angles: every cam has the example's lift table, its
    trains 0.2 mm of lash and a stiff stem, so each valve is open above 1 % of 7.8 mm, where the
    cam lifts 0.278 mm: between the table's knots at 90° (0.2689 mm) and 93° (0.2878 mm) on the
    opening ramp, and (the lobe is symmetric about 180°) at 360° − that on the closing ramp."""
    import importlib.util as iu
    import json

    s = json.load(open(i4_run / "summary.json"))
    names, opening, closing = plot_module.valve_timing_bars(s)
    assert names == ["valve%d%s" % (i, ab) for i in (1, 2, 3, 4) for ab in "ab"]
    rows = s["valve_timing"]
    for r, o, c in zip(rows, opening, closing):
        assert abs(r["threshold"] - 0.01 * (0.008 - 0.0002)) < 1e-12
        assert 90.0 < r["kinematic_opening_deg"] < 93.0
        assert abs(r["kinematic_opening_deg"] + r["kinematic_closing_deg"] - 360.0) < 1e-6
        for got, key in ((o, "opening_error_deg"), (c, "closing_error_deg")):
            assert (math.isnan(got) and r[key] is None) or got == r[key]
    assert plot_module.valve_timing_bars({}) == ([], [], [])
    fig_before = (i4_run / "camshaft.png").stat().st_size
    plot_module.plot_camshaft(str(i4_run), plot_module.read_csv(str(i4_run / "history.csv"))[1], summary={})
    assert (i4_run / "camshaft.png").stat().st_size < fig_before  # two panels without valve_timing
    plot_module.plot_camshaft(str(i4_run), plot_module.read_csv(str(i4_run / "history.csv"))[1])
    spec = iu.spec_from_file_location("camdyn_report", SRC / "scripts" / "camdyn_report.py")
    rep = iu.module_from_spec(spec)
    spec.loader.exec_module(rep)
    h = rep.valve_timing_html(s)
    assert "<h3>Valve timing</h3>" in h and h.count("<tr>") == 1 + len(rows)
    assert rep.fmt(rows[0]["kinematic_opening_deg"], 5) + "°" in h
    assert rep.valve_timing_html({}) == ""
