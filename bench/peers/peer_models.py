"""The peer models of bench/peers/peers.py: the same scenes as camdyn's, on Siconos
(Moreau–Jean time stepping) and MuJoCo (soft contacts, through bench/peers/mujoco_peer.cpp).

Both scenes are written in the frame of the cam's lift L(t): z1 = q_follower − L(t) is the
cam contact's gap, so the cam contact is a fixed unilateral constraint z1 ≥ 0 and the cam's
motion enters as a known external force (−m1·L̈, and the stem's k_s·L + c_s·L̇ on a
two-mass train). This change of variables is exact; it lets both peers use their plain
linear-time-invariant models (Siconos LagrangianLinearTIDS + LagrangianLinearTIR, MuJoCo
slide joints, a fixed tendon and two contact pairs) with the same cam as camdyn: the lift
table camdyn itself writes (`camdyn cam -n N`, Hermite-interpolated).

Scenes (parameters read from the TOML files the reference runs):
  two_mass: tappet m1 on the cam (plastic), stem k_s, c_s to the valve m2, valve spring
            k_v, c_v with preload P, seat z2 ≥ 0 with Newton restitution e.
  case_a:   METHOD.md case A: m, spring k with precompression δ0 (force k(u + δ0)), the
            follower stays on the cam; its contact force is the quantity compared.
"""
from __future__ import annotations

import csv
import math
import os
import subprocess
import time
from dataclasses import dataclass

import numpy as np


# --------------------------------------------------------------------------- the cam lift
@dataclass
class Lift:
    """L(t), L'(t), L''(t) of a cam at constant speed from camdyn's cam.csv (θ, X_C,
    dX/dθ, d²X/dθ²), L = X_C(θ) − X_C(θ0). Cubic Hermite on (X, X'), linear on X''."""
    theta: np.ndarray
    x: np.ndarray
    dx: np.ndarray
    d2x: np.ndarray
    omega: float
    theta0: float = 0.0

    @staticmethod
    def from_camdyn(camdyn: str, scene: str | None, case: str | None, out_dir: str, omega: float,
                    points: int = 72000) -> "Lift":
        os.makedirs(out_dir, exist_ok=True)
        path = os.path.join(out_dir, "cam.csv")
        if not os.path.exists(path):
            cmd = [camdyn, "cam", "-n", str(points), "--no-plot", "-q", "--out", out_dir]
            cmd += ["--case", case] if case else [scene]
            subprocess.run(cmd, check=True)
        data = np.genfromtxt(path, delimiter=",", names=True)
        th = np.append(data["theta"], 2 * math.pi)
        x = np.append(data["X_C"], data["X_C"][0])
        dx = np.append(data["dX_dtheta"], data["dX_dtheta"][0])
        d2x = np.append(data["d2X_dtheta2"], data["d2X_dtheta2"][0])
        return Lift(th, x, dx, d2x, omega)

    def table(self) -> np.ndarray:
        """Rows θ, X − X(0), dX/dθ, d²X/dθ² (the MuJoCo driver's input)."""
        return np.column_stack([self.theta, self.x - self.x[0], self.dx, self.d2x])

    def __call__(self, t: float) -> tuple[float, float, float]:
        th = (self.theta0 + self.omega * t) % (2 * math.pi)
        n = len(self.theta) - 1
        d = self.theta[1] - self.theta[0]
        i = min(int(th / d), n - 1)
        s = (th - self.theta[i]) / d
        x0, x1, m0, m1 = self.x[i], self.x[i + 1], self.dx[i] * d, self.dx[i + 1] * d
        h00, h10, h01, h11 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s, -2 * s**3 + 3 * s**2, s**3 - s**2
        X = h00 * x0 + h10 * m0 + h01 * x1 + h11 * m1 - self.x[0]
        dX = self.dx[i] + s * (self.dx[i + 1] - self.dx[i])
        d2X = self.d2x[i] + s * (self.d2x[i + 1] - self.d2x[i])
        w = self.omega
        return X, w * dX, w * w * d2X


# --------------------------------------------------------------------------- parameters
@dataclass
class TwoMass:
    m1: float = 0.045
    m2: float = 0.050
    ks: float = 1e6
    cs: float = 10.0
    kv: float = 35000.0
    cv: float = 2.0
    preload: float = 700.0
    e_seat: float = 0.3
    t_end: float = 0.04

    @staticmethod
    def from_toml(path: str) -> "TwoMass":
        try:
            import tomllib
        except ImportError:  # Python < 3.11
            import tomli as tomllib  # type: ignore
        with open(path, "rb") as f:
            s = tomllib.load(f)
        nodes = {n["name"]: n for n in s["nodes"]}
        el = {e["name"]: e for e in s["elements"]}
        seat = {c["name"]: c for c in s["contacts"]}["seat"]
        return TwoMass(nodes["tappet"]["mass"], nodes["valve"]["mass"], el["stem"]["stiffness"],
                       el["stem"].get("damping", 0.0), el["valve_spring"]["stiffness"],
                       el["valve_spring"].get("damping", 0.0), el["valve_spring"]["preload"],
                       seat.get("restitution", s["contact"].get("restitution", 0.0)), s["run"]["t_end"])


@dataclass
class CaseA:
    m: float = 1.0
    k: float = 500.0
    delta0: float = 7.0
    t_end: float = 1.0


@dataclass
class PeerRun:
    """A peer's trajectory: t and per column arrays (u_tappet, u_valve, v_valve, F_seat,
    F_cam or u_c, contact_force), its CPU seconds (stepping only), steps, and its seat
    impacts (t, speed before) as it resolves them."""
    t: np.ndarray
    cols: dict
    cpu: float
    steps: int
    impacts: list


# --------------------------------------------------------------------------- Siconos
def siconos_available() -> str | None:
    """None when importable, else the reason."""
    try:
        import siconos.kernel  # noqa: F401
    except Exception as ex:  # ImportError, or a broken install
        return f"python3-siconos not importable ({type(ex).__name__}: {ex})"
    return None


def _siconos_loop(M, K, C, rows, e_list, force, t_end, h, theta):
    """Moreau–Jean (θ) time stepping of M q̈ + C q̇ + K q = f(t) + Σ H_iᵀ λ_i, unilateral
    H_i q ≥ 0 with Newton impact laws e_i, an LCP per step. f(t) is set per step to
    θ f(t_{k+1}) + (1 − θ) f(t_k), the θ-weighting the scheme applies to a time-dependent
    force. Returns (t, q, v, impulses per step per contact, cpu)."""
    import siconos.kernel as sk
    n = M.shape[0]
    ds = sk.LagrangianLinearTIDS(np.zeros(n), np.zeros(n), M)
    ds.setKPtr(K)
    ds.setCPtr(C)
    fext = force(0.0)
    ds.setFExtPtr(fext)
    nsds = sk.NonSmoothDynamicalSystem(0.0, t_end)
    nsds.insertDynamicalSystem(ds)
    inters = []
    for H, e in zip(rows, e_list):
        inter = sk.Interaction(sk.NewtonImpactNSL(e), sk.LagrangianLinearTIR(np.array([H], dtype=float)))
        nsds.link(inter, ds)
        inters.append(inter)
    td = sk.TimeDiscretisation(0.0, h)
    osi = sk.MoreauJeanOSI(theta)
    lcp = sk.LCP()
    sim = sk.TimeStepping(nsds, td, osi, lcp)
    nsteps = int(round(t_end / h))
    T = np.zeros(nsteps + 1)
    Q = np.zeros((nsteps + 1, n))
    V = np.zeros((nsteps + 1, n))
    P = np.zeros((nsteps + 1, len(inters)))
    c0 = time.process_time()
    k = 0
    while sim.hasNextEvent() and k < nsteps:
        tk = sim.startingTime()
        ds.setFExtPtr(theta * force(tk + h) + (1 - theta) * force(tk))
        sim.computeOneStep()
        k += 1
        T[k] = sim.nextTime()
        Q[k] = ds.q()
        V[k] = ds.velocity()
        for j, inter in enumerate(inters):
            P[k, j] = inter.lambda_(1)[0]
        sim.nextStep()
    cpu = time.process_time() - c0
    P[0] = P[1]  # t = 0: the first step's impulse (the force is a step's mean)
    return T[: k + 1], Q[: k + 1], V[: k + 1], P[: k + 1], cpu


def _impacts(t, v_gap, impulse, min_speed):
    """Impacts of a time-stepping run: a step with an impulse after a step without one,
    the gap closing faster than min_speed at the step's start (t, speed before)."""
    out = []
    for k in range(2, len(t)):
        if impulse[k] > 0 and impulse[k - 1] <= 0 and v_gap[k - 1] < -min_speed:
            out.append((t[k - 1], -v_gap[k - 1]))
    return out


def siconos_two_mass(p: TwoMass, lift: Lift, h: float, theta: float = 0.5, min_speed: float = 1e-3) -> PeerRun:
    M = np.diag([p.m1, p.m2])
    K = np.array([[p.ks, -p.ks], [-p.ks, p.ks + p.kv]])
    C = np.array([[p.cs, -p.cs], [-p.cs, p.cs + p.cv]])

    def force(t):
        L, dL, d2L = lift(t)
        s = p.ks * L + p.cs * dL  # the stem's share of the cam's motion
        return np.array([-p.m1 * d2L - s, s - p.preload])

    T, Q, V, P, cpu = _siconos_loop(M, K, C, [[1.0, 0.0], [0.0, 1.0]], [0.0, p.e_seat], force, p.t_end, h, theta)
    L = np.array([lift(t)[0] for t in T])
    cols = {"u_tappet": Q[:, 0] + L, "u_valve": Q[:, 1], "v_valve": V[:, 1],
            "F_cam": P[:, 0] / h, "F_seat": P[:, 1] / h}
    return PeerRun(T, cols, cpu, len(T) - 1, _impacts(T, V[:, 1], P[:, 1], min_speed))


def siconos_case_a(p: CaseA, lift: Lift, h: float, theta: float = 0.5) -> PeerRun:
    M = np.array([[p.m]])
    K = np.array([[p.k]])
    C = np.array([[0.0]])

    def force(t):
        L, _, d2L = lift(t)
        return np.array([-p.m * d2L - p.k * (L + p.delta0)])

    T, Q, V, P, cpu = _siconos_loop(M, K, C, [[1.0]], [0.0], force, p.t_end, h, theta)
    L = np.array([lift(t)[0] for t in T])
    return PeerRun(T, {"u_c": Q[:, 0] + L, "contact_force": P[:, 0] / h}, cpu, len(T) - 1, [])


# --------------------------------------------------------------------------- MuJoCo
MUJOCO_SOURCE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "mujoco_peer.cpp")


def mujoco_driver(build_dir: str) -> tuple[str | None, str | None]:
    """(path of the MuJoCo driver, None) or (None, the reason it is not available). The
    driver is built by CMake when MuJoCo is found (target mujoco_peer); otherwise this
    compiles it into build_dir/peers when mujoco/mujoco.h and libmujoco are installed."""
    exe = os.path.join(build_dir, "bench", "peers", "mujoco_peer")
    if os.path.exists(exe):
        return exe, None
    own = os.path.join(build_dir, "peers", "mujoco_peer")
    if os.path.exists(own) and os.path.getmtime(own) >= os.path.getmtime(MUJOCO_SOURCE):
        return own, None
    if not os.path.exists("/usr/include/mujoco/mujoco.h"):
        return None, "MuJoCo not installed (no /usr/include/mujoco/mujoco.h: apt-get install libmujoco-dev)"
    os.makedirs(os.path.dirname(own), exist_ok=True)
    r = subprocess.run(["c++", "-O2", "-std=c++17", "-o", own, MUJOCO_SOURCE, "-lmujoco"],
                       capture_output=True, text=True)
    if r.returncode != 0:
        return None, "MuJoCo driver did not compile: " + r.stderr.strip().splitlines()[-1]
    return own, None


def restitution_damping_ratio(e: float) -> float:
    """Damping ratio ζ of a linear spring–damper whose bounce has restitution e:
    e = exp(−πζ/√(1 − ζ²)) ⇒ ζ = −ln e / √(π² + ln² e); e = 0: critical (1)."""
    if e <= 0:
        return 1.0
    le = math.log(e)
    return -le / math.sqrt(math.pi**2 + le * le)


def _run_mujoco(exe, args, table, work, tag):
    os.makedirs(work, exist_ok=True)
    tab = os.path.join(work, "lift_table.csv")
    if not os.path.exists(tab):
        np.savetxt(tab, table, delimiter=",")
    out = os.path.join(work, f"mujoco_{tag}.csv")
    r = subprocess.run([exe] + [str(a) for a in args] + [tab, out], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"mujoco_peer failed: {r.stderr.strip()}")
    info = dict(kv.split("=", 1) for kv in r.stdout.split())
    data = np.genfromtxt(out, delimiter=",", names=True)
    for f in ("f1", "f2"):
        data[f][0] = data[f][1]  # t = 0: the first step's force, as the other time-stepping rows
    return data, float(info["cpu"]), int(info["steps"])


def mujoco_two_mass(exe, p: TwoMass, lift: Lift, h: float, work: str, timeconst_steps: float = 5.0,
                    min_speed: float = 1e-3) -> PeerRun:
    """Seat and cam contacts with solref (timeconst = timeconst_steps·h, the smallest MuJoCo
    allows, dampratio from the restitution wanted), solimp (0.99, 0.99, 0.001): the
    constraint's reference dynamics is a spring–damper whose free bounce has restitution e."""
    zeta = restitution_damping_ratio(p.e_seat)
    args = ["two_mass", h, p.t_end, lift.omega, p.m1, p.m2, p.ks, p.cs, p.kv, p.cv, p.preload,
            timeconst_steps * h, zeta]
    d, cpu, steps = _run_mujoco(exe, args, lift.table(), work, f"two_mass_{h:g}")
    t = d["t"]
    cols = {"u_tappet": d["q1"] + np.array([lift(x)[0] for x in t]), "u_valve": d["q2"],
            "v_valve": d["v2"], "F_cam": d["f1"], "F_seat": d["f2"]}
    return PeerRun(t, cols, cpu, steps, _impacts(t, d["v2"], d["f2"], min_speed))


def mujoco_case_a(exe, p: CaseA, lift: Lift, h: float, work: str, timeconst_steps: float = 2.0) -> PeerRun:
    args = ["case_a", h, p.t_end, lift.omega, p.m, p.k, p.delta0, timeconst_steps * h, 1.0]
    d, cpu, steps = _run_mujoco(exe, args, lift.table(), work, f"case_a_{h:g}")
    t = d["t"]
    return PeerRun(t, {"u_c": d["q1"] + np.array([lift(x)[0] for x in t]), "contact_force": d["f1"]},
                   cpu, steps, [])


# --------------------------------------------------------------------------- camdyn's runs
def read_history(out_dir: str):
    data = np.genfromtxt(os.path.join(out_dir, "history.csv"), delimiter=",", names=True)
    events = []
    with open(os.path.join(out_dir, "events.csv"), newline="") as f:
        for r in csv.DictReader(f):
            events.append(r)
    return data, events
