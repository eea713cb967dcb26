"""The value checkers of scene keys: each takes a key's name and its value (as ``tomllib`` reads it) and
returns the converted value or raises ``SceneError`` naming the key. ``tribo.scene_schema`` assigns them to
the keys; ``tribo.scene_keys`` reads their first lines and their JSON Schema."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from tribo.errors import TriboError

__all__ = ["MAX_HISTORY_STEPS", "Checker", "SceneError"]

# The most steps a scene's history may have in all (each step keeps its solution in memory; the VTU files are
# written for at most 200 of them unless write_every says otherwise).
MAX_HISTORY_STEPS = 100_000


class SceneError(TriboError):
    """A scene file that cannot be read or has an unknown key or a bad value; the message names the key."""

    def __init__(self, message: str, key: str | None = None) -> None:
        super().__init__(message)
        self.kind = "SceneError"
        self.details: dict[str, Any] = {"key": key} if key is not None else {}


# Value checkers: each returns the converted value or raises SceneError naming the key.
Checker = Callable[[str, Any], Any]


def _number(key: str, v: Any) -> float:
    """A finite number.

    TOML spells nan and inf, and an integer may be too large for a float: both are refused."""
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise SceneError(f"scene key '{key}' must be a number, got {v!r}", key)
    try:
        x = float(v)
    except OverflowError:  # an integer beyond the range of a float
        x = math.inf
    if not math.isfinite(x):
        raise SceneError(f"scene key '{key}' must be a finite number, got {v!r}", key)
    return x


def _integer(key: str, v: Any) -> int:
    if isinstance(v, bool) or not isinstance(v, int):
        raise SceneError(f"scene key '{key}' must be an integer, got {v!r}", key)
    return v


def _count(largest: int) -> Checker:
    def check(key: str, v: Any) -> int:
        n = _integer(key, v)
        if not 0 <= n <= largest:
            raise SceneError(f"scene key '{key}' must be an integer in [0, {largest}], got {n}", key)
        return n

    check.__doc__ = f"An integer in [0, {largest}]."
    check.json_schema = {"type": "integer", "minimum": 0, "maximum": largest}  # type: ignore[attr-defined]
    return check


def _boolean(key: str, v: Any) -> bool:
    """true or false."""
    if not isinstance(v, bool):
        raise SceneError(f"scene key '{key}' must be true or false, got {v!r}", key)
    return v


def _string(key: str, v: Any) -> str:
    """A string."""
    if not isinstance(v, str):
        raise SceneError(f"scene key '{key}' must be a string, got {v!r}", key)
    return v


def _pair(key: str, v: Any) -> tuple[float, float]:
    """Two numbers [x, y]."""
    if not (isinstance(v, list) and len(v) == 2):
        raise SceneError(f"scene key '{key}' must be a list of two numbers, got {v!r}", key)
    return (_number(key, v[0]), _number(key, v[1]))


def _points(key: str, v: Any) -> list[tuple[float, float]]:
    """A list of at least two points [x, y] (a profile's polyline)."""
    if not (isinstance(v, list) and len(v) >= 2):
        raise SceneError(f"scene key '{key}' must be a list of at least two points [x, y], got {v!r}", key)
    return [_pair(key, p) for p in v]


def _center(key: str, v: Any) -> float | tuple[float, float]:
    """A number (an abscissa on Γ_C: a circle's or a parabola's) or two numbers [x, y] (a disc's or a hole's)."""
    return _pair(key, v) if isinstance(v, list) else _number(key, v)


def _range(key: str, v: Any) -> tuple[float, float]:
    """An interval [a, b] with a < b (a side of the rectangle)."""
    a, b = _pair(key, v)
    if not a < b:
        raise SceneError(f"scene key '{key}' must be an increasing range [a, b] with a < b, got {v!r}", key)
    return (a, b)


_PAIR_JSON: dict[str, Any] = {"type": "array", "items": {"type": "number"}, "minItems": 2, "maxItems": 2}
_POSITIVE_JSON: dict[str, Any] = {"type": "number", "exclusiveMinimum": 0}


def _object_json(required: tuple[str, ...], **properties: dict[str, Any]) -> dict[str, Any]:
    """The JSON Schema of an inline table of ``properties``, those of ``required`` required."""
    return {"type": "object", "required": list(required), "additionalProperties": False, "properties": properties}


def _table(key: str, v: Any, form: str, known: tuple[str, ...], required: tuple[str, ...]) -> dict[str, Any]:
    """``v`` as an inline table of the keys ``known``, with those of ``required`` (``form`` shows how it reads)."""
    if not isinstance(v, dict):
        raise SceneError(f"scene key '{key}' must be a table {{ {form} }}, got {v!r}", key)
    for name in v:
        if name not in known:
            raise SceneError(f"scene key '{key}.{name}' is not known (known keys: {', '.join(known)})", f"{key}.{name}")
    for name in required:
        if name not in v:
            raise SceneError(f"scene key '{key}.{name}' is required", f"{key}.{name}")
    return v


def _ring(key: str, v: Any) -> dict[str, tuple[float, float]]:
    """A ring sector ``{ center = [x, y], radii = [r_in, r_out], angles = [a0, a1] }`` (angles in degrees,
    counterclockwise from the x axis), meshed by ``Mesh.ring_sector``: edge sets ``outer``, ``inner``, ``start``,
    ``end``, the arcs carrying their circles."""
    names = ("center", "radii", "angles")
    v = _table(key, v, "center = [x, y], radii = [r_in, r_out], angles = [a0, a1]", names, names)
    return {"center": _pair(f"{key}.center", v["center"]), "radii": _range(f"{key}.radii", v["radii"]),
            "angles": _range(f"{key}.angles", v["angles"])}


_ring.json_schema = _object_json(  # type: ignore[attr-defined]
    ("center", "radii", "angles"), center=_PAIR_JSON, radii=_PAIR_JSON, angles=_PAIR_JSON)


def _disc(key: str, v: Any) -> dict[str, Any]:
    """A disc or the sector of one ``{ center = [x, y], radius = R, angles = [a0, a1] }`` (angles in degrees,
    counterclockwise from the x axis; default [0, 360], a whole disc), meshed uniformly by ``Mesh.disc``: edge sets
    ``rim`` (carrying its circle), and for a sector ``start`` and ``end``."""
    v = _table(key, v, "center = [x, y], radius = R, angles = [a0, a1]", ("center", "radius", "angles"),
               ("center", "radius"))
    radius = _number(f"{key}.radius", v["radius"])
    if not radius > 0.0:
        raise SceneError(f"scene key '{key}.radius' must be positive, got {radius:g}", f"{key}.radius")
    return {"center": _pair(f"{key}.center", v["center"]), "radius": radius,
            "angles": _range(f"{key}.angles", v.get("angles", [0.0, 360.0]))}


_disc.json_schema = _object_json(  # type: ignore[attr-defined]
    ("center", "radius"), center=_PAIR_JSON, radius=_POSITIVE_JSON, angles=_PAIR_JSON)


def _plate(key: str, v: Any) -> dict[str, Any]:
    """A rectangular plate with a circular hole ``{ center = [x, y], radius = R, half_widths = [a, b] }``: the plate
    ``[x − a, x + a] × [y − b, y + b]``, meshed by ``Mesh.plate_with_hole``: edge sets ``hole`` (carrying its circle),
    ``right``, ``top``, ``left``, ``bottom``."""
    names = ("center", "radius", "half_widths")
    v = _table(key, v, "center = [x, y], radius = R, half_widths = [a, b]", names, names)
    radius, (a, b) = _number(f"{key}.radius", v["radius"]), _pair(f"{key}.half_widths", v["half_widths"])
    if not (a > 0.0 and b > 0.0):
        raise SceneError(f"scene key '{key}.half_widths' must be positive, got [{a:g}, {b:g}]", f"{key}.half_widths")
    if not 0.0 < radius < min(a, b):
        raise SceneError(f"scene key '{key}.radius' = {radius:g} must be positive and inside the plate's "
                         f"half-widths [{a:g}, {b:g}]", f"{key}.radius")
    return {"center": _pair(f"{key}.center", v["center"]), "radius": radius, "half_widths": (a, b)}


_plate.json_schema = _object_json(  # type: ignore[attr-defined]
    ("center", "radius", "half_widths"), center=_PAIR_JSON, radius=_POSITIVE_JSON,
    half_widths={**_PAIR_JSON, "items": _POSITIVE_JSON})


def _rotation(key: str, v: Any) -> tuple[tuple[float, float], float]:
    """A small rotation ``{ center = [x, y], angle = a }`` (radians, counterclockwise), as (center, angle)."""
    v = _table(key, v, "center = [x, y], angle = a", ("center", "angle"), ("center", "angle"))
    return _pair(f"{key}.center", v["center"]), _number(f"{key}.angle", v["angle"])


_rotation.json_schema = {  # type: ignore[attr-defined]
    "type": "object", "required": ["center", "angle"], "additionalProperties": False,
    "properties": {"center": {"type": "array", "items": {"type": "number"}, "minItems": 2, "maxItems": 2},
                   "angle": {"type": "number"}},
}


def _numbers(key: str, v: Any) -> list[float]:
    """A list of numbers."""
    if not isinstance(v, list):
        raise SceneError(f"scene key '{key}' must be a list of numbers, got {v!r}", key)
    return [_number(key, x) for x in v]


def _path(key: str, v: Any) -> float | list[float]:
    """A number, or a list of at least two numbers (waypoints of a history path)."""
    if isinstance(v, list):
        if len(v) < 2:
            raise SceneError(f"scene key '{key}' must be a number or a list of at least two waypoints, got {v!r}", key)
        return _numbers(key, v)
    return _number(key, v)


def _counts(key: str, v: Any) -> int | list[int]:
    """A positive step count, or a list of them (one per segment of a history path)."""
    values = v if isinstance(v, list) else [v]
    out = [_integer(key, x) for x in values]
    if not out or any(not 1 <= n <= MAX_HISTORY_STEPS for n in out):
        raise SceneError(f"scene key '{key}' must hold step counts in [1, {MAX_HISTORY_STEPS}], got {v!r}", key)
    return out if isinstance(v, list) else out[0]


def _every(key: str, v: Any) -> int:
    """A positive integer: write every k-th step."""
    n = _integer(key, v)
    if n < 1:
        raise SceneError(f"scene key '{key}' must be a positive integer (every k-th step), got {n}", key)
    return n


def _steps(key: str, v: Any) -> list[int]:
    """A list of step indices (0-based)."""
    if not isinstance(v, list) or any(isinstance(x, bool) or not isinstance(x, int) or x < 0 for x in v):
        raise SceneError(f"scene key '{key}' must be a list of step numbers (integers ≥ 0), got {v!r}", key)
    return list(v)


def _names(key: str, v: Any) -> list[str]:
    """An edge set name, or a list of names."""
    if isinstance(v, str):
        return [v]
    if isinstance(v, list) and v and all(isinstance(x, str) for x in v):
        return list(v)
    raise SceneError(f"scene key '{key}' must be an edge set name or a non-empty list of names, got {v!r}", key)


def _choice(*options: str) -> Checker:
    def check(key: str, v: Any) -> str:
        if v not in options:
            raise SceneError(f"scene key '{key}' must be one of {', '.join(map(repr, options))}, got {v!r}", key)
        return str(v)

    check.__doc__ = f"One of {', '.join(map(repr, options))}."
    check.json_schema = {"enum": list(options)}  # type: ignore[attr-defined]
    return check


def _grading(key: str, v: Any) -> str | tuple[float, float]:
    """"auto", "none" or a segment [a, b] of the contact side."""
    if isinstance(v, str):
        return str(_choice("auto", "none")(key, v))
    return _pair(key, v)


def _pairs(key: str, v: Any) -> dict[str, tuple[float, float]]:
    """A table edge_set = [tx, ty]."""
    if not isinstance(v, dict):
        raise SceneError(f"scene key '{key}' must be a table edge_set = [tx, ty]", key)
    return {name: _pair(f"{key}.{name}", t) for name, t in v.items()}


def _pressures(key: str, v: Any) -> dict[str, float]:
    """A table edge_set = p."""
    if not isinstance(v, dict):
        raise SceneError(f"scene key '{key}' must be a table edge_set = p", key)
    return {name: _number(f"{key}.{name}", p) for name, p in v.items()}


def _paths(key: str, v: Any) -> dict[str, float | list[float]]:
    """A table of waypoint paths: prescribed displacement component → number or waypoints."""
    if not isinstance(v, dict):
        raise SceneError(f"scene key '{key}' must be a table \"set.x\" = waypoints", key)
    return {name: _path(f"{key}.{name}", path) for name, path in v.items()}
