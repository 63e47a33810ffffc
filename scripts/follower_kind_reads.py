#!/usr/bin/env python3
"""Print every place in src/ that reads the follower kind (`FollowerKind::`, or a
`single_follower` flag) outside the files allowed to; exit 1 if there is one.

The follower kind is read only by the scene and the builders (docs/guide/architecture.md,
"A follower kind"): every other part asks the built mechanism (`MechanismTraits`, its
contacts, its unknowns) or the scene's data (its [[nodes]], [[contacts]], [camshaft]) for
the property it needs, so that a new follower kind needs no edit there."""
import os, re, sys

# Folders (ending in "/") and files under src/ that may read the kind, each with its reason.
ALLOWED = {
    "scene/": "the scene: it parses, validates, writes and describes its own follower keys",
    "mechanism/mechanism.cpp": "Mechanism::Mechanism selects the builder of the scene's follower",
    "mechanism/follower_matrices.cpp": "the rigid / elastic_bar builder: the rigid mass's 1 x 1 or the bar's matrices",
    "output/scene_json.cpp": "the scene written into summary.json (the network tables of a network scene)",
    "study/jump.cpp": "the jump speed's closed form is the rigid follower's, and an elastic_bar's "
                      "speed range starts at its rigid-body estimate",
    "study/bench.cpp": "the paper's benchmark: each case's reference (engine, rtol), run length, "
                       "grid and tolerance rows by the paper's follower (rigid: closed-form contact phases)",
    "study/bench_compare.cpp": "the paper's benchmark: the same per-case choice for a stored reference",
    "study/bench_tolerance.cpp": "the paper's tolerance study: its reference engine and rtol range per case",
}
PATTERN = re.compile(r"FollowerKind::|\bsingle_follower\w*")


def allowed(rel):
    return any(rel.startswith(a) if a.endswith("/") else rel == a for a in ALLOWED)


def main():
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    src = os.path.join(root, "src")
    found = []
    for d, _, names in os.walk(src):
        for f in sorted(names):
            if not f.endswith((".cpp", ".hpp", ".h")):
                continue
            p = os.path.join(d, f)
            rel = os.path.relpath(p, src).replace(os.sep, "/")
            if allowed(rel):
                continue
            with open(p, encoding="utf-8") as fh:
                for i, line in enumerate(fh, 1):
                    if PATTERN.search(line):
                        found.append(f"src/{rel}:{i}: {line.strip()}")
    stale = [a for a in ALLOWED if not os.path.exists(os.path.join(src, a))]
    for s in found:
        print(s)
    for a in stale:
        print(f"allow-list entry src/{a} names no file or folder (remove it)")
    if found:
        print(f"{len(found)} read(s) of the follower kind outside the scene and the builders: ask the "
              "mechanism (MechanismTraits) or the scene's data for the property instead, or add the "
              "file to ALLOWED in scripts/follower_kind_reads.py with its reason")
    return 1 if found or stale else 0


if __name__ == "__main__":
    sys.exit(main())
