"""camdyn's output files checked before they are read (pure Python: no numpy needed).

`camdyn report` and `camdyn plot` call these first, so a damaged directory (a binary CSV, a
summary.json that is not an object or has values of the wrong type, a history.csv with a
header and no rows) ends with one line naming the file and what is wrong (exit 2), never a
traceback. A last line without its newline is a row cut short by a killed run: it is
skipped (docs/interface.md, `camdyn run`).
"""
import json
import math
import os


class InputError(Exception):
    pass


def read_text_lines(path):
    """The file's lines (without newlines); a last line without newline is dropped."""
    try:
        with open(path, "rb") as f:
            raw = f.read()
    except OSError as e:
        raise InputError("%s: %s" % (path, e.strerror))
    if b"\0" in raw:
        raise InputError("%s: a binary file, not CSV text" % path)
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as e:
        raise InputError("%s: not UTF-8 text (byte %d): not a CSV file" % (path, e.start))
    lines = text.split("\n")
    # "a\nb\n" -> ["a", "b", ""]: the final "" is the end of the last whole line; anything
    # else there is a line cut short.
    lines.pop()
    return lines


def check_csv(path, required=("t",), min_rows=1, numeric=True, max_checked=None):
    """Header with the `required` columns, at least `min_rows` rows, each with as many
    fields as the header (and numbers, when `numeric`). Returns (header, rows)."""
    if not os.path.isfile(path):
        raise InputError("%s: no such file" % path)
    lines = [l.rstrip("\r") for l in read_text_lines(path)]
    if not lines or not lines[0].strip():
        raise InputError("%s: empty file (no header)" % path)
    header = lines[0].split(",")
    for c in required:
        if c not in header:
            raise InputError("%s: no column '%s' in the header" % (path, c))
    rows = [l for l in lines[1:] if l.strip()]
    if len(rows) < min_rows:
        raise InputError("%s: a header and %d rows (needs at least %d)" % (path, len(rows), min_rows))
    for i, line in enumerate(rows):
        parts = line.split(",")
        if len(parts) != len(header):
            raise InputError("%s:%d: %d fields, expected %d" % (path, i + 2, len(parts), len(header)))
        if numeric and (max_checked is None or i < max_checked):
            for p in parts:
                try:
                    float(p)
                except ValueError:
                    raise InputError("%s:%d: not a number: %r" % (path, i + 2, p[:40]))
    return header, rows


_NUMBER = (int, float)
_SUMMARY_TYPES = {
    "scene": (str,), "status": (str,), "finished": (bool,), "termination": (str,), "message": (str,),
    "t_end": _NUMBER, "steps": _NUMBER, "rejected_steps": _NUMBER, "separations": _NUMBER,
    "impacts": _NUMBER, "max_contact_force": _NUMBER, "options": (dict,), "contacts": (list,),
    "warnings": (list,), "events": _NUMBER, "contract": (dict,),
}


def check_summary(path):
    """summary.json: a JSON object whose known keys have their types (numbers may be null)."""
    try:
        with open(path, "rb") as f:
            raw = f.read()
    except OSError as e:
        raise InputError("%s: %s" % (path, e.strerror))
    try:
        s = json.loads(raw.decode("utf-8"))
    except (UnicodeDecodeError, ValueError) as e:
        raise InputError("%s: not JSON (%s)" % (path, str(e).splitlines()[0][:80]))
    if not isinstance(s, dict):
        raise InputError("%s: a JSON %s, expected an object (camdyn run's summary)" % (path, type(s).__name__))
    for k, types in _SUMMARY_TYPES.items():
        if k not in s or (s[k] is None and types is _NUMBER):
            continue
        v = s[k]
        ok = isinstance(v, types) and not (types is _NUMBER and isinstance(v, bool))
        if ok and types is _NUMBER and not math.isfinite(float(v)):
            ok = False
        if not ok:
            raise InputError("%s: key '%s' = %s: expected %s" % (
                path, k, json.dumps(v)[:40], "a number" if types is _NUMBER else types[0].__name__))
    for k in ("cam", "run", "solver", "contact"):
        o = s.get("options", {})
        if k in o and not isinstance(o[k], dict):
            raise InputError("%s: key 'options.%s' = %s: expected an object" % (path, k, json.dumps(o[k])[:40]))
    return s


def check_run_dir(d):
    """A run's directory: summary.json, history.csv (≥ 1 row), events.csv when present."""
    check_summary(os.path.join(d, "summary.json"))
    check_csv(os.path.join(d, "history.csv"), required=("t",), min_rows=1)
    ev = os.path.join(d, "events.csv")
    if os.path.exists(ev):
        check_csv(ev, required=("t", "kind"), min_rows=0, numeric=False)


def check_sweep_dir(d):
    """A sweep's directory: sweep.csv with at least one row."""
    check_csv(os.path.join(d, "sweep.csv"), required=(), min_rows=1, numeric=False)
