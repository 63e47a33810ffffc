"""camdyn — cam–follower dynamics with impact, separation and elastic deformation.

Python front end of the C++ library (issue 17). A *scene* is one of

* a path to a TOML scene file (``str`` without ``=`` or a newline, or ``os.PathLike``),
* TOML text (a ``str`` containing ``=`` or a newline),
* a nested ``dict`` (tables as sub-dicts, e.g. ``{"cam": {"speed_rev_s": 3}}``),
* ``None``: the built-in default scene (the paper's case B2, as ``camdyn run``).

Overrides are dotted scene keys given as keyword arguments, exactly as the CLI's
``--set``: ``camdyn.run("examples/case_A.toml", **{"cam.speed_rev_s": 3})``; network entries
by name: ``**{"contacts.seat.restitution": 0.3}``. All overrides
are applied first and the scene is validated once, so their order never matters.

Bad input raises :class:`SceneError` (a :class:`ValueError`) whose message is the one the
CLI prints after ``camdyn:``.

Follower networks (valve trains, ``follower.kind = "network"``) run the same way; their
history also has ``F_<contact>``, ``gap_<contact>``, ``in_<contact>``, ``u_<node>``,
``v_<node>`` and their events a ``contact``. :func:`network_scene` builds one from Python
objects (dicts or :class:`Node`, :class:`Element`, :class:`Contact`).

Bring your own follower: ``run(scene, follower=obj)`` runs a follower defined by a Python
object (``size``, ``contacts``, ``mass``, ``force(t, q, v)``, optional ``jacobian``,
energies, ``initial_state``; see :func:`run`) in place of the scene's; the scene still
gives the cam, the contact method, the solver and the run.

Example::

    import camdyn
    r = camdyn.run("examples/case_A.toml", **{"run.t_end": 0.2})
    r.summary["max_contact_force"], r.history["contact_force"], r.events
    v = camdyn.run("examples/ohc_bucket_tappet.toml").history["u_valve"]
"""

from __future__ import annotations

import json
from typing import Any, Callable, Dict, Iterable, List, Mapping, Optional, Tuple

import numpy as np

from . import _camdyn
from ._camdyn import CubicSpringFollower, FollowerSystem, SceneError

__all__ = [
    "SceneError",
    "Result",
    "run",
    "resolved_scene",
    "jump_speed",
    "cam_motion",
    "order_spectrum",
    "campbell",
    "initial_state_on_cam",
    "run_batch",
    "sweep",
    "history_columns",
    "to_toml",
    "network_scene",
    "Node",
    "Element",
    "Contact",
    "FollowerContact",
    "CubicSpringFollower",
    "NETWORK_ARRAYS",
    "__version__",
]

__version__: str = _camdyn.__version__

#: History column names, in order (the columns of history.csv, energy columns included).
history_columns: Tuple[str, ...] = tuple(_camdyn.history_columns())


# ---- dict / value → TOML ---------------------------------------------------------------

from ._scene import (  # scenes as data: python/camdyn/_scene.py
    to_toml,
    NETWORK_ARRAYS,
    _scene_spec,
    Node,
    Element,
    Contact,
    network_scene,
    FollowerContact,
    _follower_spec,
)


class Result:
    """The outcome of :func:`run`.

    Attributes:
        summary: dict with exactly the keys of summary.json (``finished``, ``message``,
            ``steps``, ``max_contact_force``, ``options`` — the resolved scene —, …).
        history: dict, history column name → 1-D ``numpy.float64`` array, one entry per
            output row (``in_contact`` as 0.0 / 1.0). Network scenes then have the
            extra columns, in order: ``F_<c>``, ``gap_<c>``, ``in_<c>`` for each contact
            c, then ``u_<n>``, ``v_<n>`` for each node n (as history.csv).
        events: list of dicts with keys ``t``, ``kind`` ("impact" | "separation" |
            "tensile"), ``impact_velocity``, ``theta``, ``impulse``; network scenes also
            ``contact`` (the contact's name, as events.csv).

    ``summary["model"]["network"]`` (network scenes): the model description, one line per
    assembled element and contact.
    """

    __slots__ = ("summary", "history", "events")

    def __init__(self, summary: Dict[str, Any], history: Dict[str, np.ndarray],
                 events: List[Dict[str, Any]]):
        self.summary = summary
        self.history = history
        self.events = events

    @property
    def finished(self) -> bool:
        """``summary["finished"]``."""
        return bool(self.summary["finished"])

    def __repr__(self) -> str:
        s = self.summary
        return (f"<camdyn.Result {s.get('scene')!r}: finished={s.get('finished')}, "
                f"t_end={s.get('t_end')}, rows={len(self.history.get('t', ()))}, "
                f"events={len(self.events)}>")


# ---- API -------------------------------------------------------------------------------

def run(scene: Any = None, observer: Optional[Callable[[Dict[str, float]], Any]] = None,
        follower: Any = None, **overrides: Any) -> Result:
    """Run a scene to ``run.t_end`` and return a :class:`Result`.

    Args:
        scene: a TOML file path, TOML text, a nested dict, or None (built-in case B2).
        observer: optional callable, called with each history row as a dict
            (column → float) as it is computed, in order; every row of ``history`` is
            passed. Returning ``False`` (exactly) stops the run: the summary then says
            ``finished: false`` and ``"... stopped by caller"``. An exception raised by
            the observer stops the run and propagates.
        follower: optional user-defined follower replacing the scene's (``follower.*``,
            ``[spring]`` and the network tables are then not used): a Python object with

            * ``size``: the number n of unknowns q (an int, or a method returning it);
            * ``contacts``: list of :class:`FollowerContact` or dicts with its keys
              (attribute or method);
            * ``mass``: the constant, symmetric positive definite mass matrix M (n × n;
              a 1-D array is its diagonal, a number m·I) — attribute or method, read once;
            * ``force(t, q, v)``: r, every force on the follower but the contacts'
              (n values; q, v are fresh float64 arrays), so that M q̈ = r + Σ rowᵀ F;
            * optional ``jacobian(t, q, v)`` → ``(dr_dq, dr_dv)`` (n × n each; dr_dv may be
              None): used by the implicit engines (else difference quotients);
            * optional ``kinetic_energy(v)`` (default ½ vᵀ M v), ``potential_energy(q)``
              (default: none, the energy balance is then not checked),
              ``damping_power(v)``, ``initial_state()`` → ``(q0, v0)`` (default rest at 0),
              ``linear`` (True only if r is affine in q, v with constant coefficients),
              ``name``.

            Or a follower written in C++ (a ``camdyn._camdyn.FollowerSystem``, e.g.
            :class:`CubicSpringFollower`). The history then has the extra columns
            ``F_<c>``, ``gap_<c>``, ``in_<c>`` per contact, ``u_q<i>``, ``v_q<i>`` per
            unknown; events have ``contact``. The methods are called from the integrating
            thread with the GIL taken: about 1.2 µs more per call than C++, a run 5–8×
            slower than the same follower in C++ (README "Bring your own follower").
            An exception raised in one ends the
            run: ``summary["finished"]`` is False, ``summary["termination"]`` "error" and
            ``summary["message"]`` "at t = T: Python follower: force(t, q, v) raised
            ValueError: ..." (KeyboardInterrupt propagates). A mapping here is still the
            ``follower.*`` override it always was.
        **overrides: dotted scene keys, e.g. ``**{"cam.speed_rev_s": 3}``.

    A simulation failure is not an exception: ``summary["finished"]`` is False and
    ``summary["message"]`` says where and why (what was computed is returned).
    The GIL is released while C++ integrates; Ctrl-C raises KeyboardInterrupt.

    Raises:
        SceneError: bad input (same message as the CLI).
    """
    if observer is not None and not callable(observer):
        raise TypeError("camdyn.run: observer must be callable")
    if isinstance(follower, Mapping):  # follower={"mass": ...}: the follower.* override
        overrides = {**overrides, "follower": follower}
        follower = None
    spec = None if follower is None else _follower_spec(follower)
    kind, text, source, assignments = _scene_spec(scene, overrides)
    summary_text, history, events = _camdyn.run(kind, text, source, assignments, observer, spec)
    return Result(json.loads(summary_text), history, events)


def resolved_scene(scene: Any = None, **overrides: Any) -> str:
    """The scene as TOML with every default filled in (``camdyn scene --resolved``).

    Checked as ``camdyn scene`` and the start of :func:`run` check it (the same
    :class:`SceneError` for the same scene): a scene it returns, :func:`run` starts.
    """
    return _camdyn.resolved_scene(*_scene_spec(scene, overrides))


def jump_speed(scene: Any = None, options: Optional[Mapping[str, Any]] = None,
               follower: Any = None, **overrides: Any) -> Dict[str, Any]:
    """The jump (separation) speed at constant cam speed (``camdyn jump``).

    Closed form for a rigid follower; otherwise the speed-range map (docs/guide/sweeps.md):
    trial speeds on a grid, run in parallel, each for jump.settle_revolutions +
    jump.judge_revolutions revolutions, every boundary where a phenomenon appears or
    disappears bisected to ``rel_tol``. ``options`` may hold ``scan_points``, ``rel_tol``,
    ``lo_rev_s``, ``hi_rev_s``, ``grid_points``, ``jobs``, ``force_simulation``
    (designer.hpp, JumpOptions).

    ``follower``: a user-defined follower as for :func:`run` (a Python object or a C++
    ``FollowerSystem``); it replaces the scene's (never ignored): the map of its verdict,
    the range from 0.5× and 1.5× the scene's speed unless ``options`` give it; a Python
    follower's trials run one after the other (``jobs`` = 1).
    A mapping is the ``follower.*`` override, as for :func:`run`.

    Returns:
        dict with ``jump_speed_rev_s`` (the lowest separation speed; +inf if it never
        separates), ``method`` ("closed-form" | "simulation"), ``theta_deg``,
        ``lo_rev_s``, ``hi_rev_s``, ``simulations``, ``phenomenon``, ``phenomenon_text``;
        simulation also ``bands`` (dicts: ``kind``, ``contact``, ``theta_deg``,
        ``from_out_rev_s``, ``from_in_rev_s``, ``to_in_rev_s``, ``to_out_rev_s``; NaN for
        an end outside the range), ``trials`` (``speed_rev_s``, ``finished``, ``kinds``,
        ``text``), ``monotone``, ``monotone_text``, ``grid_simulations``,
        ``failed_simulations``, ``range_lo_rev_s``, ``range_hi_rev_s``,
        ``grid_spacing_rev_s``, ``text``.
    """
    if isinstance(follower, Mapping):
        overrides = {**overrides, "follower": follower}
        follower = None
    spec = None if follower is None else _follower_spec(follower)
    return _camdyn.jump_speed(*_scene_spec(scene, overrides), dict(options or {}), spec)


def order_spectrum(theta: Any, y: Any, revolutions: int = 0, samples_per_revolution: int = 1024,
                   max_order: float = 64.0) -> Dict[str, Any]:
    """Order spectrum of samples ``y`` against the cam angle ``theta`` [rad] (a history's
    ``theta`` column and any other), as ``camdyn spectrum`` (camdyn/spectrum.hpp): the
    record resampled uniformly in cam angle over the last ``revolutions`` complete
    revolutions (0: all), its DFT in cam orders.

    Returns:
        dict with ``order``, ``amplitude`` (the mean at order 0, else the single-sided
        amplitude), ``phase_deg``, ``revolutions``.

    Raises:
        SceneError: a non-monotone ``theta``, sizes that differ, less than one revolution.
    """
    return _camdyn.order_spectrum([float(v) for v in theta], [float(v) for v in y], int(revolutions),
                                  int(samples_per_revolution), float(max_order))


def campbell(scene: Any, speeds_rev_s: Any, column: str = "contact_force", settle_revolutions: int = 2,
             revolutions: int = 2, samples_per_revolution: int = 512, max_order: float = 32.0,
             threads: int = 0, **overrides: Any) -> Dict[str, Any]:
    """Campbell diagram, as ``camdyn campbell`` (camdyn/campbell.hpp): ``scene`` run at each
    camshaft speed of ``speeds_rev_s`` (settle, then analysed revolutions), the order
    spectrum of ``column`` at each speed, and the surge frequencies of the springs with
    coil masses.

    Returns:
        dict with ``column``, ``speed_rev_s``, ``order``, ``amplitude`` (one list per
        speed), ``lines`` (dicts ``name``, ``frequency_hz``).

    Raises:
        SceneError: bad options (naming the option), an invalid scene, an unknown column,
            a run that did not finish.
    """
    opts = {"column": column, "speeds_rev_s": [float(v) for v in speeds_rev_s],
            "settle_revolutions": int(settle_revolutions), "revolutions": int(revolutions),
            "samples_per_revolution": int(samples_per_revolution), "max_order": float(max_order),
            "threads": int(threads)}
    return _camdyn.campbell(*_scene_spec(scene, overrides), opts)


def cam_motion(scene: Any, t: Any, lift: bool = False, **overrides: Any) -> Tuple[Any, Any, Any]:
    """Cam contact-point motion along X at time(s) ``t``: ``(X_C, Ẋ_C, Ẍ_C)``.

    ``lift=False``: X_C is absolute, the flat face's distance from the cam's centre O
    (cam.hpp: Cam::motion with the drive θ(t), ω(t), ω̇(t)); a rigid or elastic_bar
    follower's gap is ``u_c − X_C``.
    ``lift=True``: X_C − X_base, the lift above the base circle that a network's or a user
    follower's cam contact subtracts in its gap ``row · q + clearance − lift``; X_base is
    ``cam.base_radius`` for a "lift" profile and the smallest X_C over a revolution for
    "points" (e.g. 1.9807 for the paper's cam, whose knots sit at 2.0) and "circle"
    (R − e). Ẋ_C and Ẍ_C are the same either way. ``t`` a float gives floats, an array
    gives arrays of its shape.
    """
    ta = np.asarray(t, dtype=np.float64)
    X, Xd, Xdd = _camdyn.cam_motion(*_scene_spec(scene, overrides), ta.ravel(), bool(lift))
    if ta.ndim == 0:
        return float(X[0]), float(Xd[0]), float(Xdd[0])
    return X.reshape(ta.shape), Xd.reshape(ta.shape), Xdd.reshape(ta.shape)


def initial_state_on_cam(scene: Any, follower: Any, **overrides: Any) -> Tuple[Any, Any]:
    """``(q0, v0)`` that put a user follower on the cam at t = 0.

    The follower's own ``initial_state()`` (default rest at 0) moved by the smallest
    M-weighted correction that closes every cam contact (gap 0 and gap rate 0 against
    ``cam_motion(scene, 0, lift=True)``) and keeps the gaps and rates of the other
    contacts. Return it from the follower's ``initial_state()`` to start held on the cam
    (C++: ``camdyn::initial_state_on_cam``, include/camdyn/initial_state.hpp).

    Raises:
        SceneError: a bad follower or cam, or a follower without a cam contact.
    """
    q, v = _camdyn.initial_state_on_cam(*_scene_spec(scene, overrides), _follower_spec(follower))
    return np.asarray(q), np.asarray(v)


def _batch_items(scenes: Iterable[Any]) -> List[Tuple[Any, Mapping[str, Any]]]:
    items = []
    for item in scenes:
        if isinstance(item, tuple) and len(item) == 2 and isinstance(item[1], Mapping):
            items.append(item)
        else:
            items.append((item, {}))
    return items


def run_batch(scenes: Iterable[Any], threads: int = 0, follower: Any = None) -> List[Dict[str, Any]]:
    """Run several scenes in C++ threads (``threads`` at a time; 0: all cores) and return
    their summaries (dicts with the summary.json keys), in order.

    Each item is a scene (path, TOML text, dict or None) or a pair ``(scene, overrides)``
    with ``overrides`` a dict of dotted keys. Every scene is built and checked before any
    run (bad input raises :class:`SceneError`); results do not depend on ``threads``
    (except the timings). Ctrl-C stops the runs and raises KeyboardInterrupt.

    ``follower``: a user-defined follower as for :func:`run`, used by every run instead of
    the scenes' own. Its methods are called with the GIL held, so the runs are made one
    after the other on this thread (``threads`` must be 0 or 1; more raises
    :class:`SceneError`). A C++ ``FollowerSystem`` runs the same way.
    """
    items = _batch_items(scenes)
    specs = [_scene_spec(scene, overrides) for scene, overrides in items]
    if follower is None:
        return [json.loads(t) for t in _camdyn.run_batch(specs, int(threads))]
    if int(threads) not in (0, 1):
        raise SceneError(f"camdyn.run_batch: key 'threads' = {int(threads)}: a user follower runs on one "
                         "thread (its methods are called with the GIL held): must be 0 or 1")
    for spec in specs:  # every scene checked before any run
        _camdyn.resolved_scene(*spec)
    return [run(scene, follower=follower, **overrides).summary for scene, overrides in items]


#: Summary entries that :func:`sweep` returns as arrays (the numeric ones of sweep.csv).
SWEEP_COLUMNS = ("finished", "separations", "impacts", "max_contact_force", "min_contact_force",
                 "min_force_theta_deg", "first_separation_theta_deg", "max_impact_velocity",
                 "max_gap", "period", "steps", "cpu_seconds")


def sweep(scene: Any, key: str, values: Iterable[float], threads: int = 0,
          follower: Any = None, **overrides: Any) -> Dict[str, Any]:
    """Run ``scene`` once per value of the dotted ``key`` (like ``camdyn sweep``), in C++
    threads. A network entry's key by name works too: ``"elements.valve_spring.preload"``.

    ``follower``: a user-defined follower for every run (:func:`run_batch`: one thread);
    keys of ``follower.*``, ``[spring]`` and the network tables are then refused.

    Returns:
        dict: ``key`` → the values (float64 array), each name of :data:`SWEEP_COLUMNS` →
        a float64 array (``finished`` as 0/1, null as NaN), for each acceptance criterion
        of the scene ``criterion_<name>_value`` and ``criterion_<name>_pass`` (1/0, NaN when
        not judged), and ``"summaries"`` → the list of summary dicts.
    """
    if isinstance(follower, Mapping):
        overrides = {**overrides, "follower": follower}
        follower = None
    if follower is not None and (key.startswith(("follower.", "spring.", "nodes", "elements", "contacts"))):
        raise SceneError(f"--key: key 'key' = {key}: is replaced by the user follower (follower.*, [spring] "
                         "and the network tables are not used): sweeping it would change nothing")
    vals = np.asarray(list(values), dtype=np.float64)
    sums = run_batch([(scene, {**overrides, key: float(v)}) for v in vals], threads, follower)
    out: Dict[str, Any] = {key: vals}
    for c in SWEEP_COLUMNS:
        out[c] = np.array([np.nan if s.get(c) is None else float(s[c]) for s in sums],
                          dtype=np.float64)
    # the scene's acceptance criteria ([criteria]), as sweep.csv's criterion columns
    names = []
    for s in sums:
        for c in s.get("criteria") or []:
            if c["name"] not in names:
                names.append(c["name"])
    for n in names:
        val, ok = [], []
        for s in sums:
            c = next((x for x in s.get("criteria") or [] if x["name"] == n), None)
            judged = c is not None and c.get("value") is not None
            val.append(float(c["value"]) if judged else np.nan)
            ok.append((1.0 if c["pass"] else 0.0) if judged else np.nan)
        out["criterion_%s_value" % n] = np.array(val, dtype=np.float64)
        out["criterion_%s_pass" % n] = np.array(ok, dtype=np.float64)
    out["summaries"] = sums
    return out
