#!/usr/bin/env python3
"""One self-contained HTML page of a camdyn run or sweep (`camdyn report DIR`, `--plot`).

Usage: camdyn_report.py DIR [--quiet] [--reuse]

A run directory (summary.json, history.csv, events.csv from `camdyn run`): the figures of
camdyn_plot.py (for a network also the lift and every node against cam angle, and every
contact's force) and the designer results in words, from summary.json, events.csv and
history.csv. A sweep directory (sweep.csv, sweep.meta.json from `camdyn sweep`): the figures
of camdyn_sweep_plot.py and the sweep's results in words. Writes DIR/report.html with the
figures embedded as base64 PNG (no other file is needed to view it).

When summary.json has per-contact results ("contacts", a list of objects or an object by
contact name) or a "verdict" (text or an object), they are shown; otherwise the per-contact
results are computed here from history.csv and events.csv.

--reuse: keep figures already in DIR (draw only missing ones). --quiet: print nothing.
Exit status: 0 done, 2 bad input (not a run or sweep directory, unreadable files),
3 numpy/matplotlib missing.
"""
import base64
import csv
import html
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)


class InputError(Exception):
    pass


def num(x):
    try:
        return float(x)
    except (TypeError, ValueError):
        return math.nan


def fmt(x, digits=4):
    x = num(x)
    if not math.isfinite(x):
        return "—"
    return "%.*g" % (digits, x)


def angle(deg_cumulative):
    """'152.6° cam' (and the revolution when past the first)."""
    d = num(deg_cumulative)
    if not math.isfinite(d):
        return "—"
    rev = int(math.floor(d / 360.0))
    text = "%.1f° cam" % (d - 360.0 * rev)
    return text + (" (revolution %d)" % (rev + 1) if rev > 0 else "")


def load_json(path):
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except OSError as e:
        raise InputError("%s: %s" % (path, e.strerror))
    except ValueError as e:
        raise InputError("%s: not JSON (%s)" % (path, e))


def read_rows(path):
    if not os.path.isfile(path):
        return [], []
    with open(path, newline="", encoding="utf-8") as f:
        r = csv.reader(f)
        header = next(r, [])
        return header, [dict(zip(header, row)) for row in r]


def embed(d, names):
    """[(file name, data URI)] of the PNGs in DIR among `names`, in that order."""
    out = []
    for n in names:
        p = os.path.join(d, n)
        if os.path.isfile(p):
            with open(p, "rb") as f:
                out.append((n, "data:image/png;base64," + base64.b64encode(f.read()).decode("ascii")))
    return out


# ---- a run --------------------------------------------------------------------------------


def contact_results_from_files(c, events, contacts):
    """Per contact, from history columns (dict of arrays) and events.csv rows."""
    import numpy as np

    deg = np.degrees(c["theta"])
    res = []
    for name in contacts:
        f, closed = c["F_" + name], c["in_" + name] > 0.5
        ev = [e for e in events if e.get("contact") == name]
        seps = [e for e in ev if e.get("kind") == "separation"]
        imps = [e for e in ev if e.get("kind") == "impact"]
        r = {"contact": name, "separations": len(seps), "impacts": len(imps)}
        if seps:
            r["first_separation_theta_deg"] = math.degrees(num(seps[0]["theta"]))
        if imps:
            big = max(imps, key=lambda e: num(e["impact_velocity"]))
            r["max_impact_velocity"] = num(big["impact_velocity"])
            r["max_impact_theta_deg"] = math.degrees(num(big["theta"]))
        if f.size:
            i = int(np.nanargmax(f))
            r["max_force"], r["max_force_theta_deg"] = float(f[i]), float(deg[i])
        if np.any(closed):
            fc = np.where(closed, f, np.inf)
            i = int(np.argmin(fc))
            r["min_force_closed"], r["min_force_theta_deg"] = float(f[i]), float(deg[i])
        res.append(r)
    return res


def contact_sentence(r, si):
    n = r["contact"]
    v = " m/s" if si else ""
    F = " N" if si else ""
    parts = []
    if r["separations"]:
        parts.append("opens %d time%s, first at %s" % (r["separations"], "s" if r["separations"] != 1 else "",
                                                     angle(r.get("first_separation_theta_deg"))))
    else:
        parts.append("never opens")
    if r["impacts"]:
        parts.append("%d impact%s, the largest %s%s at %s" % (r["impacts"], "s" if r["impacts"] != 1 else "",
                                                            fmt(r.get("max_impact_velocity"), 3), v,
                                                            angle(r.get("max_impact_theta_deg"))))
    if "max_force" in r:
        parts.append("peak force %s%s at %s" % (fmt(r["max_force"]), F, angle(r["max_force_theta_deg"])))
    if "min_force_closed" in r:
        parts.append("least force while closed%s %s%s at %s" % (r.get("min_force_note", ""), fmt(r["min_force_closed"]),
                                                               F, angle(r["min_force_theta_deg"])))
    return "<b>%s</b>: %s." % (html.escape(n), "; ".join(parts))


def summary_contacts(s):
    """Per-contact results of summary.json as [(name, {key: value})], or None."""
    pc = s.get("contacts")
    if isinstance(pc, dict):
        return [(str(k), v) for k, v in pc.items() if isinstance(v, dict)]
    if isinstance(pc, list) and pc and all(isinstance(x, dict) for x in pc):
        return [(str(x.get("name", x.get("contact", i))), x) for i, x in enumerate(pc)]
    return None


def verdict_html(v):
    if v is None:
        return ""
    if isinstance(v, str):
        return "<p class='verdict'><b>Verdict:</b> %s</p>" % html.escape(v)
    if isinstance(v, dict):
        text = v.get("text") or v.get("summary") or v.get("words")
        head = "<p class='verdict'><b>Verdict:</b> %s</p>" % html.escape(str(text)) if text else ""
        rows = "".join("<tr><th>%s</th><td>%s</td></tr>" % (html.escape(str(k)), html.escape(json.dumps(x)))
                       for k, x in v.items() if k not in ("text", "summary", "words"))
        return head + ("<table>%s</table>" % rows if rows else "")
    if isinstance(v, list):
        return "<p class='verdict'><b>Verdict:</b></p><ul>%s</ul>" % "".join(
            "<li>%s</li>" % html.escape(x if isinstance(x, str) else
                                        str(x["text"]) if isinstance(x, dict) and "text" in x else json.dumps(x))
            for x in v)
    return "<p class='verdict'><b>Verdict:</b> %s</p>" % html.escape(json.dumps(v))


def table_of(rows):
    """HTML table of [(name, {key: value})], the union of scalar keys as columns."""
    keys = []
    for _, r in rows:
        for k, x in r.items():
            if k not in keys and k not in ("name", "contact") and not isinstance(x, (dict, list)):
                keys.append(k)
    head = "<tr><th>contact</th>%s</tr>" % "".join("<th>%s</th>" % html.escape(k) for k in keys)
    body = "".join("<tr><td>%s</td>%s</tr>" % (
        html.escape(n), "".join("<td>%s</td>" % html.escape(
            fmt(r[k], 6) if isinstance(r.get(k), (int, float)) and not isinstance(r.get(k), bool)
            else str(r.get(k, "—"))) for k in keys)) for n, r in rows)
    return "<table>%s%s</table>" % (head, body)


LIGHT = {True: ("#2a2", "pass"), False: ("#c22", "FAIL"), None: ("#bbb", "—")}


def light(ok):
    colour, word = LIGHT[ok]
    return "<td style='background:%s;color:#fff;font-weight:bold'>%s</td>" % (colour, word)


def designer_html(s):
    """Hertz stress, cam torque, oil film, ramp velocity, lift deviation, seat landings."""
    rows = []
    if math.isfinite(num(s.get("max_hertz_stress"))):
        rows.append(("largest Hertz stress", "%s at %s" % (fmt(s["max_hertz_stress"]), angle(s.get("max_hertz_theta_deg")))))
    if math.isfinite(num(s.get("cam_torque_peak"))):
        rows.append(("cam torque", "peak %s, mean %s; power peak %s, mean %s" % (
            fmt(s.get("cam_torque_peak")), fmt(s.get("cam_torque_mean")), fmt(s.get("cam_power_peak")),
            fmt(s.get("cam_power_mean")))))
    if math.isfinite(num(s.get("min_film_thickness"))):
        lam = num(s.get("min_lambda"))
        rows.append(("least oil film at the cam", "%s at %s%s" % (
            fmt(s["min_film_thickness"]), angle(s.get("min_film_theta_deg")),
            ", λ = %s" % fmt(lam) if math.isfinite(lam) else "")))
    if math.isfinite(num(s.get("max_ramp_velocity"))):
        rows.append(("ramp velocity at the lash take-up", "%s at %s" % (
            fmt(s["max_ramp_velocity"]), angle(s.get("max_ramp_theta_deg")))))
    dev = s.get("lift_deviation")
    if isinstance(dev, list) and dev:
        lo = min(dev, key=lambda r: num(r.get("min")))
        hi = max(dev, key=lambda r: num(r.get("max")))
        rows.append(("valve lift − kinematic lift", "from %s (%s, revolution %d) to %s (%s, revolution %d)" % (
            fmt(lo.get("min")), angle(lo.get("min_theta_deg")), int(num(lo.get("revolution"))) + 1,
            fmt(hi.get("max")), angle(hi.get("max_theta_deg")), int(num(hi.get("revolution"))) + 1)))
    land = s.get("landings")
    if isinstance(land, list) and land:
        v = max(land, key=lambda r: num(r.get("max_velocity")))
        b = max(land, key=lambda r: num(r.get("bounce_height")))
        n = max(int(num(r.get("bounces"))) for r in land)
        rows.append(("seat landings", "%d; hardest %s at %s; most bounces after one landing %d; highest bounce %s" % (
            len(land), fmt(v.get("max_velocity")), angle(v.get("max_velocity_theta_deg")), n,
            fmt(b.get("bounce_height")))))
    if not rows:
        return ""
    return "<h2>Designer results</h2><table>%s</table>" % "".join(
        "<tr><th>%s</th><td>%s</td></tr>" % (html.escape(k), html.escape(v)) for k, v in rows)


def spectra_html(d):
    """The order spectra `camdyn spectrum DIR --column NAME` wrote (DIR/spectrum_NAME.csv):
    per column, its mean and the eight largest orders."""
    out = []
    for f in sorted(os.listdir(d)):
        if not (f.startswith("spectrum_") and f.endswith(".csv")):
            continue
        _, rows = read_rows(os.path.join(d, f))
        try:
            pts = [(num(r["order"]), num(r["amplitude"])) for r in rows]
        except (KeyError, TypeError):
            continue
        mean = next((a for o, a in pts if o == 0), math.nan)
        top = sorted((p for p in pts if p[0] > 0 and math.isfinite(p[1])), key=lambda p: -p[1])[:8]
        out.append("<tr><td>%s</td><td>%s</td><td>%s</td></tr>" % (
            html.escape(f[len("spectrum_"):-len(".csv")]), html.escape(fmt(mean, 5)),
            html.escape(", ".join("%s: %s" % (fmt(o, 4), fmt(a, 4)) for o, a in top))))
    if not out:
        return ""
    return ("<h2>Order spectra</h2><table><tr><th>column</th><th>mean</th><th>largest orders "
            "(order: amplitude)</th></tr>%s</table><p class='note'>From DIR/spectrum_*.csv "
            "(camdyn spectrum DIR --column NAME).</p>" % "".join(out))


def camshaft_html(s, c):
    """A [camshaft] run (history.csv has drive_torque): the drive torque's range, each cam's
    largest wind-up against the drive station, and the model's frequency lines (summary.json
    model.network)."""
    if "drive_torque" not in c:
        return ""
    import numpy as np

    tq = c["drive_torque"]
    items = ["drive torque %s … %s" % (fmt(float(np.min(tq))), fmt(float(np.max(tq))))]
    cams = sorted((k for k in c if k.startswith("windup_cam")), key=lambda k: int(k[len("windup_cam"):]))
    for k in cams:
        w = c[k]
        i = int(np.argmax(np.abs(w)))
        items.append("%s: largest wind-up %s mrad at %s" % (html.escape(k[len("windup_"):]), fmt(1e3 * float(w[i])),
                                                           angle(np.degrees(c["theta"][i]))))
    model = s.get("model") if isinstance(s.get("model"), dict) else {}
    for line in model.get("network", []) if isinstance(model.get("network"), list) else []:
        if "frequenc" in str(line):
            items.append(html.escape(str(line)))
    return "<h2>Camshaft</h2><ul>%s</ul><p class='note'>Wind-up: the drive station's angle − the cam's " \
           "station's angle (&gt; 0: the cam lags). Torque in N m (SI scenes).</p>%s" % (
               "".join("<li>%s</li>" % x for x in items), valve_timing_html(s))


def valve_timing_html(s):
    """summary.json's valve_timing as a table: per valve its kinematic and dynamic opening and
    closing angles and their errors (camshaft degrees; "" without valve_timing)."""
    rows = s.get("valve_timing") if isinstance(s, dict) else None
    if not isinstance(rows, list) or not rows:
        return ""

    def deg(v, digits=5):
        t = fmt(v, digits)
        return t if t == "—" else t + "°"

    body = "".join("<tr><td>%s</td><td>%s</td><td>%s</td><td>%s</td><td>%s</td><td>%s</td><td>%s</td>"
                   "<td>%s</td></tr>" % (html.escape(str(r.get("valve"))), html.escape(str(r.get("cam"))),
                                         deg(r.get("kinematic_opening_deg")), deg(r.get("opening_deg")),
                                         deg(r.get("opening_error_deg"), 3), deg(r.get("kinematic_closing_deg")),
                                         deg(r.get("closing_deg")), deg(r.get("closing_error_deg"), 3))
                   for r in rows)
    return ("<h3>Valve timing</h3><table><tr><th>valve</th><th>cam</th><th>opens (kinematic)</th>"
            "<th>opens</th><th>error</th><th>closes (kinematic)</th><th>closes</th><th>error</th></tr>%s"
            "</table><p class='note'>Open above 1 %% of the valve's kinematic lift. Kinematic: the cam's own "
            "angle; dynamic: the crank's angle − the cam's offset when the valve crosses that lift (the last "
            "revolution with both); camshaft degrees, error &gt; 0: late.</p>" % body)


def criteria_html(crit):
    """The acceptance criteria of a run as a traffic-light table."""
    if not isinstance(crit, list) or not crit:
        return ""
    body = "".join("<tr><td>%s</td><td>%s %s</td><td>%s</td><td>%s</td>%s<td>%s</td></tr>" % (
        html.escape(str(c.get("name"))), "≤" if c.get("kind") == "max" else "≥", fmt(c.get("limit"), 6),
        fmt(c.get("value"), 6), angle(c.get("theta_deg")), light(bool(c.get("pass"))),
        html.escape(str(c.get("note") or ""))) for c in crit)
    return ("<h2>Acceptance criteria</h2><table><tr><th>criterion</th><th>limit</th><th>value</th>"
            "<th>worst at</th><th></th><th>note</th></tr>%s</table>" % body)


def run_report(d, reuse):
    import camdyn_plot as cp

    s = load_json(os.path.join(d, "summary.json"))
    hpath = os.path.join(d, "history.csv")
    try:
        _, c = cp.read_csv(hpath)
    except cp.InputError as e:
        raise InputError(str(e))
    _, events = read_rows(os.path.join(d, "events.csv"))
    contacts, nodes = cp.network_names(c)
    network = bool(contacts)
    figs = ["network_motion.png", "network_forces.png"] if network else []
    figs += ["displacement.png", "contact_force.png", "contact_force_zoom.png"]
    if "lift_deviation" in c:
        figs.append("lift_deviation.png")
    if "drive_torque" in c:
        figs.append("camshaft.png")
    if not (reuse and all(os.path.isfile(os.path.join(d, f)) for f in figs)):
        cp.plot_run(d)

    opts = s.get("options", {}) if isinstance(s.get("options"), dict) else {}
    cam = opts.get("cam", {}) if isinstance(opts.get("cam"), dict) else {}
    speed = cam.get("speed_rev_s")
    title = str(s.get("scene") or "camdyn run")
    words = []
    if s.get("finished") is False:
        words.append("<p class='bad'><b>The run did not finish</b> (at t = %s): %s</p>" % (
            fmt(s.get("t_end"), 8), html.escape(str(s.get("message", "")))))
    at = " at %s rev/s" % fmt(speed, 6) if speed is not None else ""
    words.append("<p>%s, %s of %s s simulated%s (%s, contact method %s).</p>" % (
        html.escape(title), fmt(s.get("t_end"), 6), fmt(s.get("t_end_requested"), 6), at,
        html.escape(str(s.get("integrator", ""))), html.escape(str(s.get("contact_model", "")))))
    words.append(verdict_html(s.get("verdict")))
    per = summary_contacts(s)
    if network:
        # In words from the files always; the run's own per-contact results (summary.json,
        # lash take-up window excluded: docs/contacts.md) as a table beside them when present.
        res = contact_results_from_files(c, events, contacts)
        if per is not None:
            # the numbers summary.json also shows are its own (the least force leaves out the
            # lash take-up window, docs/contacts.md), so the page and the file agree
            by_name = dict(per)
            for r in res:
                sr = by_name.get(r["contact"])
                if not isinstance(sr, dict):
                    continue
                r.pop("min_force_closed", None)
                if math.isfinite(num(sr.get("min_force"))):
                    r["min_force_closed"] = num(sr.get("min_force"))
                    r["min_force_theta_deg"] = num(sr.get("min_force_theta_deg"))
                    r["min_force_note"] = " (outside the lash take-up)"
                for k in ("max_impact_velocity", "max_impact_theta_deg", "first_separation_theta_deg"):
                    if k in sr:
                        r[k] = num(sr[k])
        words.append("<h2>Results per contact</h2><ul>%s</ul>" % "".join(
            "<li>%s</li>" % contact_sentence(r, True) for r in res))
        words.append("<p class='note'>From history.csv (forces at the output times) and events.csv. "
                     "Forces in N, speeds in m/s (network scenes are in SI units).</p>")
        if per is not None:
            words.append("<h2>Results per contact (summary.json)</h2>" + table_of(per))
        import numpy as np

        deg = np.degrees(c["theta"])
        lift = c["u_c"] - c["gap"]
        items = ["cam lift: peak %s mm at %s" % (fmt(1e3 * np.max(lift)), angle(deg[int(np.argmax(lift))]))]
        for n in nodes:
            u = c["u_" + n]
            items.append("%s: peak %s mm at %s" % (html.escape(n), fmt(1e3 * np.max(u)),
                                                   angle(deg[int(np.argmax(u))])))
        words.append("<h2>Motion</h2><ul>%s</ul>" % "".join("<li>%s</li>" % x for x in items))
    else:
        if per is not None:
            words.append("<h2>Results per contact (summary.json)</h2>" + table_of(per))
        sep, imp = int(num(s.get("separations")) or 0), int(num(s.get("impacts")) or 0)
        if sep == 0 and imp == 0:
            words.append("<p>The follower stays on the cam%s: it never separates. The least contact force "
                         "(the margin) is %s at %s; the largest %s.</p>" % (
                             at, fmt(s.get("min_contact_force")), angle(s.get("min_force_theta_deg")),
                             fmt(s.get("max_contact_force"))))
        else:
            words.append("<p>The follower separates from the cam %d time%s%s, first at %s; %d impact%s, "
                         "the hardest at impact speed %s at %s. Contact force up to %s; the least "
                         "while in contact %s at %s.</p>" % (
                             sep, "s" if sep != 1 else "", at, angle(s.get("first_separation_theta_deg")),
                             imp, "s" if imp != 1 else "", fmt(s.get("max_impact_velocity"), 3),
                             angle(s.get("max_impact_theta_deg")), fmt(s.get("max_contact_force")),
                             fmt(s.get("min_contact_force")), angle(s.get("min_force_theta_deg"))))
    words.append(camshaft_html(s, c))
    words.append(designer_html(s))
    words.append(criteria_html(s.get("criteria")))
    words.append(spectra_html(d))
    stats = [("steps", s.get("steps")), ("rejected steps", s.get("rejected_steps")),
             ("events", s.get("events")), ("CPU seconds", s.get("cpu_seconds")),
             ("largest penetration", s.get("max_penetration")), ("energy residual", s.get("energy_residual"))]
    words.append("<h2>Run</h2><table>%s</table>" % "".join(
        "<tr><th>%s</th><td>%s</td></tr>" % (k, html.escape(fmt(v, 6))) for k, v in stats))
    return title, "".join(words), embed(d, figs)


# ---- a sweep ------------------------------------------------------------------------------


def sweep_report(d, reuse):
    import camdyn_sweep_plot as sp

    header, rows = read_rows(os.path.join(d, "sweep.csv"))
    if not header:
        raise InputError("%s: empty sweep.csv" % d)
    meta = load_json(os.path.join(d, "sweep.meta.json"))
    figs = ["sweep_force.png", "sweep_bifurcation.png", "sweep_impacts.png"]
    if not (reuse and all(os.path.isfile(os.path.join(d, f)) for f in figs)):
        rc = sp.main(["camdyn_sweep_plot.py", d, "--quiet"])
        if rc != 0:
            raise InputError("%s: the sweep figures could not be drawn (status %d)" % (d, rc))
    key = header[0]
    key2 = header[1] if len(header) > 1 and header[1] != "finished" else None
    ok = [r for r in rows if r.get("finished") == "1"]
    title = str(meta.get("scene") or "camdyn sweep")
    words = ["<p>Sweep of <code>%s</code>%s from %s to %s: %d points, %d finished, %d failed.</p>" % (
        html.escape(key), (" and <code>%s</code>" % html.escape(key2)) if key2 else "",
        fmt(min(num(r[key]) for r in rows), 8), fmt(max(num(r[key]) for r in rows), 8),
        len(rows), len(ok), len(rows) - len(ok))]
    items = []
    sep = [r for r in ok if num(r.get("separations")) > 0]
    if sep:
        vals = sorted({num(r[key]) for r in sep})
        shown = ", ".join(fmt(v, 8) for v in vals[:8]) + (", …" if len(vals) > 8 else "")
        r = min(sep, key=lambda r: num(r[key]))
        first = angle(r.get("first_separation_theta_deg"))
        items.append("separations in %d of %d finished points (%s = %s)%s" % (
            len(sep), len(ok), html.escape(key), shown,
            "; at the smallest %s the first at %s" % (html.escape(key), first) if first != "—" else ""))
    elif ok:
        items.append("no separation at any point of the range")
    if ok:
        r = max(ok, key=lambda r: num(r.get("max_contact_force")))
        items.append("the largest contact force, %s, at %s = %s" % (fmt(r["max_contact_force"]), html.escape(key),
                                                                    fmt(r[key], 8)))
        r = min(ok, key=lambda r: num(r.get("min_contact_force")))
        items.append("the smallest force margin, %s, at %s = %s (%s)" % (
            fmt(r["min_contact_force"]), html.escape(key), fmt(r[key], 8), angle(r.get("min_force_theta_deg"))))
        imp = [r for r in ok if math.isfinite(num(r.get("max_impact_velocity")))]
        if imp:
            r = max(imp, key=lambda r: num(r["max_impact_velocity"]))
            items.append("the hardest impact, %s, at %s = %s (%s)" % (
                fmt(r["max_impact_velocity"], 3), html.escape(key), fmt(r[key], 8), angle(r.get("max_impact_theta_deg"))))
    if "verdict" in header:
        items += ["%s = %s: %s" % (html.escape(key), fmt(r[key], 8), html.escape(r["verdict"])) for r in ok]
    words.append("<ul>%s</ul>" % "".join("<li>%s</li>" % x for x in items))
    words.append(sweep_criteria_html(header, rows, key))
    return title, "".join(words), embed(d, figs)


def sweep_criteria_html(header, rows, key):
    """The criteria columns of sweep.csv (criterion_<name>_pass) as a traffic-light table over
    the first key, with each criterion's first failing value."""
    names = [h[len("criterion_"):-len("_pass")] for h in header
             if h.startswith("criterion_") and h.endswith("_pass")]
    if not names:
        return ""
    rows = sorted(rows, key=lambda r: num(r.get(key)))
    first = {}
    for n in names:
        fails = [num(r[key]) for r in rows if r.get("criterion_%s_pass" % n) == "0"]
        first[n] = min(fails) if fails else None
    head = "<tr><th>%s</th>%s</tr>" % (html.escape(key), "".join("<th>%s</th>" % html.escape(n) for n in names))
    body = ""
    for r in rows:
        cells = ""
        for n in names:
            p = r.get("criterion_%s_pass" % n, "")
            ok = True if p == "1" else False if p == "0" else None
            colour, word = LIGHT[ok]
            cells += "<td style='background:%s;color:#fff' title='%s'>%s %s</td>" % (
                colour, word, word, html.escape(fmt(r.get("criterion_%s_value" % n))))
        body += "<tr><td>%s</td>%s</tr>" % (html.escape(fmt(r.get(key), 8)), cells)
    firsts = "".join("<li>%s: %s</li>" % (html.escape(n), "first fails at %s = %s" % (html.escape(key), fmt(first[n], 8))
                                         if first[n] is not None else "passes at every judged point")
                     for n in names)
    return ("<h2>Acceptance criteria over the sweep</h2><ul>%s</ul><table>%s%s</table>" % (firsts, head, body))


# ---- the page -----------------------------------------------------------------------------

CSS = """body{font-family:sans-serif;max-width:60em;margin:2em auto;padding:0 1em;color:#222}
h1{font-size:1.5em}h2{font-size:1.15em;margin-top:1.5em}table{border-collapse:collapse;margin:.5em 0}
th,td{border:1px solid #ccc;padding:.2em .6em;text-align:left}figure{margin:1.5em 0}
img{max-width:100%;border:1px solid #ddd}.bad{color:#a00}.verdict{font-size:1.1em}.note{color:#666;font-size:.9em}"""


def page(kind, title, body, figs):
    imgs = "".join("<figure><img src='%s' alt='%s'><figcaption>%s</figcaption></figure>" % (uri, n, n)
                   for n, uri in figs)
    return ("<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'><title>%s</title>"
            "<style>%s</style></head><body><h1>%s: %s</h1>%s<h2>Figures</h2>%s</body></html>\n" % (
                html.escape(title), CSS, kind, html.escape(title), body, imgs))


def main(argv):
    args = [a for a in argv[1:] if not a.startswith("--")]
    quiet, reuse = "--quiet" in argv, "--reuse" in argv
    if len(args) != 1:
        sys.stderr.write(__doc__)
        return 2
    d = args[0]
    # The inputs first (pure Python): a damaged directory is one line and exit 2.
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import camdyn_inputs
    try:
        if os.path.isfile(os.path.join(d, "sweep.csv")):
            camdyn_inputs.check_sweep_dir(d)
        elif os.path.isfile(os.path.join(d, "summary.json")):
            camdyn_inputs.check_run_dir(d)
    except camdyn_inputs.InputError as e:
        sys.stderr.write("camdyn_report: %s\n" % e)
        return 2
    try:
        import matplotlib  # noqa: F401
        import numpy  # noqa: F401
    except ImportError as e:
        sys.stderr.write("camdyn_report: needs numpy and matplotlib (%s)\n" % e)
        return 3
    import camdyn_plot

    camdyn_plot.QUIET = True
    try:
        if os.path.isfile(os.path.join(d, "sweep.csv")):
            kind, (title, body, figs) = "Sweep", sweep_report(d, reuse)
        elif os.path.isfile(os.path.join(d, "summary.json")):
            kind, (title, body, figs) = "Run", run_report(d, reuse)
        else:
            raise InputError("%s: holds neither summary.json (from 'camdyn run') nor sweep.csv "
                             "(from 'camdyn sweep')" % d)
    except InputError as e:
        sys.stderr.write("camdyn_report: %s\n" % e)
        return 2
    out = os.path.join(d, "report.html")
    tmp = out + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(page(kind, title, body, figs))
    os.replace(tmp, out)
    if not quiet:
        print("wrote %s (%d figures)" % (out, len(figs)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
