"""camdyn — cam–follower dynamics with impact, separation and elastic deformation.

Python front end of the C++ library (issue 17). A *scene* is one of

* a path to a TOML scene file (``str`` without ``=`` or a newline, or ``os.PathLike``),
* TOML text (a ``str`` containing ``=`` or a newline),
* a nested ``dict`` (tables as sub-dicts, e.g. ``{"cam": {"speed_rev_s": 3}}``),
* ``None``: the built-in default scene (the paper's case B2, as ``camdyn run``).

Overrides are dotted scene keys given as keyword arguments, exactly as the CLI's
``--set``: ``camdyn.run("examples/case_A.toml", **{"cam.speed_rev_s": 3})``. All overrides
are applied first and the scene is validated once, so their order never matters.

Bad input raises :class:`SceneError` (a :class:`ValueError`) whose message is the one the
CLI prints after ``camdyn: ``.

Example::

    import camdyn
    r = camdyn.run("examples/case_A.toml", **{"run.t_end": 0.2})
    r.summary["max_contact_force"], r.history["contact_force"], r.events
"""

from __future__ import annotations

import json
import math
import os
from typing import Any, Callable, Dict, Iterable, List, Mapping, Optional, Tuple

import numpy as np

from . import _camdyn
from ._camdyn import SceneError

__all__ = [
    "SceneError",
    "Result",
    "run",
    "resolved_scene",
    "jump_speed",
    "cam_motion",
    "run_batch",
    "sweep",
    "history_columns",
    "to_toml",
    "__version__",
]

__version__: str = _camdyn.__version__

#: History column names, in order (the columns of history.csv, energy columns included).
history_columns: Tuple[str, ...] = tuple(_camdyn.history_columns())


# ---- dict / value → TOML ---------------------------------------------------------------

def _toml_value(value: Any, where: str) -> str:
    """TOML text of one value (bool, int, float, str, or a sequence of numbers)."""
    if isinstance(value, (bool, np.bool_)):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        x = float(value)
        if math.isnan(x):
            return "nan"
        if math.isinf(x):
            return "inf" if x > 0 else "-inf"
        return repr(x)  # shortest round-trip text: the C++ side reads back the same double
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)  # a valid TOML basic string
    if isinstance(value, (list, tuple, np.ndarray)):
        return "[" + ", ".join(_toml_value(v, where) for v in value) + "]"
    raise TypeError(f"camdyn: {where}: cannot write a {type(value).__name__} as a TOML value")


def _toml_key(k: str) -> str:
    return k if k and all(c.isascii() and (c.isalnum() or c in "_-") for c in k) else json.dumps(k)


def to_toml(scene: Mapping[str, Any]) -> str:
    """TOML text of a nested dict scene (tables as sub-dicts, any depth)."""

    lines: List[str] = []

    def table(d: Mapping[str, Any], path: List[str]) -> None:
        subs = []
        if path:
            lines.append("[" + ".".join(_toml_key(p) for p in path) + "]")
        for k, v in d.items():
            if not isinstance(k, str):
                raise TypeError(f"camdyn: scene keys must be strings, got {k!r}")
            if isinstance(v, Mapping):
                subs.append((k, v))
            else:
                lines.append(f"{_toml_key(k)} = {_toml_value(v, '.'.join(path + [k]))}")
        for k, v in subs:
            table(v, path + [k])

    table(scene, [])
    return "\n".join(lines) + "\n"


def _flatten(prefix: str, value: Any, out: List[str]) -> None:
    if isinstance(value, Mapping):
        for k, v in value.items():
            _flatten(f"{prefix}.{k}", v, out)
    else:
        out.append(f"{prefix}={_toml_value(value, prefix)}")


def _assignments(overrides: Mapping[str, Any]) -> List[str]:
    """Keyword overrides → "dotted.key=value" assignments (values in TOML syntax).

    A dict value is flattened: ``cam={"speed_rev_s": 3}`` is ``cam.speed_rev_s=3``.
    """
    out: List[str] = []
    for key, value in overrides.items():
        _flatten(key, value, out)
    return out


def _scene_args(scene: Any) -> Tuple[str, str, str]:
    """(kind, text, source) for the C++ side."""
    if scene is None:
        return "default", "", "<built-in>"
    if isinstance(scene, Mapping):
        return "toml", to_toml(scene), "<dict>"
    if isinstance(scene, os.PathLike):
        return "file", os.fspath(scene), ""
    if isinstance(scene, bytes):
        scene = scene.decode()
    if isinstance(scene, str):
        if scene == "" or "=" in scene or "\n" in scene:
            return "toml", scene, "<string>"
        return "file", scene, ""
    raise TypeError(
        "camdyn: scene must be a TOML file path, TOML text, a dict or None, "
        f"not {type(scene).__name__}")


# ---- results ---------------------------------------------------------------------------

class Result:
    """The outcome of :func:`run`.

    Attributes:
        summary: dict with exactly the keys of summary.json (``finished``, ``message``,
            ``steps``, ``max_contact_force``, ``options`` — the resolved scene —, …).
        history: dict, history column name → 1-D ``numpy.float64`` array, one entry per
            output row (``in_contact`` as 0.0 / 1.0).
        events: list of dicts with keys ``t``, ``kind`` ("impact" | "separation" |
            "tensile"), ``impact_velocity``, ``theta``, ``impulse``.
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
        **overrides: Any) -> Result:
    """Run a scene to ``run.t_end`` and return a :class:`Result`.

    Args:
        scene: a TOML file path, TOML text, a nested dict, or None (built-in case B2).
        observer: optional callable, called with each history row as a dict
            (column → float) as it is computed, in order; every row of ``history`` is
            passed. Returning ``False`` (exactly) stops the run: the summary then says
            ``finished: false`` and ``"... stopped by caller"``. An exception raised by
            the observer stops the run and propagates.
        **overrides: dotted scene keys, e.g. ``**{"cam.speed_rev_s": 3}``.

    A simulation failure is not an exception: ``summary["finished"]`` is False and
    ``summary["message"]`` says where and why (what was computed is returned).
    The GIL is released while C++ integrates; Ctrl-C raises KeyboardInterrupt.

    Raises:
        SceneError: bad input (same message as the CLI).
    """
    if observer is not None and not callable(observer):
        raise TypeError("camdyn.run: observer must be callable")
    kind, text, source = _scene_args(scene)
    summary_text, history, events = _camdyn.run(kind, text, source, _assignments(overrides),
                                                observer)
    return Result(json.loads(summary_text), history, events)


def resolved_scene(scene: Any = None, **overrides: Any) -> str:
    """The scene as TOML with every default filled in (``camdyn scene --resolved``)."""
    kind, text, source = _scene_args(scene)
    return _camdyn.resolved_scene(kind, text, source, _assignments(overrides))


def jump_speed(scene: Any = None, options: Optional[Mapping[str, Any]] = None,
               **overrides: Any) -> Dict[str, Any]:
    """The jump (separation) speed at constant cam speed (``camdyn jump``).

    Closed form for a rigid follower, bisection over simulations for an elastic one.
    ``options`` may hold ``scan_points``, ``rel_tol``, ``lo_rev_s``, ``hi_rev_s``,
    ``force_simulation`` (designer.hpp, JumpOptions).

    Returns:
        dict with ``jump_speed_rev_s`` (+inf if it never separates), ``method``
        ("closed-form" | "simulation"), ``theta_deg``, ``lo_rev_s``, ``hi_rev_s``,
        ``simulations``.
    """
    kind, text, source = _scene_args(scene)
    return _camdyn.jump_speed(kind, text, source, _assignments(overrides), dict(options or {}))


def cam_motion(scene: Any, t: Any, **overrides: Any) -> Tuple[Any, Any, Any]:
    """Cam contact-point motion along X at time(s) ``t``: ``(X_C, Ẋ_C, Ẍ_C)``.

    The follower's face position, velocity and acceleration while it rides the cam
    (cam.hpp: Cam::motion with the drive θ(t), ω(t), ω̇(t)). ``t`` a float gives floats,
    an array gives arrays of its shape.
    """
    kind, text, source = _scene_args(scene)
    ta = np.asarray(t, dtype=np.float64)
    X, Xd, Xdd = _camdyn.cam_motion(kind, text, source, _assignments(overrides), ta.ravel())
    if ta.ndim == 0:
        return float(X[0]), float(Xd[0]), float(Xdd[0])
    return X.reshape(ta.shape), Xd.reshape(ta.shape), Xdd.reshape(ta.shape)


def run_batch(scenes: Iterable[Any], threads: int = 0) -> List[Dict[str, Any]]:
    """Run several scenes in C++ threads (``threads`` at a time; 0: all cores) and return
    their summaries (dicts with the summary.json keys), in order.

    Each item is a scene (path, TOML text, dict or None) or a pair ``(scene, overrides)``
    with ``overrides`` a dict of dotted keys. Every scene is built and checked before any
    run (bad input raises :class:`SceneError`); results do not depend on ``threads``
    (except the timings). Ctrl-C stops the runs and raises KeyboardInterrupt.
    """
    specs = []
    for item in scenes:
        if isinstance(item, tuple) and len(item) == 2 and isinstance(item[1], Mapping):
            scene, overrides = item
        else:
            scene, overrides = item, {}
        kind, text, source = _scene_args(scene)
        specs.append((kind, text, source, _assignments(overrides)))
    return [json.loads(t) for t in _camdyn.run_batch(specs, int(threads))]


#: Summary entries that :func:`sweep` returns as arrays (the numeric ones of sweep.csv).
SWEEP_COLUMNS = ("finished", "separations", "impacts", "max_contact_force", "min_contact_force",
                 "min_force_theta_deg", "first_separation_theta_deg", "max_impact_velocity",
                 "max_gap", "period", "steps", "cpu_seconds")


def sweep(scene: Any, key: str, values: Iterable[float], threads: int = 0,
          **overrides: Any) -> Dict[str, Any]:
    """Run ``scene`` once per value of the dotted ``key`` (like ``camdyn sweep``), in C++
    threads.

    Returns:
        dict: ``key`` → the values (float64 array), each name of :data:`SWEEP_COLUMNS` →
        a float64 array (``finished`` as 0/1, null as NaN), and ``"summaries"`` → the list
        of summary dicts.
    """
    vals = np.asarray(list(values), dtype=np.float64)
    sums = run_batch([(scene, {**overrides, key: float(v)}) for v in vals], threads)
    out: Dict[str, Any] = {key: vals}
    for c in SWEEP_COLUMNS:
        out[c] = np.array([np.nan if s.get(c) is None else float(s[c]) for s in sums],
                          dtype=np.float64)
    out["summaries"] = sums
    return out
