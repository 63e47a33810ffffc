"""Cost of a Python observer per history row (README "Python").

    PYTHONPATH=build/python python3 bench/python/observer_cost.py

Case A for 0.5 s with output_dt = 1e-6 (500 001 rows), best of 3, without an observer,
with a no-op observer and with one that reads row["t"]; prints the extra time per row.
"""
import time, camdyn, statistics
ov = {"run.t_end": 0.5, "run.output_dt": 1e-6}
def t(obs):
    t0 = time.perf_counter(); r = camdyn.run("examples/case_A.toml", observer=obs, **ov); return time.perf_counter() - t0, len(r.history["t"])
res = {"none": [], "noop": [], "count": []}
n_rows = 0
cnt = [0]
def count(row): cnt[0] += row["t"] > 0
for _ in range(3):
    for k, f in (("none", None), ("noop", lambda row: None), ("count", count)):
        dt, n_rows = t(f); res[k].append(dt)
m = {k: min(v) for k, v in res.items()}
print("rows", n_rows, {k: round(v, 3) for k, v in m.items()})
print("noop observer: %.2f us/row" % ((m["noop"] - m["none"]) / n_rows * 1e6))
print("observer reading row['t']: %.2f us/row" % ((m["count"] - m["none"]) / n_rows * 1e6))
