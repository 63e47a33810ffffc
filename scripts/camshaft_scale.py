#!/usr/bin/env python3
"""Scale of a [camshaft] run (issue 40): N bucket-tappet trains (the trains of
examples/i4_dohc_intake_camshaft.toml) on one shaft of N + 1 stations (a sprocket and one
station per cam), one camshaft revolution at 6000 engine rpm (50 rev/s), penalty contact on
arkode-erk at rtol 1e-6. The cams' offsets are spread over the base circle's window so that
every train starts at rest on its seat. Prints N, unknowns, contacts, steps, CPU seconds (best
of --repeat) and the largest resident set (kB).

  python3 scripts/camshaft_scale.py --camdyn build/camdyn [--counts 1 2 4 8 16] [--repeat 3]
"""
import argparse
import json
import os
import re
import subprocess
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))


def scene(n):
    src = open(os.path.join(HERE, "..", "examples", "ohc_bucket_tappet.toml")).read()
    cam = src[src.index("\n[cam]") + 1:src.index("\nspeed_rev_s = 25.0")]
    offsets = [0.0] if n == 1 else [-55.0 + 110.0 * i / (n - 1) for i in range(n)]
    s = ['title = "camshaft scale %d"\n\n' % n, cam, "\nspeed_rev_s = 50.0\n",
         '[follower]\nkind = "network"\n[contact]\nmodel = "penalty"\ntol_u = 1e-9\n'
         'penalty_stiffness = 2e9\npenalty_damping = 2000.0\n'
         '[solver]\nintegrator = "arkode-erk"\nrtol = 1e-6\natol = 1e-12\n'
         '[run]\nt_end = 0.02\noutput_dt = 1e-4\n[camshaft]\n',
         "inertias = [%s]\n" % ", ".join(["1.2e-3"] + ["2.5e-5"] * n),
         "stiffnesses = [%s]\n" % ", ".join(["3.4e4"] * n),
         "rayleigh_beta = 2e-5\n",
         "cam_stations = [%s]\n" % ", ".join(str(i + 1) for i in range(n)),
         "cam_offsets_deg = [%s]\n" % ", ".join("%.6g" % a for a in offsets),
         "drive_stiffness = 2e4\ndrive_damping = 1.0\n"]
    for i in range(n):
        s.append(f'''[[nodes]]
name = "tappet{i}"
mass = 0.045
[[nodes]]
name = "valve{i}"
mass = 0.050
[[elements]]
type = "spring"
nodes = ["tappet{i}", "valve{i}"]
stiffness = 5e7
damping = 30.0
[[elements]]
type = "spring"
nodes = ["valve{i}", "ground"]
stiffness = 35000.0
preload = 250.0
damping = 2.0
[[contacts]]
name = "cam{i}"
type = "cam"
nodes = ["tappet{i}"]
clearance = 0.2e-3
[[contacts]]
name = "seat{i}"
type = "stop"
nodes = ["valve{i}"]
side = "below"
''')
    return "".join(s)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--camdyn", default=os.path.join(HERE, "..", "build", "camdyn"))
    ap.add_argument("--counts", type=int, nargs="+", default=[1, 2, 4, 8, 16])
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    print("| valve trains | unknowns | contacts | steps | CPU s (best of %d) | max RSS kB |" % a.repeat)
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as d:
        for n in a.counts:
            path = os.path.join(d, "s%d.toml" % n)
            open(path, "w").write(scene(n))
            best, rss, steps, unknowns = float("inf"), 0, 0, 0
            for _ in range(a.repeat):
                out = os.path.join(d, "o%d" % n)
                p = subprocess.run(["/usr/bin/time", "-v", a.camdyn, "run", path, "-o", out],
                                   capture_output=True, text=True)
                if p.returncode != 0:
                    raise SystemExit(p.stdout + p.stderr)
                s = json.load(open(os.path.join(out, "summary.json")))
                best = min(best, s["cpu_seconds"])
                steps = s["steps"]
                unknowns = s["model"]["unknowns"]
                rss = max(rss, int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", p.stderr).group(1)))
            print("| %d | %d | %d | %d | %.3f | %d |" % (n, unknowns, 2 * n, steps, best, rss))


if __name__ == "__main__":
    main()
