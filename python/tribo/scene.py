"""TOML scenes: a whole contact problem in one file, as the command line runs it.

A scene has these tables (every key is optional unless marked *required*; see ``scenes/demo.toml``):

``[body]``
    ``x``, ``y``: the rectangle's ranges, e.g. ``x = [-2.0, 2.0]``; or ``mesh``: a mesh file meshio reads
    (a path relative to the scene file), whose named line sets are the edge sets. One of the two is
    required. A rectangle has the edge sets ``bottom``, ``right``, ``top``, ``left``.
``[material]``
    ``young``, ``poisson`` (*required*): plane strain.
``[supports]`` or ``[[supports]]`` (*required*, one of the two forms)
    ``[supports]`` with ``clamped``: an edge set name or a list of names (u = 0 there). Or a list of
    ``[[supports]]`` entries, each with ``kind`` and ``edge_set``: ``kind = "clamp"`` (u = 0),
    ``"roller"`` (u·n = 0 on a straight set of any direction, tangential component free: a symmetry
    line) or ``"displacement"`` with ``x`` and/or ``y`` (prescribed components; one left out is free).
    Conditions meeting at a node combine (a clamp and a roller at a corner clamp it); contradictory ones
    are an error that names the node.
``[loads]``
    ``body_force = [fx, fy]``; ``[loads.tractions]``: ``edge_set = [tx, ty]`` per loaded edge set.
``[contact]``
    ``edge_set`` (*required*): the straight edge set Γ_C.
``[obstacle]``
    ``shape``: ``"flat"`` (default), ``"circle"``, ``"parabola"`` (both with ``radius`` *required* and
    ``center``, an abscissa on Γ_C, default 0) or ``"polyline"`` (``xi`` and ``gap`` lists, *required*);
    a key of another shape is an error; ``approach`` (δ, toward the body) and ``shift`` (s, along the
    tangent t = (−n₂, n₁), n the outward normal of the body: on a top face t = (−1, 0), so a positive
    shift moves the obstacle toward −x; ``summary.json`` gives the motion in global axes as
    ``obstacle_motion`` = −δ n + s t).
``[friction]``
    ``mu`` (Coulomb; 0 is frictionless) or ``threshold`` (Tresca); neither: frictionless (the core decides,
    with the same rule as ``Problem.solve``). Tresca's threshold is given, not μ λ_n: friction acts
    wherever the body slides against the obstacle's line, so λ_t may sit at ±threshold where there is
    no contact (those dofs are in the state separation, not slip). That is Tresca's model; use ``mu``
    for friction that vanishes with the pressure.
``[discretization]``
    For a rectangle: ``grading`` = ``"auto"`` (default: refine toward where contact can occur),
    ``"none"`` (a uniform mesh of size ``h``) or ``[a, b]`` (refine toward that segment of Γ_C);
    ``h`` (the largest cell size; default a quarter of the shorter side), ``h_min`` (the size at the
    contact zone; default h / 16), ``growth`` (default 0.3), ``diagonal`` (uniform mesh only).
    For any body: ``multiplier_ratio`` (H/h) or ``multiplier_size`` (H), ``space`` (``"P0"``/``"P1"``),
    ``gamma0`` or ``gamma0_fraction`` (of the admissible bound).
``[history]``
    A quasi-static loading history (``tribo run`` then solves it step by step, see ``tribo.history``):
    piecewise-linear paths through waypoints. ``shift``, ``approach`` and ``load_factor`` are each a
    number (the same at every waypoint) or a list of waypoint values (lists have one length, at least 2);
    unset, they take ``obstacle.shift``, ``obstacle.approach`` and 1. ``steps`` (default 10) is the
    number of steps from one waypoint to the next (one count, or a list with one per segment); the first
    waypoint is step 0. ``plot_steps``: the steps whose tractions the plots show (default: the first, the
    middle and the last).
``[solver]``
    Any solver setting by the name ``Problem.solve`` takes (``tribo.solver_settings()`` lists them with
    their kinds and defaults): ``qp_tol``, ``qp_max_iter``, ``qp_kkt_solver`` (``"faer"``/``"qdldl"``),
    ``qp_working_set`` (true/false), ``fp_tol``, ``fp_max_iter``, ``fp_relaxation``. Unset keys take the
    core's defaults. The table of keys is built from the core's, so it cannot drift from it.

Top-level ``title`` and ``description`` are free text. An unknown key or a value of the wrong type is a
``SceneError`` that names the key (``scene key 'obstacle.radus' is not known``). Numbers must be finite
(TOML allows ``nan`` and ``inf``), counts lie in the core's range (``tribo.solver_settings()``), ranges
``x``, ``y`` increase, and a uniform grid has at most ``MAX_CELLS`` cells.

Automatic grading: for a circle or parabola of radius R pushed δ into the body, contact stays within
about the geometric overlap half-width ``a = sqrt(2 R δ)`` of the centre (the Hertz half-width of the
plane-strain problem is smaller), so the mesh is refined toward ``[c − 2a, c + 2a]``; for a polyline,
toward the abscissae where the initial gap is at most 2δ; for a flat obstacle, toward all of Γ_C.
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

from tribo._tribo import MAX_CELLS as _MAX_CELLS
from tribo._tribo import Mesh, Obstacle, Support, TriboError, choices, solver_settings
from tribo.checks import warn_solution
from tribo.io import read_mesh
from tribo.problem import Problem
from tribo.results import History, Solution

__all__ = ["Scene", "SceneError", "load_scene", "parse_scene", "demo_scene_path", "scene_path"]

CHOICES = choices()
SIDES = tuple(CHOICES["side"])

# Keys renamed so that a scene key, a Python keyword and the core's setting name are one name.
RENAMED = {
    "solver.kkt_solver": "solver.qp_kkt_solver",
    "solver.working_set": "solver.qp_working_set",
    "solver.relaxation": "solver.fp_relaxation",
}


class SceneError(TriboError):
    """A scene file that cannot be read or has an unknown key or a bad value; the message names the key."""

    def __init__(self, message: str, key: str | None = None) -> None:
        super().__init__(message)
        self.kind = "SceneError"
        self.details: dict[str, Any] = {"key": key} if key is not None else {}


# Value checkers: each returns the converted value or raises SceneError naming the key.
Checker = Callable[[str, Any], Any]


def _number(key: str, v: Any) -> float:
    """A finite number: TOML spells nan and inf, and an integer may be too large for a float."""
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

    return check


def _boolean(key: str, v: Any) -> bool:
    if not isinstance(v, bool):
        raise SceneError(f"scene key '{key}' must be true or false, got {v!r}", key)
    return v


def _string(key: str, v: Any) -> str:
    if not isinstance(v, str):
        raise SceneError(f"scene key '{key}' must be a string, got {v!r}", key)
    return v


def _pair(key: str, v: Any) -> tuple[float, float]:
    if not (isinstance(v, list) and len(v) == 2):
        raise SceneError(f"scene key '{key}' must be a list of two numbers, got {v!r}", key)
    return (_number(key, v[0]), _number(key, v[1]))


def _range(key: str, v: Any) -> tuple[float, float]:
    """An interval [a, b] with a < b (a side of the rectangle)."""
    a, b = _pair(key, v)
    if not a < b:
        raise SceneError(f"scene key '{key}' must be an increasing range [a, b] with a < b, got {v!r}", key)
    return (a, b)


def _numbers(key: str, v: Any) -> list[float]:
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


def _steps(key: str, v: Any) -> list[int]:
    if not isinstance(v, list) or any(isinstance(x, bool) or not isinstance(x, int) or x < 0 for x in v):
        raise SceneError(f"scene key '{key}' must be a list of step numbers (integers ≥ 0), got {v!r}", key)
    return list(v)


def _names(key: str, v: Any) -> list[str]:
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

    return check


def _grading(key: str, v: Any) -> str | tuple[float, float]:
    if isinstance(v, str):
        return str(_choice("auto", "none")(key, v))
    return _pair(key, v)


def _pairs(key: str, v: Any) -> dict[str, tuple[float, float]]:
    if not isinstance(v, dict):
        raise SceneError(f"scene key '{key}' must be a table edge_set = [tx, ty]", key)
    return {name: _pair(f"{key}.{name}", t) for name, t in v.items()}


def _setting_checker(spec: dict[str, Any]) -> Checker:
    """The checker of one solver setting, from its kind in the core's table."""
    kind = spec["kind"]
    if kind == "float":
        return _number
    if kind == "bool":
        return _boolean
    if kind == "count":
        return _count(int(spec["max"]))
    return _choice(*spec["options"])


SCHEMA: dict[str, dict[str, Checker]] = {
    "body": {"x": _range, "y": _range, "mesh": _string},
    "material": {"young": _number, "poisson": _number},
    "supports": {"clamped": _names},
    "loads": {"body_force": _pair, "tractions": _pairs},
    "contact": {"edge_set": _string},
    "obstacle": {
        "shape": _choice("flat", "circle", "parabola", "polyline"),
        "radius": _number,
        "center": _number,
        "xi": _numbers,
        "gap": _numbers,
        "approach": _number,
        "shift": _number,
    },
    "friction": {"mu": _number, "threshold": _number},
    "discretization": {
        "grading": _grading,
        "h": _number,
        "h_min": _number,
        "growth": _number,
        "diagonal": _choice(*CHOICES["diagonal"]),
        "multiplier_ratio": _number,
        "multiplier_size": _number,
        "space": _choice(*CHOICES["space"]),
        "gamma0": _number,
        "gamma0_fraction": _number,
    },
    "history": {"shift": _path, "approach": _path, "load_factor": _path, "steps": _counts, "plot_steps": _steps},
    "solver": {name: _setting_checker(spec) for name, spec in solver_settings().items()},
}
REQUIRED = {"material": ("young", "poisson"), "contact": ("edge_set",)}
# The keys of one [[supports]] entry, by kind (besides kind and edge_set).
SUPPORT_KINDS: dict[str, tuple[str, ...]] = {"clamp": (), "roller": (), "displacement": ("x", "y")}
# The keys of [obstacle] that describe its shape: those each shape takes, and those it requires.
SHAPE_KEYS = {"flat": (), "circle": ("radius", "center"), "parabola": ("radius", "center"), "polyline": ("xi", "gap")}
SHAPE_REQUIRED = {"flat": (), "circle": ("radius",), "parabola": ("radius",), "polyline": ("xi", "gap")}
# The most cells (nx · ny) a uniform rectangle may have: the limit of the core's Mesh.rectangle, checked here
# before nx and ny are rounded to integers (an absurd h would overflow the binding's conversion).
MAX_CELLS = _MAX_CELLS  # the core's limit (tribo.generate::MAX_CELLS)
# The most steps a scene's history may have in all (each step writes three VTU files).
MAX_HISTORY_STEPS = 100_000


@dataclass
class Scene:
    """A parsed, type-checked scene; ``build`` makes the mesh and problem, ``solve`` runs it."""

    sections: dict[str, dict[str, Any]]
    title: str = ""
    description: str = ""
    base_dir: Path = field(default_factory=Path.cwd)

    def get(self, section: str, key: str, default: Any = None) -> Any:
        return self.sections.get(section, {}).get(key, default)

    def solve_kwargs(self) -> dict[str, Any]:
        """Keyword arguments of ``Problem.solve``: only what the scene sets (the core picks the friction
        law from ``mu`` and ``threshold``, as for any call of ``Problem.solve``)."""
        kw: dict[str, Any] = dict(self.sections.get("friction", {}))
        for key in ("gamma0", "gamma0_fraction"):
            if self.get("discretization", key) is not None:
                kw[key] = self.get("discretization", key)
        kw.update(self.sections.get("solver", {}))
        return kw

    def supports(self) -> list[Support]:
        """The ``[[supports]]`` entries as ``tribo.Support`` values (none for the ``clamped`` form)."""
        out = []
        for entry in self.get("supports", "entries", []):
            kind, name = entry["kind"], entry["edge_set"]
            if kind == "clamp":
                out.append(Support.clamp(name))
            elif kind == "roller":
                out.append(Support.roller(name))
            else:
                out.append(Support.displacement(name, x=entry.get("x"), y=entry.get("y")))
        return out

    # ----- geometry -----
    def obstacle(self) -> Obstacle:
        """The obstacle (its keys were checked by ``parse_scene``; the core checks their values)."""
        o = self.sections.get("obstacle", {})
        shape = o.get("shape", "flat")
        if shape in ("circle", "parabola"):
            make = Obstacle.circle if shape == "circle" else Obstacle.parabola
            return make(o["radius"], o.get("center", 0.0))
        if shape == "polyline":
            return Obstacle.polyline(o["xi"], o["gap"])
        return Obstacle.flat()

    def contact_segment(self, side_range: tuple[float, float]) -> tuple[float, float]:
        """The segment of Γ_C (coordinate range along its side) that the mesh is refined toward."""
        grading = self.get("discretization", "grading", "auto")
        lo, hi = side_range
        if isinstance(grading, tuple):
            return grading
        obstacle = self.obstacle()  # first: the core refuses a bad radius before it is used here
        o = self.sections.get("obstacle", {})
        shape = o.get("shape", "flat")
        delta = max(o.get("approach", 0.0), 0.0)
        if shape in ("circle", "parabola"):
            c = o.get("center", 0.0)
            a = math.sqrt(2.0 * o["radius"] * delta)
            a = max(a, 0.01 * (hi - lo))  # no approach: still refine around the first touching point
            seg = (c - 2.0 * a, c + 2.0 * a)
        elif shape == "polyline":
            xi = np.linspace(lo, hi, 2001)
            gap = obstacle.gap0(xi)
            close = xi[gap <= 2.0 * delta + 1e-12 * (hi - lo)]
            seg = (float(close.min()), float(close.max())) if len(close) else (lo, hi)
        else:
            seg = (lo, hi)
        a, b = max(seg[0], lo), min(seg[1], hi)
        if a > b:  # the obstacle is beyond Γ_C: refine toward its nearest end
            a = b = lo if seg[1] < lo else hi
        return (a, b)

    def mesh(self) -> Mesh:
        """The mesh: read from the file, or generated on the rectangle (graded unless asked not to)."""
        body = self.sections.get("body", {})
        d = self.sections.get("discretization", {})
        if "mesh" in body:
            if "x" in body or "y" in body:
                raise SceneError("give either body.mesh or body.x/body.y, not both", "body.mesh")
            rect_keys = sorted(set(d) & {"grading", "h", "h_min", "growth", "diagonal"})
            if rect_keys:
                raise SceneError(
                    f"scene key 'discretization.{rect_keys[0]}' applies to a rectangle body, not a mesh file",
                    f"discretization.{rect_keys[0]}",
                )
            return read_mesh(self.base_dir / body["mesh"])
        for k in ("x", "y"):
            if k not in body:
                raise SceneError(f"scene key 'body.{k}' is required (or give body.mesh)", f"body.{k}")
        x, y = body["x"], body["y"]
        h = d.get("h", 0.25 * min(x[1] - x[0], y[1] - y[0]))
        if not h > 0.0:
            raise SceneError(f"scene key 'discretization.h' must be positive, got {h}", "discretization.h")
        grading = d.get("grading", "auto")
        if grading == "none":
            extra = sorted(set(d) & {"h_min", "growth"})
            if extra:
                raise SceneError(
                    f"scene key 'discretization.{extra[0]}' needs a graded mesh (grading is 'none')",
                    f"discretization.{extra[0]}",
                )
            fx, fy = (x[1] - x[0]) / h, (y[1] - y[0]) / h
            if fx * fy > MAX_CELLS:
                raise SceneError(
                    f"scene key 'discretization.h' = {h:g} makes a grid of about {fx:.3g} x {fy:.3g} cells,"
                    f" more than the limit of {MAX_CELLS}",
                    "discretization.h",
                )
            nx, ny = max(1, math.ceil(fx - 1e-9)), max(1, math.ceil(fy - 1e-9))
            return Mesh.rectangle(x, y, nx, ny, diagonal=d.get("diagonal"))
        if "diagonal" in d:
            raise SceneError("scene key 'discretization.diagonal' applies to grading = 'none'", "discretization.diagonal")
        side = self.get("contact", "edge_set")
        if side not in SIDES:
            raise SceneError(
                f"scene key 'contact.edge_set' = {side!r}: a rectangle's edge sets are {', '.join(SIDES)}",
                "contact.edge_set",
            )
        along = x if side in ("bottom", "top") else y
        segment = self.contact_segment((min(along), max(along)))
        return Mesh.graded_rectangle(
            x,
            y,
            side=side,
            segment=segment,
            h_min=d.get("h_min", h / 16.0),
            h_max=h,
            growth=d.get("growth", 0.3),
        )

    def build(self) -> Problem:
        """The mesh and the problem the scene describes."""
        o = self.sections.get("obstacle", {})
        d = self.sections.get("discretization", {})
        loads = self.sections.get("loads", {})
        try:
            obstacle = self.obstacle()  # before the mesh, whose grading uses the obstacle's values
            return Problem(
                self.mesh(),
                young=self.get("material", "young"),
                poisson=self.get("material", "poisson"),
                clamped=self.get("supports", "clamped"),
                supports=self.supports(),
                contact=self.get("contact", "edge_set"),
                obstacle=obstacle,
                approach=o.get("approach"),
                shift=o.get("shift"),
                tractions=loads.get("tractions"),
                body_force=loads.get("body_force"),
                multiplier_ratio=d.get("multiplier_ratio"),
                multiplier_size=d.get("multiplier_size"),
                space=d.get("space"),
            )
        except TriboError as e:
            if not isinstance(e, SceneError):
                e.add_note(f"while building the scene '{self.title or self.base_dir}'")
            raise

    def solve(
        self,
        problem: Problem | None = None,
        progress: Callable[[int, float, int, float], object] | None = None,
        on_phase: Callable[[str, float], object] | None = None,
    ) -> tuple[Problem, Solution]:
        """Builds (unless given) and solves; returns the problem and the solution. A solution that is
        probably not what the scene meant (nothing touches, few multiplier dofs in contact, a large
        approach: ``tribo.checks``) emits a ``SceneWarning``."""
        problem = problem if problem is not None else self.build()
        solution = problem.solve(progress=progress, on_phase=on_phase, **self.solve_kwargs())
        warn_solution(problem, solution, stacklevel=2)
        return problem, solution

    @property
    def has_history(self) -> bool:
        """True when the scene has a ``[history]`` table."""
        return "history" in self.sections

    def history_steps(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The steps of ``[history]``: approach, shift and load factor per step (the first waypoint is step 0)."""
        h = self.sections.get("history", {})
        o = self.sections.get("obstacle", {})
        given = {
            "approach": h.get("approach", o.get("approach", 0.0)),
            "shift": h.get("shift", o.get("shift", 0.0)),
            "load_factor": h.get("load_factor", 1.0),
        }
        lengths = {k: len(v) for k, v in given.items() if isinstance(v, list)}
        if len(set(lengths.values())) > 1:
            raise SceneError(f"the waypoint lists of [history] have different lengths: {lengths}", "history")
        n_points = max(lengths.values(), default=2)
        counts = h.get("steps", 10)
        counts = counts if isinstance(counts, list) else [counts] * (n_points - 1)
        if len(counts) != n_points - 1:
            raise SceneError(
                f"scene key 'history.steps' must have one count per segment ({n_points - 1}), got {len(counts)}",
                "history.steps",
            )
        if sum(counts) + 1 > MAX_HISTORY_STEPS:
            raise SceneError(f"[history] has {sum(counts) + 1} steps, more than {MAX_HISTORY_STEPS}", "history.steps")
        # Parameter t of each step along the waypoints: 0, then counts[i] equal steps per segment.
        t = np.concatenate([[0.0], *[i + np.arange(1, c + 1) / c for i, c in enumerate(counts)]])
        waypoints = np.arange(n_points, dtype=float)

        def sample(v: float | list[float]) -> np.ndarray:
            values = np.asarray(v if isinstance(v, list) else [v] * n_points, dtype=float)
            out: np.ndarray = np.interp(t, waypoints, values)
            return out

        return sample(given["approach"]), sample(given["shift"]), sample(given["load_factor"])

    def solve_history(
        self, problem: Problem | None = None, progress: Callable[[int, int, str, float], object] | None = None
    ) -> tuple[Problem, History]:
        """Builds (unless given) and solves the ``[history]``; returns the problem and the history."""
        problem = problem if problem is not None else self.build()
        approach, shift, load_factor = self.history_steps()
        kw = self.solve_kwargs()
        return problem, problem.solve_history(approach, shift, load_factor, progress=progress, **kw)

    def to_dict(self) -> dict[str, Any]:
        """The scene as plain data (for the JSON summary)."""
        out: dict[str, Any] = {"title": self.title, "description": self.description}
        for section, values in self.sections.items():
            out[section] = {k: list(v) if isinstance(v, tuple) else v for k, v in values.items()}
        return out


def _check_obstacle(o: Mapping[str, Any]) -> None:
    """The shape keys of [obstacle]: each one the shape requires is given, and none it does not take."""
    shape = o.get("shape", "flat")
    for key in sorted(set(o) & {k for keys in SHAPE_KEYS.values() for k in keys}):
        if key not in SHAPE_KEYS[shape]:
            raise SceneError(f"scene key 'obstacle.{key}' does not apply to a {shape} obstacle", f"obstacle.{key}")
    for key in SHAPE_REQUIRED[shape]:
        if key not in o:
            raise SceneError(f"scene key 'obstacle.{key}' is required for a {shape}", f"obstacle.{key}")


def _support_entry(index: int, entry: Any) -> dict[str, Any]:
    """One ``[[supports]]`` entry: ``kind``, ``edge_set`` and the keys of its kind, checked."""
    where = f"supports[{index}]"
    if not isinstance(entry, dict):
        raise SceneError(f"scene key '{where}' must be a table with kind and edge_set", where)
    for key in ("kind", "edge_set"):
        if key not in entry:
            raise SceneError(f"scene key '{where}.{key}' is required", f"{where}.{key}")
    kind = _choice(*SUPPORT_KINDS)(f"{where}.kind", entry["kind"])
    out: dict[str, Any] = {"kind": kind, "edge_set": _string(f"{where}.edge_set", entry["edge_set"])}
    for key, value in entry.items():
        if key in ("kind", "edge_set"):
            continue
        if key not in SUPPORT_KINDS[kind]:
            known = ", ".join(("kind", "edge_set", *SUPPORT_KINDS[kind]))
            raise SceneError(
                f"scene key '{where}.{key}' is not known for kind = {kind!r} (known keys: {known})", f"{where}.{key}"
            )
        out[key] = _number(f"{where}.{key}", value)
    if kind == "displacement" and "x" not in out and "y" not in out:
        raise SceneError(f"scene key '{where}' (a displacement) needs x, y or both", f"{where}.x")
    return out


def parse_scene(data: Mapping[str, Any], base_dir: Path | None = None) -> Scene:
    """Checks a scene given as a dict (as tomllib returns it): unknown keys and bad types are errors."""
    sections: dict[str, dict[str, Any]] = {}
    for name, table in data.items():
        if name in ("title", "description"):
            if not isinstance(table, str):
                raise SceneError(f"scene key '{name}' must be a string", name)
            continue
        if name not in SCHEMA:
            raise SceneError(f"scene key '{name}' is not known (known tables: {', '.join(SCHEMA)})", name)
        if name == "supports" and isinstance(table, list):
            sections[name] = {"entries": [_support_entry(k, e) for k, e in enumerate(table)]}
            continue
        if not isinstance(table, dict):
            raise SceneError(f"scene key '{name}' must be a table", name)
        checked: dict[str, Any] = {}
        for key, value in table.items():
            check = SCHEMA[name].get(key)
            if check is None and f"{name}.{key}" in RENAMED:
                raise SceneError(
                    f"scene key '{name}.{key}' was renamed '{RENAMED[f'{name}.{key}']}'", f"{name}.{key}"
                )
            if check is None:
                raise SceneError(
                    f"scene key '{name}.{key}' is not known (known keys of [{name}]: {', '.join(SCHEMA[name])})",
                    f"{name}.{key}",
                )
            checked[key] = check(f"{name}.{key}", value)
        sections[name] = checked
    for name, keys in REQUIRED.items():
        for key in keys:
            if key not in sections.get(name, {}):
                raise SceneError(f"scene key '{name}.{key}' is required", f"{name}.{key}")
    if "supports" not in sections:
        raise SceneError("scene key 'supports' is required: [supports] clamped = … or [[supports]] entries", "supports")
    body = sections.get("body", {})
    if "mesh" not in body and not ("x" in body and "y" in body):
        raise SceneError("scene key 'body.x' and 'body.y' (a rectangle) or 'body.mesh' is required", "body")
    _check_obstacle(sections.get("obstacle", {}))
    f = sections.get("friction", {})
    if "mu" in f and "threshold" in f:
        raise SceneError("scene keys 'friction.mu' and 'friction.threshold' exclude each other", "friction")
    d = sections.get("discretization", {})
    for a, b in (("multiplier_ratio", "multiplier_size"), ("gamma0", "gamma0_fraction")):
        if a in d and b in d:
            raise SceneError(
                f"scene keys 'discretization.{a}' and 'discretization.{b}' exclude each other", f"discretization.{a}"
            )
    return Scene(
        sections=sections,
        title=str(data.get("title", "")),
        description=str(data.get("description", "")),
        base_dir=base_dir if base_dir is not None else Path.cwd(),
    )


def load_scene(path: str | Path) -> Scene:
    """Reads and checks a TOML scene file."""
    path = Path(path)
    try:
        with path.open("rb") as f:
            data = tomllib.load(f)
    except OSError as e:
        raise SceneError(f"cannot read scene file {path}: {e.strerror}") from e
    except UnicodeDecodeError as e:  # tomllib decodes the bytes as UTF-8 before it parses them
        raise SceneError(f"scene file {path} is not UTF-8 text: {e.reason} at byte {e.start}") from e
    except tomllib.TOMLDecodeError as e:
        raise SceneError(f"scene file {path} is not valid TOML: {e}") from e
    return parse_scene(data, base_dir=path.resolve().parent)


def scene_path(name: str) -> Path:
    """Path of a scene shipped in the package: ``"demo"``, ``"hertz"``."""
    path = Path(str(resources.files("tribo") / "scenes" / f"{name}.toml"))
    if not path.is_file():
        shipped = sorted(p.stem for p in path.parent.glob("*.toml"))
        raise SceneError(f"no shipped scene named '{name}' (shipped: {', '.join(shipped)})")
    return path


def demo_scene_path() -> Path:
    """Path of the built-in demo scene shipped in the package."""
    return scene_path("demo")
