"""Where a bench script's Markdown goes: standard output, or a file (a page of the docs site).

    from markdown_out import write_markdown   # bench/ is the script's own folder
"""
import sys

ORPHAN = "---\norphan: true\n---\n\n"  # a page of the docs site outside its toctree


def write_markdown(text, out, orphan=False):
    """`text` to standard output when `out` is None, "" or "-"; else to the file `out`,
    after the front matter of a page outside the toctree when `orphan`."""
    if out in (None, "", "-"):
        sys.stdout.write(text)
        return
    with open(out, "w") as f:
        f.write((ORPHAN if orphan else "") + text)
