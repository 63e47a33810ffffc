#!/usr/bin/env python3
"""Print the include arrows between src/ folders that point up the layer order of
docs/guide/architecture.md ("Folders"); exit 1 if there is one not listed as known."""
import collections, os, re, sys

ORDER = ["scene", "cam", "contact/laws", "mechanism", "engine", "results", "contact", "run",
         "output", "study", "cli"]
KNOWN = set()  # (from, to) pairs allowed to point up: none


def layer(path):
    rel = os.path.relpath(path, "src") if path.startswith("src/") else path
    return "contact/laws" if rel.startswith("contact/laws/") else rel.split("/")[0]


def main():
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    os.chdir(root)
    up = collections.defaultdict(set)
    for d, _, files in os.walk("src"):
        for f in files:
            p = os.path.join(d, f)
            a = layer(p)
            for line in open(p, encoding="utf-8"):
                m = re.match(r'\s*#\s*include\s+"([a-z_]+(?:/laws)?)/', line)
                if not m or m.group(1) not in ORDER:
                    continue
                b = m.group(1)
                if b != a and a in ORDER and ORDER.index(b) > ORDER.index(a):
                    up[(a, b)].add(p)
    bad = 0
    for (a, b), files in sorted(up.items()):
        known = (a, b) in KNOWN
        bad += not known
        print(f"{a} -> {b}{' (known)' if known else ''}: {', '.join(sorted(files))}")
    print(f"{sum(len(v) for v in up.values())} upward include(s), {bad} not known")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
