"""bench/headline_factors.py: the headline's pair of runs and its two factors, on a hand-made table.

Truth by hand: Lee's cheapest run under err_force 1e-3 is the 0.002 s one (100 steps), the
penalty's the 0.03 s one (1500 steps; a cheaper penalty run misses the target); CPU ratio 15 =
step ratio 15 x CPU-per-step ratio 1 (20 us per step both).
"""
import csv
import pathlib
import subprocess
import sys

SCRIPT = pathlib.Path(__file__).resolve().parents[2] / "bench" / "headline_factors.py"
COLS = ["scene", "method", "engine", "variant", "tol", "kp", "cp", "cpu_seconds", "steps", "rhs_evals",
        "err_force", "finished", "rejected_steps", "lin_setups", "nonlin_iters"]


def row(method, cpu, steps, err, finished="1", **kw):
    r = {c: "" for c in COLS}
    r.update(scene="X", method=method, engine="cvode-bdf", variant="-", tol="1e-06", cpu_seconds=str(cpu),
             steps=str(steps), rhs_evals=str(2 * steps), err_force=str(err), finished=finished,
             rejected_steps="0", lin_setups="1", nonlin_iters=str(steps))
    r.update(kw)
    return r


def write(tmp, ratio):
    d = tmp / "wp_A"
    d.mkdir()
    rows = [row("lee", 0.002, 100, 5e-4), row("lee", 0.001, 40, 2e-3),  # the second misses 1e-3
            row("penalty", 0.03, 1500, 9e-4, kp="1e8", cp="2e4"),
            row("penalty", 0.01, 500, 5e-3, kp="1e6", cp="2e3"),  # cheaper, misses the target
            row("penalty", 0.005, 100, 1e-4, finished="0"),  # not finished: ignored
            row("event", 0.004, 150, 1e-5)]
    with open(d / "work_precision.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLS)
        w.writeheader()
        w.writerows(rows)
    with open(d / "headlines.csv", "w", newline="") as f:
        f.write("scene,versus,target,ratio,goal,verdict,lee,other\n")
        f.write(f"A,penalty,0.001,{ratio},50,goal not met,x,y\nA,event,0.001,2,,no goal,x,y\n")


def test_factors_of_the_headline_pair(tmp_path):
    write(tmp_path, 15.0)
    out = subprocess.run([sys.executable, str(SCRIPT), "--dir", str(tmp_path)], capture_output=True,
                         text=True, check=True).stdout
    assert "CPU ratio 15 = steps 15× × CPU per step 1×" in out
    assert "Lee takes 15× fewer steps than penalty" in out
    assert "the same pair of runs" in out
    # event: 0.004 / 0.002 = 2 = steps 1.5 x per step 1.33
    assert "CPU ratio 2 = steps 1.5× × CPU per step 1.33×" in out
    assert "not the same pair" not in out


def test_a_different_headline_is_flagged(tmp_path):
    write(tmp_path, 7.0)
    out = subprocess.run([sys.executable, str(SCRIPT), "--dir", str(tmp_path)], capture_output=True,
                         text=True, check=True).stdout
    assert "**not the same pair of runs**" in out
