#!/usr/bin/env python3
"""Print the include arrows between src/ folders that point up the layer order of
docs/guide/architecture.md ("Folders", read from that page); exit 1 if there is one not
listed as known.

A public header include/camdyn/X.hpp belongs to the folder of the one source src/**/X.cpp
that implements it (camdyn/cam.hpp to cam, camdyn/output.hpp to output); a public header
without such a source (data types: summary.hpp, history.hpp, network.hpp, ...) belongs to no
folder and every folder may include it."""
import collections, os, re, sys

# {(from, to): why} allowed to point up, each with its reason (none: every include points down)
KNOWN = {}


def layer_order(architecture_md):
    """The src/ folders of the page's folder block, bottom-up ("src/contact/laws/" -> "contact/laws")."""
    text = open(architecture_md, encoding="utf-8").read()
    block = re.search(r"^## Folders.*?^```\n(.*?)^```", text, re.S | re.M)
    if not block:
        sys.exit(f"{architecture_md}: no folder block under '## Folders'")
    return re.findall(r"^src/([a-z_/]+?)/\s", block.group(1), re.M)


def main():
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    os.chdir(root)
    order = layer_order("docs/guide/architecture.md")

    def layer(rel):  # rel: a path under src/ ("contact/laws/penalty_law.hpp")
        best = None
        for name in order:
            if rel.startswith(name + "/") and (best is None or len(name) > len(best)):
                best = name
        return best

    sources = collections.defaultdict(list)  # stem -> folders of src/**/stem.cpp
    files = []
    for d, _, names in os.walk("src"):
        for f in names:
            p = os.path.join(d, f)
            files.append(p)
            if f.endswith(".cpp"):
                sources[f[:-4]].append(layer(os.path.relpath(p, "src")))

    def target_layer(inc):
        if inc.startswith("camdyn/"):
            stem = os.path.splitext(os.path.basename(inc))[0]
            folders = sources.get(stem, [])
            return folders[0] if len(folders) == 1 else None
        return layer(inc)

    up = collections.defaultdict(set)
    for p in files:
        a = layer(os.path.relpath(p, "src"))
        if a is None:
            continue
        for line in open(p, encoding="utf-8"):
            m = re.match(r'\s*#\s*include\s+"([^"]+)"', line)
            if not m:
                continue
            b = target_layer(m.group(1))
            if b is not None and b != a and order.index(b) > order.index(a):
                up[(a, b)].add(f"{p} ({m.group(1)})")
    bad = 0
    for (a, b), files_up in sorted(up.items()):
        known = (a, b) in KNOWN
        bad += not known
        print(f"{a} -> {b}{' (known: ' + KNOWN[(a, b)] + ')' if known else ''}: {', '.join(sorted(files_up))}")
    print(f"layers, bottom-up: {', '.join(order)}")
    print(f"{sum(len(v) for v in up.values())} upward include(s), {bad} not known")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
