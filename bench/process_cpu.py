#!/usr/bin/env python3
"""CPU of a whole `camdyn run` process (user + sys, getrusage of the child) for two binaries,
interleaved (old, new, old, new, …), best of REPS; with summary.json's cpu_seconds and steps.

Usage:
  python3 bench/process_cpu.py REPS OLD_BIN NEW_BIN "label scene key=value ... ;; label scene ..."
Prints Markdown rows: label | process CPU old | new | ratio | cpu_seconds old | new | ratio |
steps old | steps new.
"""
import json
import os
import resource
import subprocess
import sys
import tempfile

tmp = tempfile.mkdtemp(prefix="proc_cpu_")
reps=int(sys.argv[1]); bins={"old":sys.argv[2],"new":sys.argv[3]}
cases=[c.split() for c in " ".join(sys.argv[4:]).split(";;")]
def one(b, scene, sets, out):
    r0=resource.getrusage(resource.RUSAGE_CHILDREN)
    cmd=[b,"run",scene,"--out",out,"--quiet"]
    for s in sets: cmd+=["--set",s]
    subprocess.run(cmd,stdout=subprocess.DEVNULL,stderr=subprocess.DEVNULL)
    r1=resource.getrusage(resource.RUSAGE_CHILDREN)
    d=json.load(open(out+"/summary.json"))
    return (r1.ru_utime-r0.ru_utime)+(r1.ru_stime-r0.ru_stime), d["cpu_seconds"], d["steps"]
for c in cases:
    label,scene,sets=c[0],c[1],c[2:]
    best={}
    for _ in range(reps):
        for k,b in bins.items():
            p,cs,st=one(b,scene,sets,os.path.join(tmp, k))
            o=best.get(k)
            best[k]=(min(p,o[0]) if o else p, min(cs,o[1]) if o else cs, st)
    print(f"| {label} | {best['old'][0]:.4f} | {best['new'][0]:.4f} | {best['new'][0]/best['old'][0]:.2f} | {best['old'][1]:.4g} | {best['new'][1]:.4g} | {best['new'][1]/best['old'][1]:.2f} | {best['old'][2]} | {best['new'][2]} |", flush=True)
