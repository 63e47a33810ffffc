#!/usr/bin/env python3
"""Do two `camdyn bench` outputs have the same rows, timings aside?

    python3 scripts/bench_rows_equal.py DIR_OR_CSV_1 DIR_OR_CSV_2

Compares work_precision.csv row by row: every column but cpu_seconds must be equal, and
the note after removing the CPU times it quotes ("… 1.23 s …") and "timed once". A row whose run was stopped
by the CPU budget depends on the machine's load: such differences are listed apart and do
not fail the check (the budget is the bench's --budget). Exit 0 when equal, 1 otherwise
(each difference printed), 2 on bad input.
"""
import csv
import os
import re
import sys

TIMING = {"cpu_seconds"}
CPU_IN_NOTE = re.compile(r"\d+(?:\.\d+)?(?:e[-+]?\d+)? s\b")


def norm_note(n):
    """The note without what depends on the clock or the cache: CPU times, "timed once (> 5 s)"
    (a run is timed once when its first timing exceeds the cap), and whether a reference came
    from the reference cache (its rows are the same)."""
    n = CPU_IN_NOTE.sub("<t> s", n)
    n = re.sub(r"[,;] this check from the cache too", "", n)
    n = re.sub(r"[,;] from the cache", "", n)
    n = re.sub(r"(; )?timed once \(> <t> s\)", "", n)
    return n.strip("; ")


def load(p):
    if os.path.isdir(p):
        p = os.path.join(p, "work_precision.csv")
    if not os.path.isfile(p):
        print(f"bench_rows_equal: {p}: no such file", file=sys.stderr)
        sys.exit(2)
    with open(p, newline="") as f:
        return list(csv.DictReader(f))


def key(r):
    return tuple(r.get(c, "") for c in ("scene", "method", "engine", "variant", "tol", "kp", "cp", "max_step"))


def budget_bound(r):
    """Was the row's run stopped by the CPU budget, or skipped because a looser run of the
    same series was ("skipped: … took over 10 s")?"""
    n = r.get("note", "")
    return "budget" in n or ("skipped:" in n and "took over" in n)


def main(argv):
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    a, b = load(argv[1]), load(argv[2])
    ka, kb = {key(r): r for r in a}, {key(r): r for r in b}
    diffs, budget = [], []
    for k in sorted(set(ka) | set(kb)):
        ra, rb = ka.get(k), kb.get(k)
        if ra is None or rb is None:
            (budget if (ra and budget_bound(ra)) or (rb and budget_bound(rb)) else diffs).append(
                f"{k}: only in {'the first' if rb is None else 'the second'}")
            continue
        for c in ra:
            if c in TIMING:
                continue
            va, vb = ra[c], rb.get(c, "")
            if c == "note":
                va, vb = norm_note(va), norm_note(vb)
            if va != vb:
                (budget if budget_bound(ra) or budget_bound(rb) else diffs).append(f"{k}: {c}: {va!r} != {vb!r}")
    for d in budget:
        print("budget-dependent (not a failure): " + d)
    for d in diffs:
        print("differs: " + d)
    print(f"bench_rows_equal: {len(a)} and {len(b)} rows, {len(diffs)} differences"
          + (f", {len(budget)} budget-dependent" if budget else ""))
    return 1 if diffs else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
