"""summary.json's Newton statistics of the implicit engines: nonlin_iters, nonlin_conv_fails,
err_test_fails (SUNDIALS' own counters, summed over restarts).

Checked against what each integrator must do per step, not against earlier output:
CVODE's BDF and IDA solve one nonlinear system per attempted step (≥ 1 Newton iteration
each); ARKODE's SDIRK 5(3)4 solves one per implicit stage, five per attempted step; the
explicit engine has none. An attempted step is an accepted or a failed one, so
nonlin_iters ≥ per_step · steps in every case.
"""
import pathlib

import pytest

camdyn = pytest.importorskip("camdyn")

ROOT = pathlib.Path(__file__).resolve().parents[2]
STIFF = str(ROOT / "examples" / "stiff_bar.toml")
CASE_A = str(ROOT / "examples" / "case_A.toml")
KEYS = ("nonlin_iters", "nonlin_conv_fails", "err_test_fails")


def run(scene, **sets):
    r = camdyn.run(scene, **sets)
    s = r.summary
    assert s["finished"], s["message"]
    for k in KEYS:
        assert k in s and s[k] >= 0
    return s


def test_cvode_bdf_one_newton_iteration_per_step_at_least():
    # the stiff bar's penalty run (measured: 1.04 iterations per step, no convergence failure)
    s = run(STIFF, **{"contact.model": "penalty", "contact.penalty_stiffness": 1e7,
                      "contact.penalty_damping": 632.0, "solver.integrator": "cvode-bdf",
                      "solver.rtol": 1e-3, "run.t_end": 0.002})
    assert s["steps"] > 10
    assert s["nonlin_iters"] >= s["steps"]
    # the exact contact Jacobian: Newton converges at once; more than 3 per step would mean
    # it limits the step (the check of docs/bench/generated/newton_stiff.md)
    assert s["nonlin_iters"] <= 3 * (s["steps"] + s["nonlin_conv_fails"] + s["err_test_fails"])
    assert s["nonlin_conv_fails"] == 0


def test_arkode_dirk_five_stages_per_step():
    s = run(CASE_A, **{"contact.model": "penalty", "solver.integrator": "arkode-dirk",
                       "solver.rtol": 1e-6, "run.t_end": 0.1})
    assert s["steps"] > 10
    assert s["nonlin_iters"] >= 5 * s["steps"]


def test_ida_one_newton_iteration_per_step_at_least():
    s = run(CASE_A, **{"contact.model": "holonomic", "solver.integrator": "ida",
                       "solver.rtol": 1e-6, "run.t_end": 0.1})
    assert s["steps"] > 10
    assert s["nonlin_iters"] >= s["steps"]


def test_explicit_engine_has_no_newton():
    s = run(CASE_A, **{"contact.model": "lee", "solver.integrator": "arkode-erk", "run.t_end": 0.1})
    assert (s["nonlin_iters"], s["nonlin_conv_fails"], s["err_test_fails"]) == (0, 0, 0)
