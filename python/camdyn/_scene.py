"""camdyn (private module): scenes as data — TOML text from dicts and dataclasses, the
network entries (Node, Element, Contact, network_scene), a Python follower's contacts and
its spec for the bindings. Re-exported by camdyn/__init__.py."""
from __future__ import annotations
import dataclasses
import json
import math
import os
from typing import Any, Dict, Iterable, List, Mapping, Optional, Sequence, Tuple
import numpy as np
from . import _camdyn
from ._camdyn import FollowerSystem, SceneError


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
    if _is_dataclass_instance(value):
        value = _entry_dict(value)
    if isinstance(value, Mapping):  # an inline table (e.g. an entry of an array of tables)
        return "{" + ", ".join(f"{_toml_key(k)} = {_toml_value(v, f'{where}.{k}')}"
                               for k, v in value.items() if v is not None) + "}"
    if isinstance(value, (list, tuple, np.ndarray)):
        return "[" + ", ".join(_toml_value(v, where) for v in value) + "]"
    raise TypeError(f"camdyn: {where}: cannot write a {type(value).__name__} as a TOML value")


def _toml_key(k: str) -> str:
    return k if k and all(c.isascii() and (c.isalnum() or c in "_-") for c in k) else json.dumps(k)


def _is_dataclass_instance(x: Any) -> bool:
    return dataclasses.is_dataclass(x) and not isinstance(x, type)


def _entry_dict(entry: Any) -> Dict[str, Any]:
    """A network entry (a mapping or a :class:`Node` / :class:`Element` / :class:`Contact`)
    as a dict; dataclass fields left at None are left out (the library's default)."""
    if _is_dataclass_instance(entry):
        return {f.name: getattr(entry, f.name) for f in dataclasses.fields(entry)
                if getattr(entry, f.name) is not None}
    if isinstance(entry, Mapping):
        return dict(entry)
    raise TypeError(f"camdyn: a network entry must be a dict or a camdyn.Node/Element/Contact, "
                    f"not {type(entry).__name__}")


def _is_table_array(v: Any) -> bool:
    """A non-empty list/tuple of dicts (or entry dataclasses): a TOML array of tables."""
    return (isinstance(v, (list, tuple)) and len(v) > 0
            and all(isinstance(x, Mapping) or _is_dataclass_instance(x) for x in v))


def to_toml(scene: Mapping[str, Any]) -> str:
    """TOML text of a nested dict scene (tables as sub-dicts, any depth; a list of dicts —
    the network's ``nodes``, ``elements``, ``contacts`` — as an array of tables
    ``[[nodes]]``, in list order)."""

    lines: List[str] = []

    def body(d: Mapping[str, Any], path: List[str]) -> None:
        subs, arrays = [], []
        for k, v in d.items():
            if not isinstance(k, str):
                raise TypeError(f"camdyn: scene keys must be strings, got {k!r}")
            if v is None:  # left out: the library's default
                continue
            if isinstance(v, Mapping):
                subs.append((k, v))
            elif _is_table_array(v):
                arrays.append((k, v))
            else:
                lines.append(f"{_toml_key(k)} = {_toml_value(v, '.'.join(path + [k]))}")
        # Sub-tables and arrays of tables after the keys (a key after a header would
        # belong to that table).
        for k, v in subs:
            lines.append("[" + ".".join(_toml_key(p) for p in path + [k]) + "]")
            body(v, path + [k])
        for k, v in arrays:
            for entry in v:
                lines.append("[[" + ".".join(_toml_key(p) for p in path + [k]) + "]]")
                body(_entry_dict(entry), path + [k])

    body(scene, [])
    return "\n".join(lines) + "\n"


def _flatten(prefix: str, value: Any, out: List[str]) -> None:
    if isinstance(value, Mapping):
        for k, v in value.items():
            _flatten(f"{prefix}.{k}", v, out)
    else:
        out.append(f"{prefix}={_toml_value(value, prefix)}")


def _scene_error(key: str, value: Any, rule: str, file: str = "<python>") -> "SceneError":
    """A :class:`SceneError` raised on the Python side, shaped as the library's."""
    e = SceneError(f"{file}: key '{key}' = {value!r}: {rule}")
    e.file, e.line, e.key, e.value, e.rule = file, 0, key, repr(value), rule
    return e


def _checked_text(key: str, text: str) -> str:
    """``text`` if it can cross to the C++ side (UTF-8, no NUL), else a :class:`SceneError`."""
    try:
        text.encode("utf-8")
    except UnicodeEncodeError as err:
        raise _scene_error(key, text, f"is not valid text (a lone surrogate at position {err.start}): "
                           "paths, TOML text and values must be encodable as UTF-8") from None
    if "\0" in text:
        raise _scene_error(key, text, f"contains a NUL character at position {text.index(chr(0))}: "
                           "no file path or TOML text holds one")
    return text


def _assignments(overrides: Mapping[str, Any]) -> List[str]:
    """Keyword overrides → "dotted.key=value" assignments (values in TOML syntax).

    A dict value is flattened: ``cam={"speed_rev_s": 3}`` is ``cam.speed_rev_s=3``.
    """
    out: List[str] = []
    for key, value in overrides.items():
        if not isinstance(key, str):
            raise TypeError(f"camdyn: override keys are strings, not {type(key).__name__}")
        _flatten(key, value, out)
    return [_checked_text(a.split("=", 1)[0], a) for a in out]


#: The network's arrays of tables; as keyword overrides they replace the whole array.
NETWORK_ARRAYS = ("nodes", "elements", "contacts")


def _scene_spec(scene: Any, overrides: Mapping[str, Any]) -> Tuple[str, str, str, List[str]]:
    """(kind, text, source, assignments) for the C++ side.

    Network entries are addressed by name or index like any dotted key
    (``**{"contacts.seat.restitution": 0.3}``, ``**{"elements[1].preload": 300}``), or as a
    dict by name (``contacts={"seat": {"restitution": 0.3}}``).
    ``nodes=[...]``, ``elements=[...]``, ``contacts=[...]`` overrides (lists: the CLI's
    ``--set`` has no such keys) replace the scene's array: the scene is taken as a dict (a file or
    TOML text through its resolved form, which needs Python ≥ 3.11's tomllib), the arrays
    replaced, and the result passed as a dict scene (source ``<dict>``).
    """
    # A dict value addresses entries by name: contacts={"seat": {"restitution": 0.3}} is
    # contacts.seat.restitution=0.3 (as "contacts.seat.restitution": 0.3).
    arrays = {k: v for k, v in overrides.items() if k in NETWORK_ARRAYS and not isinstance(v, Mapping)}
    rest = {k: v for k, v in overrides.items() if k not in arrays}
    if arrays:
        if isinstance(scene, Mapping):
            base = dict(scene)
        else:
            try:
                import tomllib
            except ImportError as e:  # Python < 3.11
                raise TypeError("camdyn: nodes/elements/contacts overrides need a dict scene "
                                "(or Python >= 3.11 for a file or TOML text)") from e
            kind, text, source = _scene_args(scene)
            base = tomllib.loads(_camdyn.scene_toml(kind, text, source, []))
        for k, v in arrays.items():
            if not isinstance(v, (list, tuple)):
                raise TypeError(f"camdyn: {k}={v!r}: must be a list of [[{k}]] entries (dicts or "
                                f"dataclasses), or a dict by name ({k}={{\"NAME\": {{\"KEY\": value}}}}), "
                                f"not {type(v).__name__}")
            base[k] = [_entry_dict(e) for e in v]
        scene = base
    return (*_scene_args(scene), _assignments(rest))


def _scene_args(scene: Any) -> Tuple[str, str, str]:
    """(kind, text, source) for the C++ side."""
    if scene is None:
        return "default", "", "<built-in>"
    if isinstance(scene, Mapping):
        return "toml", to_toml(scene), "<dict>"
    if isinstance(scene, os.PathLike):
        path = os.fspath(scene)
        if isinstance(path, bytes):
            path = os.fsdecode(path)
        return "file", _checked_text("scene", path), ""
    if isinstance(scene, bytes):
        try:
            scene = scene.decode()
        except UnicodeDecodeError as err:
            raise _scene_error("scene", scene[:40], f"is not UTF-8 (byte {err.start}): a scene is a "
                               "TOML file path or TOML text") from None
    if isinstance(scene, str):
        _checked_text("scene", scene)
        if scene.strip() == "":
            raise _scene_error("scene", scene, "is empty: give a TOML file path, TOML text, a dict, "
                               "or None for the built-in scene")
        if "=" in scene or "\n" in scene:
            return "toml", scene, "<string>"
        return "file", scene, ""
    raise TypeError(
        "camdyn: scene must be a TOML file path, TOML text, a dict or None, "
        f"not {type(scene).__name__}")


# ---- networks (valve trains): a user-defined follower from Python objects -------------

@dataclasses.dataclass
class Node:
    """A ``[[nodes]]`` entry (docs/interface.md "Networks"). None: the library default."""
    name: str
    mass: Optional[float] = None
    initial_displacement: Optional[float] = None
    initial_velocity: Optional[float] = None


@dataclasses.dataclass
class Element:
    """An ``[[elements]]`` entry: ``type`` "spring" | "dashpot" | "bar" | "lever",
    ``nodes`` = [lower, upper] ([input, output] for a lever; "ground" may end a spring,
    dashpot or bar). Only the keys of its type may be set (others stay None)."""
    type: str
    nodes: Sequence[str]
    name: Optional[str] = None
    stiffness: Optional[float] = None
    preload: Optional[float] = None
    damping: Optional[float] = None
    mass: Optional[float] = None
    masses: Optional[int] = None
    youngs_modulus: Optional[float] = None
    area: Optional[float] = None
    length: Optional[float] = None
    elements: Optional[int] = None
    mass_matrix: Optional[str] = None
    rayleigh_alpha: Optional[float] = None
    rayleigh_beta: Optional[float] = None
    ratio: Optional[float] = None


@dataclasses.dataclass
class Contact:
    """A ``[[contacts]]`` entry: ``type`` "cam" ([node]) | "lash" ([lower, upper]) |
    "stop" ([node], ``side`` "below" | "above"). Its history columns are F_<name>,
    gap_<name>, in_<name>."""
    name: str
    type: str
    nodes: Sequence[str]
    clearance: Optional[float] = None
    side: Optional[str] = None
    restitution: Optional[float] = None
    penalty_stiffness: Optional[float] = None
    penalty_damping: Optional[float] = None


def network_scene(nodes: Iterable[Any], elements: Iterable[Any] = (),
                  contacts: Iterable[Any] = (), cam: Optional[Mapping[str, Any]] = None,
                  title: Optional[str] = None, validate: bool = True,
                  **tables: Any) -> Dict[str, Any]:
    """A network scene (``follower.kind = "network"``) as a dict, from Python objects.

    Args:
        nodes, elements, contacts: the ``[[nodes]]``, ``[[elements]]``, ``[[contacts]]``
            entries, in order: dicts with the TOML keys, or :class:`Node`,
            :class:`Element`, :class:`Contact`.
        cam: the ``[cam]`` table (None: the library's default cam).
        title: the scene title.
        validate: check the scene now (raises :class:`SceneError` with the library's
            message, source ``<dict>``); else at the first use.
        **tables: other tables, e.g. ``contact={"model": "lee"}``,
            ``run={"t_end": 0.1}``, ``solver={...}``; ``follower`` is merged with
            ``kind = "network"``.

    Returns:
        the scene dict, usable wherever a scene is (:func:`run`, :func:`resolved_scene`,
        :func:`to_toml`, …); it is the scene the equivalent TOML file describes.
    """
    scene: Dict[str, Any] = {}
    if title is not None:
        scene["title"] = title
    if cam is not None:
        scene["cam"] = dict(cam)
    follower = dict(tables.pop("follower", None) or {})
    follower["kind"] = "network"
    scene["follower"] = follower
    scene.update(tables)
    scene["nodes"] = [_entry_dict(n) for n in nodes]
    scene["elements"] = [_entry_dict(e) for e in elements]
    scene["contacts"] = [_entry_dict(c) for c in contacts]
    if validate:
        from . import resolved_scene  # the package's (it runs the library's checks)
        resolved_scene(scene)
    return scene



# ---- bring your own follower (issue 17): a Python object as the follower ----------------

@dataclasses.dataclass
class FollowerContact:
    """One contact of a user-defined follower (C++ ``camdyn::FollowerContact``).

    The gap is ``row · q + clearance − X_L(t)`` for a cam contact and ``row · q + clearance``
    for a stop (``cam=False``). X_L is the cam's lift above its base circle,
    ``cam_motion(scene, t, lift=True)[0]``: X_C − cam.base_radius for a "lift" profile,
    X_C − min over θ of X_C for "points" and "circle" (not the absolute X_C that
    ``cam_motion(scene, t)`` gives). A start below the cam (gap < −contact.tol_u at t = 0)
    raises :class:`SceneError`; :func:`initial_state_on_cam` gives the state on the cam. The contact
    force F ≥ 0 acts on the follower as ``rowᵀ F``. History columns: ``F_<name>``,
    ``gap_<name>``, ``in_<name>``. None: the scene's ``[contact]`` value."""
    name: str
    row: Sequence[float]
    clearance: float = 0.0
    cam: bool = True
    restitution: Optional[float] = None
    penalty_stiffness: Optional[float] = None
    penalty_damping: Optional[float] = None


_CONTACT_KEYS = tuple(f.name for f in dataclasses.fields(FollowerContact))


def _member(obj: Any, name: str) -> Any:
    """``obj.name``, called if it is a method (``size``, ``contacts``, ``mass``, ``linear``,
    ``name`` may be plain attributes or methods without arguments); None if absent."""
    value = getattr(obj, name, None)
    if callable(value) and not isinstance(value, type):
        value = value()
    return value


def _follower_spec(follower: Any) -> Any:
    """The spec dict the C++ adapter (camdyn._camdyn, PyFollower) reads, from a Python
    follower object; a follower made in C++ (a ``camdyn._camdyn.FollowerSystem``) as is."""
    if isinstance(follower, FollowerSystem):
        return follower
    where = f"camdyn.run: follower ({type(follower).__name__})"
    size = _member(follower, "size")
    if size is None:
        raise TypeError(f"{where} has no 'size'")
    n = int(size)
    force = getattr(follower, "force", None)
    if not callable(force):
        raise TypeError(f"{where} has no method force(t, q, v)")
    contacts_in = _member(follower, "contacts")
    if contacts_in is None:
        raise TypeError(f"{where} has no 'contacts'")
    contacts = []
    for i, c in enumerate(contacts_in):
        d = _entry_dict(c) if not isinstance(c, FollowerContact) else dataclasses.asdict(c)
        unknown = set(d) - set(_CONTACT_KEYS)
        if unknown:
            raise TypeError(f"{where}: contacts[{i}] has unknown keys {sorted(unknown)}; "
                            f"allowed: {', '.join(_CONTACT_KEYS)}")
        if "name" not in d or "row" not in d:
            raise TypeError(f"{where}: contacts[{i}] needs 'name' and 'row'")
        full = {"clearance": 0.0, "cam": True, **d}
        full["row"] = [float(x) for x in np.atleast_1d(np.asarray(full["row"], dtype=np.float64))]
        contacts.append(full)
    mass = _member(follower, "mass")
    if mass is None:
        raise TypeError(f"{where} has no 'mass' (a constant mass matrix)")
    M = np.asarray(mass, dtype=np.float64)
    if M.ndim == 0:
        M = float(M) * np.eye(n)
    elif M.ndim == 1:
        M = np.diag(M)
    init = getattr(follower, "initial_state", None)
    if init is not None:
        q0, v0 = init() if callable(init) else init
        init = (np.atleast_1d(np.asarray(q0, dtype=np.float64)).tolist(),
                np.atleast_1d(np.asarray(v0, dtype=np.float64)).tolist())
    name = _member(follower, "name")

    def optional(attr: str) -> Any:
        fn = getattr(follower, attr, None)
        if fn is not None and not callable(fn):
            raise TypeError(f"{where}: '{attr}' must be a method")
        return fn

    return {
        "size": n,
        "contacts": contacts,
        "mass": M,
        "force": force,
        "jacobian": optional("jacobian"),
        "kinetic_energy": optional("kinetic_energy"),
        "potential_energy": optional("potential_energy"),
        "damping_power": optional("damping_power"),
        "initial_state": init,
        "linear": bool(_member(follower, "linear") or False),
        "name": str(name) if name is not None else type(follower).__name__,
    }


# ---- results ---------------------------------------------------------------------------
