"""scripts/camdyn_report.py (issue 26) on the summary.json of other versions: per-contact
results ("contacts") and a "verdict" are shown when summary.json has them, and the page falls
back to the results computed from history.csv and events.csv when it has not.

Run by ctest (label "python") like test_camdyn.py; the browser check is report_browser_test.sh.
"""

import json
import os
import pathlib
import shutil
import subprocess
import sys

import pytest

SRC = pathlib.Path(os.environ.get("CAMDYN_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
CLI = os.environ.get("CAMDYN_CLI") or str(SRC / "build" / "camdyn")
REPORT = SRC / "scripts" / "camdyn_report.py"


@pytest.fixture(scope="module")
def ohc_run(tmp_path_factory):
    if not os.access(CLI, os.X_OK):
        pytest.skip(f"camdyn CLI not found at {CLI} (set CAMDYN_CLI)")
    pytest.importorskip("matplotlib")
    d = tmp_path_factory.mktemp("report") / "run"
    r = subprocess.run([CLI, "run", str(SRC / "examples" / "ohc_bucket_tappet.toml"), "--out", str(d),
                        "--quiet"], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    return d


def report(d, *args):
    r = subprocess.run([sys.executable, str(REPORT), str(d), "--quiet", *args], capture_output=True,
                       text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    return (d / "report.html").read_text(encoding="utf-8")


def test_falls_back_to_the_files_without_per_contact_results(ohc_run, tmp_path):
    # a run directory whose summary.json has no per-contact results (written before issue 28)
    d = tmp_path / "old_run"
    shutil.copytree(ohc_run, d)
    s = json.loads((d / "summary.json").read_text())
    s.pop("contacts", None)
    s.pop("verdict", None)
    (d / "summary.json").write_text(json.dumps(s))
    page = report(d)
    ohc_run = d
    assert "Verdict" not in page
    assert "<h2>Results per contact</h2>" in page
    # the two contacts of the scene, and the seat closing once (events.csv: 1 seat impact)
    events = (ohc_run / "events.csv").read_text().splitlines()[1:]
    seat_impacts = sum(1 for e in events if e.split(",")[1] == "impact" and e.split(",")[5] == "seat")
    assert "<b>cam</b>:" in page and "<b>seat</b>:" in page
    assert f"; {seat_impacts} impact{'s' if seat_impacts != 1 else ''}, the largest" in page
    assert page.count("<img src='data:image/png;base64,") == 5


def test_shows_per_contact_results_and_verdict_when_present(ohc_run, tmp_path):
    d = tmp_path / "run"
    shutil.copytree(ohc_run, d)
    s = json.loads((d / "summary.json").read_text())
    s["verdict"] = "the valve floats from 152.6° cam at 48 rev/s"
    s["contacts"] = [{"name": "cam", "min_force_closed": 316.25, "impacts": 1},
                     {"name": "seat", "max_impact_velocity": 2.04, "max_impact_theta_deg": 238.0}]
    (d / "summary.json").write_text(json.dumps(s))
    page = report(d, "--reuse")
    assert "<b>Verdict:</b> the valve floats from 152.6° cam at 48 rev/s" in page
    assert "Results per contact (summary.json)" in page
    assert "<td>seat</td>" in page and "<td>2.04</td>" in page and "<td>316.25</td>" in page
    # an object verdict: its text, then its other fields
    s["verdict"] = {"text": "seat bounce", "class": "seat_bounce", "theta_deg": 276.0}
    (d / "summary.json").write_text(json.dumps(s))
    page = report(d, "--reuse")
    assert "<b>Verdict:</b> seat bounce" in page and "seat_bounce" in page


def test_shows_the_order_spectra_camdyn_spectrum_wrote(ohc_run, tmp_path):
    # issue 38 item 4: `camdyn spectrum DIR --column NAME` and in the report. The OHC cam
    # force's largest order is 1 (one lift per revolution); the table lists what the CSV says.
    d = tmp_path / "run"
    shutil.copytree(ohc_run, d)
    r = subprocess.run([CLI, "spectrum", str(d), "--column", "F_cam"], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    rows = [line.split(",") for line in (d / "spectrum_F_cam.csv").read_text().splitlines()[1:]]
    top = max((float(a), float(o)) for o, a, _ in rows if float(o) > 0)
    page = report(d)
    assert "<h2>Order spectra</h2>" in page
    assert "<td>F_cam</td>" in page
    assert page.index("largest orders") < page.index("%.4g: " % top[1])
