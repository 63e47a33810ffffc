#!/usr/bin/env python3
"""The tables of docs/cam_laws.md "Speed (bench_cam)" from build/bench/bench_cam.

Runs the Google Benchmark target once (JSON output, median of --reps repetitions) and writes
Markdown: CPU ns per call of Cam::evaluate (θ in small steps, θ at random) and Cam::motion for
each profile kind, and the motion-law run's steps and rejected steps with and without
landing on the law's joints (LawRunSteps).

usage: bench/bench_cam_table.py --bin build/bench/bench_cam [--reps 5] [--min-time S] [--out FILE]
"""
import argparse
import json
import subprocess
import sys

from markdown_out import write_markdown

FILTER = "SmallSteps|RandomJumps|MotionSmallSteps|LawRunSteps"
PROFILES = ["paper", "circle", "lift", "law", "arc"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bin", required=True, help="build/bench/bench_cam")
    ap.add_argument("--reps", type=int, default=5, help="repetitions (median)")
    ap.add_argument("--min-time", type=float, default=0.0,
                    help="Google Benchmark's minimum time per benchmark [s] (0: its default)")
    ap.add_argument("--out", default="-", help="Markdown file (- : stdout)")
    a = ap.parse_args()
    if a.reps < 1:
        sys.exit(f"bench_cam_table.py: --reps {a.reps}: must be >= 1")
    cmd = [a.bin, f"--benchmark_filter={FILTER}", f"--benchmark_repetitions={a.reps}",
           "--benchmark_report_aggregates_only=true"]
    if a.min_time > 0:
        cmd.append(f"--benchmark_min_time={a.min_time:g}")
    cmd.append("--benchmark_format=json")
    res = subprocess.run(cmd, capture_output=True, text=True)
    if res.returncode != 0:
        sys.exit(f"bench_cam_table.py: {' '.join(cmd)} failed (exit {res.returncode}): {res.stderr[-400:]}")
    data = json.loads(res.stdout)
    med = {}
    for b in data["benchmarks"]:
        if b.get("aggregate_name") != "median":
            continue
        med[b["run_name"]] = b

    def ns(name):
        b = med.get(name)
        if b is None:
            return "–"
        scale = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}[b["time_unit"]]
        return f"{b['cpu_time'] * scale:.1f} ns"

    ctx = data.get("context", {})
    lines = [
        "# Cam evaluation cost (bench_cam)",
        "",
        f"`{' '.join(cmd[:-1])}` (median of {a.reps}; CPU time per call; host {ctx.get('host_name', '?')}, "
        f"{ctx.get('num_cpus', '?')} CPUs, load average {ctx.get('load_avg', '?')} when it ran: "
        "a shared machine, compare within the table).",
        "",
        "| profile | `Cam::evaluate`, θ in small steps | `Cam::evaluate`, random θ | `Cam::motion`, small steps |",
        "|---|---:|---:|---:|",
    ]
    for p in PROFILES:
        lines.append(f"| {p} | {ns(f'SmallSteps/{p}/1')} | {ns(f'RandomJumps/{p}')} | "
                     f"{ns(f'MotionSmallSteps/{p}')} |")
    lines += [
        "",
        "Motion-law run (rise and fall between dwells, 3.5 revolutions, Lee located on arkode-erk, "
        "rigid follower; `LawRunSteps/<3-4-5: 0, cycloidal: 1>/<land on the joints: 1>`):",
        "",
        "| law | landing on the joints: steps, rejected, CPU ms | not landing: steps, rejected, CPU ms |",
        "|---|---|---|",
    ]
    for k, law in ((0, "3-4-5"), (1, "cycloidal")):
        cells = []
        for land in (1, 0):
            b = med.get(f"LawRunSteps/{k}/{land}")
            if b is None:
                cells.append("–")
                continue
            scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b["time_unit"]]
            cells.append(f"{int(b.get('steps', 0))} steps, {int(b.get('rejected', 0))} rejected, "
                         f"{b['cpu_time'] * scale:.2f} ms")
        lines.append(f"| {law} | {cells[0]} | {cells[1]} |")
    text = "\n".join(lines) + "\n"
    write_markdown(text, a.out)


if __name__ == "__main__":
    main()
