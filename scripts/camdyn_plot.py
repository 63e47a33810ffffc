#!/usr/bin/env python3
"""Figures of a camdyn output directory (numpy + matplotlib, no display needed).

    camdyn_plot.py run DIR [--zoom T0 T1]
        DIR/history.csv -> DIR/displacement.png       u_c(t) and the cam X_C = u_c − gap
                           DIR/contact_force.png      contact force over the run
                           DIR/contact_force_zoom.png 0.02 s around the largest force
                                                      (or the window T0..T1)
                           networks (F_<contact>, u_<node> columns) also:
                           DIR/network_motion.png     cam lift and every node vs cam angle
                           DIR/network_forces.png     every contact's force, impacts marked
                           with run.valve_node (a lift_deviation column) also:
                           DIR/lift_deviation.png     valve lift − kinematic lift vs cam angle,
                                                      one line per revolution
                           with a [camshaft] (drive_torque, windup_cam<i> columns) also:
                           DIR/camshaft.png           drive torque and every cam's wind-up
                                                      against the cam angle θ(t), and each
                                                      valve's timing error (summary.json
                                                      valve_timing)
    camdyn_plot.py cam DIR [--speed REV_S]
        DIR/cam.csv     -> DIR/cam_profile.png        the profile in the cam frame
                           DIR/cam_kinematics.png     lift, velocity, acceleration vs cam angle
                           DIR/cam_geometry.png       jerk, pressure angle, radius of curvature
                           (speed: --speed, else DIR/cam_info.json written by `camdyn cam`)
    --quiet: do not list the files written.

Exit status: 0 done, 2 bad input (missing/unreadable file), 3 numpy/matplotlib missing.
"""
import argparse
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

try:
    import numpy as np
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError as exc:  # pragma: no cover - depends on the system
    sys.stderr.write("camdyn_plot: needs numpy and matplotlib (%s)\n" % exc)
    sys.exit(3)


class InputError(Exception):
    pass


def read_csv(path):
    """Numeric CSV with a header row -> (column names, dict name -> 1-D float array)."""
    if not os.path.isfile(path):
        raise InputError("%s: no such file" % path)
    import camdyn_inputs
    try:
        # whole lines only (a last line cut short by a killed run is dropped), UTF-8 text
        lines = camdyn_inputs.read_text_lines(path)
    except camdyn_inputs.InputError as e:
        raise InputError(str(e))
    header = lines[0].strip() if lines else ""
    if not header:
        raise InputError("%s: empty file (no header)" % path)
    names = header.split(",")
    rows = []
    for lineno, line in enumerate(lines[1:], start=2):
        line = line.strip()
        if not line:
            continue
        parts = line.split(",")
        if len(parts) != len(names):
            raise InputError(
                "%s:%d: %d fields, expected %d" % (path, lineno, len(parts), len(names))
            )
        try:
            rows.append([float(p) for p in parts])
        except ValueError:
            raise InputError("%s:%d: not a number in %r" % (path, lineno, line[:80]))
    if not rows:
        raise InputError("%s: a header and no rows" % path)
    data = np.array(rows, dtype=float).reshape(-1, len(names))
    return names, {n: data[:, i] for i, n in enumerate(names)}


def require(cols, path, names):
    missing = [n for n in names if n not in cols]
    if missing:
        raise InputError("%s: missing column(s) %s" % (path, ", ".join(missing)))


def scene_title(d):
    try:
        with open(os.path.join(d, "summary.json"), "r", encoding="utf-8") as f:
            s = json.load(f)
        title = str(s.get("scene", ""))
        if s.get("finished") is False:
            title += "  (did not finish: %s)" % s.get("message", "")
        return title
    except (OSError, ValueError):
        return ""


QUIET = False


def save(fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    if not QUIET:
        print("wrote %s" % path)


def cam_info(d):
    """DIR/cam_info.json from `camdyn cam` (title, speed_rev_s), or {}."""
    try:
        with open(os.path.join(d, "cam_info.json"), "r", encoding="utf-8") as f:
            info = json.load(f)
        return info if isinstance(info, dict) else {}
    except (OSError, ValueError):
        return {}


# ---- run -----------------------------------------------------------------------------


def cam_of_history(c):
    """The cam's contact point from a history: gap = u_c − X_C (docs/interface.md), so
    X_C = u_c − gap (networks: u_c and X_C measured from the base circle, X_C the lift)."""
    return c["u_c"] - c["gap"]


def plot_run(d, zoom=None):
    path = os.path.join(d, "history.csv")
    _, c = read_csv(path)
    require(c, path, ["t", "u_c", "contact_force", "gap"])
    t, u, force, gap = c["t"], c["u_c"], c["contact_force"], c["gap"]
    title = scene_title(d)
    if t.size == 0:
        raise InputError("%s: no rows" % path)

    # Displacement of the contact face, and the cam's contact point.
    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.plot(t, u, "-", lw=1.2, label="follower $u_c$")
    ax.plot(t, cam_of_history(c), "--", lw=1.0, label="cam $X_C = u_c - $gap")
    ax.set_xlabel("time t")
    ax.set_ylabel("displacement")
    ax.set_title(("Displacement of the contact face\n" + title).strip())
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best")
    save(fig, os.path.join(d, "displacement.png"))

    # Contact force over the run.
    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.plot(t, force, "-", lw=0.8)
    ax.set_xlabel("time t")
    ax.set_ylabel("contact force $-p$")
    ax.set_title(("Contact force\n" + title).strip())
    ax.grid(True, alpha=0.3)
    save(fig, os.path.join(d, "contact_force.png"))

    # Zoomed window.
    if zoom is not None:
        t0, t1 = zoom
    else:
        finite = np.where(np.isfinite(force), force, -np.inf)
        i = int(np.argmax(finite)) if finite.size else 0
        half = 0.01
        t0, t1 = t[i] - half, t[i] + half
        # keep the window inside the run when the run is long enough
        if t[-1] - t[0] >= 2 * half:
            if t0 < t[0]:
                t0, t1 = t[0], t[0] + 2 * half
            if t1 > t[-1]:
                t0, t1 = t[-1] - 2 * half, t[-1]
    sel = (t >= t0) & (t <= t1)
    fig, ax = plt.subplots(figsize=(8, 4.5))
    if np.any(sel):
        ax.plot(t[sel], force[sel], ".-", lw=0.8, ms=2)
    ax.set_xlim(t0, t1)
    ax.set_xlabel("time t")
    ax.set_ylabel("contact force $-p$")
    ax.set_title(("Contact force, t = %.6g … %.6g\n" % (t0, t1) + title).strip())
    ax.grid(True, alpha=0.3)
    save(fig, os.path.join(d, "contact_force_zoom.png"))
    if network_names(c)[0]:
        plot_network(d, c, title)
    if "lift_deviation" in c and "theta" in c:
        plot_lift_deviation(d, c, title)
    if "drive_torque" in c:
        plot_camshaft(d, c, title)


def camshaft_curves(c):
    """A camshaft run's curves: the cam angle θ(t) that [cam] prescribes [deg] (the crank's
    mean angle), the drive torque, and each cam's wind-up against the drive station [mrad] as
    (name, values), in cam order."""
    drive_deg = np.degrees(c["theta"])
    cams = sorted((k for k in c if k.startswith("windup_cam")), key=lambda k: int(k[len("windup_cam"):]))
    return drive_deg, c["drive_torque"], [(k[len("windup_"):], 1e3 * c[k]) for k in cams]


def valve_timing_bars(s):
    """Each valve's timing errors from a summary.json (dict) of a camshaft run: (valve names,
    opening errors, closing errors) [deg, camshaft degrees; NaN where the valve did not open or
    close], in the summary's valve order; three empty lists without "valve_timing"."""
    rows = s.get("valve_timing") if isinstance(s, dict) else None
    if not isinstance(rows, list):
        return [], [], []

    def num(v):
        return float("nan") if v is None else float(v)

    return ([str(r.get("valve")) for r in rows], [num(r.get("opening_error_deg")) for r in rows],
            [num(r.get("closing_error_deg")) for r in rows])


def read_summary(d):
    try:
        with open(os.path.join(d, "summary.json"), "r", encoding="utf-8") as f:
            s = json.load(f)
        return s if isinstance(s, dict) else {}
    except (OSError, ValueError):
        return {}


def plot_camshaft(d, c, title="", summary=None):
    """DIR/camshaft.png: the drive torque and every cam's wind-up against the prescribed cam
    angle over the run, and, when summary.json (or `summary`) has "valve_timing", each valve's
    opening and closing timing error (dynamic − kinematic, camshaft degrees)."""
    deg, torque, windups = camshaft_curves(c)
    names, opening, closing = valve_timing_bars(read_summary(d) if summary is None else summary)
    panels = 3 if names else 2
    fig, axes = plt.subplots(panels, 1, figsize=(8, 3.5 * panels))
    a1, a2 = axes[0], axes[1]
    a1.plot(deg, torque, "-", lw=1.0)
    a1.set_ylabel("drive torque")
    a1.set_title(("Camshaft: drive torque and wind-up\n" + title).strip())
    a1.grid(True, alpha=0.3)
    a1.sharex(a2)
    for name, w in windups:
        a2.plot(deg, w, "-", lw=0.9, label=name)
    a2.set_xlabel("cam angle θ(t) [deg]")
    a2.set_ylabel("wind-up against the drive [mrad]")
    a2.grid(True, alpha=0.3)
    if 0 < len(windups) <= 16:
        a2.legend(loc="best", fontsize=7, ncol=2)
    if names:
        a3 = axes[2]
        x = np.arange(len(names))
        a3.bar(x - 0.2, opening, 0.4, label="opening")
        a3.bar(x + 0.2, closing, 0.4, label="closing")
        a3.axhline(0.0, color="k", lw=0.6)
        a3.set_xticks(x)
        a3.set_xticklabels(names, rotation=45 if len(names) > 8 else 0, fontsize=8)
        a3.set_ylabel("timing error [cam deg]")
        a3.set_title("Timing error per valve: dynamic − kinematic (> 0: late)", fontsize=9)
        a3.grid(True, axis="y", alpha=0.3)
        a3.legend(loc="best", fontsize=7)
    save(fig, os.path.join(d, "camshaft.png"))


def plot_lift_deviation(d, c, title=""):
    """DIR/lift_deviation.png: the valve's lift minus its kinematic lift (the cam law through
    the levers, lashes taken up) against the cam angle, one line per camshaft revolution."""
    deg = np.degrees(c["theta"])
    dev = c["lift_deviation"]
    rev = np.floor(deg / 360.0).astype(int)
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for k in np.unique(rev):
        sel = rev == k
        ax.plot(deg[sel] - 360.0 * k, dev[sel], "-", lw=1.0, label="revolution %d" % (k + 1))
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set_xlim(0, 360)
    ax.set_xlabel("cam angle [deg]")
    ax.set_ylabel("valve lift − kinematic lift")
    ax.set_title(("Dynamic against kinematic valve lift\n" + title).strip())
    ax.grid(True, alpha=0.3)
    if np.unique(rev).size <= 8:
        ax.legend(loc="best", fontsize=8)
    save(fig, os.path.join(d, "lift_deviation.png"))


# ---- networks (valve trains) ----------------------------------------------------------


def network_names(c):
    """(contacts, nodes) of a network history: the c of every F_<c>, the n of every u_<n>."""
    contacts = [k[2:] for k in c if k.startswith("F_")]
    nodes = [k[2:] for k in c if k.startswith("u_") and k != "u_c"]
    return contacts, nodes


def cam_contact_clearances(d):
    """[(name, clearance)] of the cam contacts of DIR/summary.json's scene ("options" →
    "contacts", type "cam"), in the scene's order; [] if unknown."""
    try:
        with open(os.path.join(d, "summary.json"), "r", encoding="utf-8") as f:
            s = json.load(f)
        cs = s.get("options", {}).get("contacts", [])
        return [(str(k.get("name", "")), float(k.get("clearance", 0.0) or 0.0))
                for k in cs if k.get("type") == "cam"]
    except (OSError, ValueError, AttributeError, TypeError):
        return []


def cam_curves(c, clearances):
    """The cam's input to each cam contact's node, in the node's coordinates: the lift above
    the base circle X_C − X_base (= u_c − gap of the history's first cam contact,
    docs/interface.md) minus the contact's clearance, so that it lies on the node's curve
    while the contact is closed and at −clearance on the base circle.
    Returns [(label, array)]; without known clearances the bare lift."""
    lift = cam_of_history(c)
    if not clearances:
        return [("cam lift $X_C - X_{base}$", lift)]
    return [("cam '%s': lift − clearance %.4g mm" % (n, 1e3 * g), lift - g) for n, g in clearances]


def read_impacts(d):
    """{contact: [t of each impact]} from DIR/events.csv ({} if absent)."""
    impacts = {}
    ev = os.path.join(d, "events.csv")
    if os.path.isfile(ev):
        import csv
        with open(ev, newline="", encoding="utf-8") as f:
            for e in csv.DictReader(f):
                if e.get("kind") == "impact" and e.get("contact"):
                    impacts.setdefault(e["contact"], []).append(float(e["t"]))
    return impacts


def plot_network(d, c, title=""):
    """DIR/network_motion.png: the cam's input (lift − clearance, per cam contact) and every
    node's displacement against cam angle, impacts marked; DIR/network_forces.png: the force
    of every contact against cam angle, its impacts (DIR/events.csv) marked."""
    contacts, nodes = network_names(c)
    deg = np.degrees(c["theta"])
    impacts = read_impacts(d)
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for label, curve in cam_curves(c, cam_contact_clearances(d)):
        ax.plot(deg, 1e3 * curve, "k--", lw=1.0, label=label)
    for n in nodes:
        ax.plot(deg, 1e3 * c["u_" + n], "-", lw=1.1, label=n)
    ts = sorted(t for v in impacts.values() for t in v)
    if ts:
        ax.plot(np.degrees(np.interp(ts, c["t"], c["theta"])), np.zeros(len(ts)), "rv", ms=5,
                label="impacts")
    ax.set_xlabel("cam angle [deg]")
    ax.set_ylabel("displacement [mm]")
    ax.set_title(("Lift and node displacements\n" + title).strip())
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    save(fig, os.path.join(d, "network_motion.png"))

    fig, axs = plt.subplots(len(contacts), 1, figsize=(8, 2.2 + 1.8 * len(contacts)), sharex=True,
                            squeeze=False)
    for ax, name in zip(axs[:, 0], contacts):
        f = c["F_" + name]
        ax.plot(deg, f, "-", lw=0.9)
        ts = impacts.get(name, [])
        if ts:
            ax.plot(np.degrees(np.interp(ts, c["t"], c["theta"])), np.interp(ts, c["t"], f), "rv", ms=6,
                    label="impact")
            ax.legend(loc="best", fontsize="small")
        ax.set_ylabel("F_%s [N]" % name)
        ax.grid(True, alpha=0.3)
    axs[-1, 0].set_xlabel("cam angle [deg]")
    axs[0, 0].set_title(("Contact forces\n" + title).strip())
    save(fig, os.path.join(d, "network_forces.png"))


# ---- cam -----------------------------------------------------------------------------


def plot_cam(d, speed=None):
    path = os.path.join(d, "cam.csv")
    _, c = read_csv(path)
    require(c, path, ["theta", "X_C", "dX_dtheta", "d2X_dtheta2", "beta", "r"])
    th, h, dh, ddh = c["theta"], c["X_C"], c["dX_dtheta"], c["d2X_dtheta2"]
    beta, r = c["beta"], c["r"]
    if th.size == 0:
        raise InputError("%s: no rows" % path)
    info = cam_info(d)
    title = str(info.get("title") or "")
    if speed is None and isinstance(info.get("speed_rev_s"), (int, float)):
        speed = float(info["speed_rev_s"])

    # Profile: the contact point C at cam angle θ has polar angle β − θ in the cam frame.
    phi = beta - th
    x, y = r * np.cos(phi), r * np.sin(phi)
    x, y = np.append(x, x[:1]), np.append(y, y[:1])
    fig, ax = plt.subplots(figsize=(6, 6))
    ax.plot(x, y, "-", lw=1.5, label="profile (contact points)")
    ax.plot([0], [0], "k+", ms=10, label="centre of rotation O")
    rmin = float(np.min(r))
    a = np.linspace(0, 2 * math.pi, 361)
    ax.plot(rmin * np.cos(a), rmin * np.sin(a), ":", lw=0.8, color="gray",
            label="circle r = %.4g" % rmin)
    # The follower at θ = 0 (cam and fixed frames coincide): face, knife edge or roller.
    face = str(info.get("follower_face") or "flat")
    if str(info.get("follower_motion") or "") == "oscillating":
        # Oscillating follower: the pivot and the arm to the contact point at θ = 0.
        px, py = float(info.get("pivot_x") or 0.0), float(info.get("pivot_y") or 0.0)
        qx, qy = float(r[0] * np.cos(beta[0])), float(r[0] * np.sin(beta[0]))
        ax.plot([px], [py], "o", color="C3", label="pivot")
        ax.plot([px, qx], [py, qy], "-", lw=2.0, color="C3", label="arm to the contact (θ = 0)")
    elif face != "point" and np.all(np.isfinite(h[:1])):
        eps = float(info.get("follower_offset") or 0.0)
        rr = float(info.get("roller_radius") or 0.0)
        x0 = float(h[0])
        span = float(np.nanmax(r)) * 0.5
        if face == "flat":
            ax.plot([x0, x0], [-span, span], "-", lw=2.5, color="C3", label="flat face (θ = 0)")
        else:
            ax.plot([x0, x0 + span], [eps, eps], "-", lw=2.0, color="C3", label="%s (θ = 0)" % face)
            if face == "roller" and rr > 0:
                ax.plot(x0 + rr * np.cos(a), eps + rr * np.sin(a), "-", lw=1.5, color="C3")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (cam frame)")
    ax.set_ylabel("y (cam frame)")
    ax.set_title(("Cam profile\n" + title).strip())
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=3, fontsize="small")
    save(fig, os.path.join(d, "cam_profile.png"))

    # Kinematics at constant speed ω: X_C, Ẋ_C = h'ω, Ẍ_C = h''ω².
    deg = np.degrees(th)
    fig, axs = plt.subplots(3, 1, figsize=(8, 8), sharex=True)
    axs[0].plot(deg, h - np.min(h), "-")
    axs[0].set_ylabel("lift $X_C - \\min X_C$")
    if speed is not None and math.isfinite(speed) and speed != 0:
        w = 2 * math.pi * speed
        axs[1].plot(deg, dh * w, "-")
        axs[1].set_ylabel("velocity $\\dot X_C$")
        axs[2].plot(deg, ddh * w * w, "-")
        axs[2].set_ylabel("acceleration $\\ddot X_C$")
        fig.suptitle(("Cam kinematics at %.6g rev/s\n" % speed + title).strip())
    else:
        axs[1].plot(deg, dh, "-")
        axs[1].set_ylabel("$dX_C/d\\theta$")
        axs[2].plot(deg, ddh, "-")
        axs[2].set_ylabel("$d^2X_C/d\\theta^2$")
        fig.suptitle(("Cam kinematics (per radian of cam angle)\n" + title).strip())
    axs[2].set_xlabel("cam angle θ [deg]")
    axs[2].set_xlim(0, 360)
    for ax in axs:
        ax.grid(True, alpha=0.3)
    save(fig, os.path.join(d, "cam_kinematics.png"))

    # Jerk, pressure angle and radius of curvature (cam.csv columns of issue 24).
    if "d3X_dtheta3" in c and "pressure_angle" in c:
        fig, axs = plt.subplots(3, 1, figsize=(8, 8), sharex=True)
        axs[0].plot(deg, c["d3X_dtheta3"], "-")
        axs[0].set_ylabel("jerk $d^3X_C/d\\theta^3$")
        axs[1].plot(deg, np.degrees(c["pressure_angle"]), "-")
        axs[1].set_ylabel("pressure angle [deg]")
        if "rho" in c:
            axs[2].plot(deg, c["rho"], "-")
        axs[2].set_ylabel("radius of curvature ρ")
        axs[2].set_xlabel("cam angle θ [deg]")
        axs[2].set_xlim(0, 360)
        for ax in axs:
            ax.grid(True, alpha=0.3)
        cont = str(info.get("continuity") or "")
        fig.suptitle(("Cam geometry" + ("\njoints: " + cont if cont else "") + "\n" + title).strip(),
                     fontsize="small")
        save(fig, os.path.join(d, "cam_geometry.png"))


def main(argv=None):
    p = argparse.ArgumentParser(prog="camdyn_plot.py", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="mode")
    pr = sub.add_parser("run", help="figures from DIR/history.csv")
    pr.add_argument("dir")
    pr.add_argument("--zoom", nargs=2, type=float, metavar=("T0", "T1"),
                    help="time window of contact_force_zoom.png")
    pc = sub.add_parser("cam", help="figures from DIR/cam.csv")
    pc.add_argument("dir")
    pc.add_argument("--speed", type=float, default=None,
                    help="cam speed [rev/s] for velocity and acceleration")
    for q in (pr, pc):
        q.add_argument("--quiet", action="store_true", help="do not list the files written")
    a = p.parse_args(argv)
    global QUIET
    QUIET = bool(getattr(a, "quiet", False))
    if a.mode is None:
        p.print_help(sys.stderr)
        return 2
    try:
        if a.mode == "run":
            if a.zoom is not None and not a.zoom[0] < a.zoom[1]:
                raise InputError("--zoom: expected T0 < T1")
            plot_run(a.dir, a.zoom)
        else:
            plot_cam(a.dir, a.speed)
    except InputError as e:
        sys.stderr.write("camdyn_plot: %s\n" % e)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
