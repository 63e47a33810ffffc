"""scripts/bench_rows_equal.py: two bench outputs are equal when only the clock differs."""
import pathlib
import subprocess
import sys

SCRIPT = pathlib.Path(__file__).resolve().parents[2] / "scripts" / "bench_rows_equal.py"
HEAD = "scene,method,engine,variant,tol,kp,cp,cpu_seconds,steps,err_u,note\n"


def check(tmp_path, a, b):
    pa, pb = tmp_path / "a.csv", tmp_path / "b.csv"
    pa.write_text(HEAD + a)
    pb.write_text(HEAD + b)
    r = subprocess.run([sys.executable, str(SCRIPT), str(pa), str(pb)], capture_output=True, text=True)
    return r.returncode, r.stdout


def test_timings_and_cache_notes_aside(tmp_path):
    rc, out = check(tmp_path,
                    "A,lee,arkode-erk,-,1e-05,,,0.0031,425,1e-15,\n"
                    "A,reference-check,arkode-erk,event,1e-11,,,0.01,1805,8e-16,ref cpu 0.109 s\n"
                    "B,penalty,cvode-bdf,linear,1e-06,1e6,2e3,6.2,57521,1e-4,timed once (> 5 s)\n",
                    "A,lee,arkode-erk,-,1e-05,,,0.0047,425,1e-15,\n"
                    "A,reference-check,arkode-erk,event,1e-11,,,0.02,1805,8e-16,ref cpu 0.2 s; from the cache\n"
                    "B,penalty,cvode-bdf,linear,1e-06,1e6,2e3,4.9,57521,1e-4,\n")
    assert rc == 0, out


def test_a_changed_result_fails(tmp_path):
    rc, out = check(tmp_path, "A,lee,arkode-erk,-,1e-05,,,0.003,425,1e-15,\n",
                    "A,lee,arkode-erk,-,1e-05,,,0.003,426,1e-15,\n")
    assert rc == 1 and "steps" in out
    rc, out = check(tmp_path, "A,lee,arkode-erk,-,1e-05,,,0.003,425,1e-15,\n",
                    "A,lee,arkode-erk,-,1e-06,,,0.003,425,1e-15,\n")
    assert rc == 1 and "only in" in out


def test_budget_stops_are_listed_not_failed(tmp_path):
    rc, out = check(tmp_path,
                    "S,lee,arkode-erk,-,1e-08,,,20.1,9000,1e-6,stopped: over the 20 s CPU budget at t = 0.01\n",
                    "S,lee,arkode-erk,-,1e-08,,,19.0,12000,1e-7,\n")
    assert rc == 0 and "budget-dependent" in out


def test_rows_skipped_after_a_budget_stop_are_listed_not_failed(tmp_path):
    rc, out = check(tmp_path,
                    "S,penalty,arkode-dirk,linear critical,1e-07,1e10,2e3,,0,,skipped: penalty arkode-dirk linear critical 1e+10 at rtol 1e-06 took over 10 s\n",
                    "S,penalty,arkode-dirk,linear critical,1e-07,1e10,2e3,8.1,90000,1e-6,\n")
    assert rc == 0 and "budget-dependent" in out
