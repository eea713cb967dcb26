"""TOML scenes: a whole contact problem in one file, as the command line runs it.

This module holds the builder: ``parse_scene`` and ``load_scene`` check a scene (a dict, or a TOML file)
against the schema and return a ``Scene``, whose ``build`` makes the ``tribo.Mesh`` and ``tribo.Problem``
it describes and whose ``solve`` and ``solve_history`` run them, with a ``SceneWarning`` for a solution
that is probably not what the scene meant. The tables and keys of a scene file, their types and defaults
are described (and checked) in ``tribo.scene_schema`` (see ``scenes/demo.toml``); its names are importable
from here too.

Automatic grading: for a circle or parabola of radius R pushed δ into the body, contact stays within
about the geometric overlap half-width ``a = sqrt(2 R δ)`` of the centre (the Hertz half-width of the
plane-strain problem is smaller), so the mesh is refined toward ``[c − 2a, c + 2a]``; for a polyline,
toward the abscissae where the initial gap is at most 2δ; for a flat obstacle, toward all of Γ_C.
"""

from __future__ import annotations

import contextlib
import math
import tomllib
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

from tribo._tribo import Mesh, Obstacle, Support
from tribo.errors import TriboError
from tribo.checks import warn_missing_error_bars, warn_solution
from tribo.io import read_mesh, read_triangle_groups
from tribo.problem import Body, Pair, Problem, check_adapt
from tribo.results import Adaptive, AdaptiveHistory, History, Solution
# The schema's names, importable from here as before the split (``X as X``: re-exported).
from tribo.scene_schema import CHOICES as CHOICES
from tribo.scene_schema import MAX_CELLS as MAX_CELLS
from tribo.scene_schema import MAX_HISTORY_STEPS as MAX_HISTORY_STEPS
from tribo.scene_schema import RENAMED as RENAMED
from tribo.scene_schema import REQUIRED as REQUIRED
from tribo.scene_schema import SCHEMA as SCHEMA
from tribo.scene_schema import SHAPE_KEYS as SHAPE_KEYS
from tribo.scene_schema import SHAPE_REQUIRED as SHAPE_REQUIRED
from tribo.scene_schema import SIDES as SIDES
from tribo.scene_schema import SUPPORT_KINDS as SUPPORT_KINDS
from tribo.scene_schema import Checker as Checker
from tribo.scene_schema import SceneError as SceneError
from tribo.scene_schema import check_scene

__all__ = ["Scene", "SceneError", "load_scene", "parse_scene", "demo_scene_path", "scene_path"]


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
        return [_support(entry) for entry in self.get("supports", "entries", [])]

    # ----- geometry -----
    def obstacle(self) -> Obstacle:
        """The obstacle (its keys were checked by ``parse_scene``; the core checks their values); between two
        bodies, the initial gap ``contact.gap``."""
        return _obstacle_of(self.get("contact", "gap", {}) if self.is_two_bodies else self.sections.get("obstacle", {}))

    def pairs(self) -> list[Pair] | None:
        """The further contact pairs ``[[contact.pairs]]`` as ``Problem`` takes them (None without)."""
        given = self.get("contact", "pairs")
        return None if given is None else [Pair(p["edge_set"], _obstacle_of(p), p.get("approach"), p.get("shift"),
                                                p.get("mu")) for p in given]

    def _approach(self) -> float:
        """How far contact reaches into the gap: the obstacle's approach; between two bodies, the largest
        prescribed displacement of the scene (its supports and its history's waypoints)."""
        if not self.is_two_bodies:
            return float(max(self.get("obstacle", "approach", 0.0), 0.0))
        values = [abs(e.get(c, 0.0)) for b in self.sections["bodies"]["entries"] for e in b["supports"] for c in "xy"]
        for path in self.get("history", "displacements", {}).values():
            values += [abs(v) for v in (path if isinstance(path, list) else [path])]
        return max(values, default=0.0)

    def contact_segment(
        self, side_range: tuple[float, float], d: Mapping[str, Any] | None = None
    ) -> tuple[float, float]:
        """The segment of Γ_C (coordinate range along its side) that the mesh is refined toward (``d``: the
        discretization table, the scene's or a body's)."""
        d = self.sections.get("discretization", {}) if d is None else d
        grading = d.get("grading", "auto")
        lo, hi = side_range
        if isinstance(grading, tuple):
            return grading
        obstacle = self.obstacle()  # first: the core refuses a bad radius before it is used here
        o = self.get("contact", "gap", {}) if self.is_two_bodies else self.sections.get("obstacle", {})
        shape = o.get("shape", "flat")
        delta = self._approach()
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
        return self._mesh(self.sections.get("body", {}), self.sections.get("discretization", {}),
                          self.get("contact", "edge_set"), "body", "discretization", "contact.edge_set")

    def _mesh(self, body: Mapping[str, Any], d: Mapping[str, Any], side: Any, body_key: str, d_key: str,
              side_key: str) -> Mesh:
        """The mesh of ``body`` (``[body]`` or a ``[[bodies]]`` entry) with the discretization ``d``, graded
        toward its contact ``side``; the keys name the tables in errors."""
        if "ring" in body:
            return self._ring(body, d, body_key, d_key)
        if "disc" in body or "plate" in body:
            return self._round(body, d, body_key, d_key)
        if "mesh" in body:
            if "x" in body or "y" in body:
                raise SceneError(f"give either {body_key}.mesh or {body_key}.x/{body_key}.y, not both",
                                 f"{body_key}.mesh")
            rect_keys = sorted(set(d) & {"grading", "h", "h_min", "growth", "diagonal"})
            if rect_keys:
                raise SceneError(
                    f"scene key '{d_key}.{rect_keys[0]}' applies to a rectangle body, not a mesh file",
                    f"{d_key}.{rect_keys[0]}",
                )
            return read_mesh(self.base_dir / body["mesh"])
        for k in ("x", "y"):
            if k not in body:
                raise SceneError(f"scene key '{body_key}.{k}' is required (or give {body_key}.mesh)", f"{body_key}.{k}")
        x, y = body["x"], body["y"]
        h = d.get("h", 0.25 * min(x[1] - x[0], y[1] - y[0]))
        if not h > 0.0:
            raise SceneError(f"scene key '{d_key}.h' must be positive, got {h}", f"{d_key}.h")
        grading = d.get("grading", "auto")
        if grading == "none":
            extra = sorted(set(d) & {"h_min", "growth"})
            if extra:
                raise SceneError(
                    f"scene key '{d_key}.{extra[0]}' needs a graded mesh (grading is 'none')", f"{d_key}.{extra[0]}"
                )
            fx, fy = (x[1] - x[0]) / h, (y[1] - y[0]) / h
            if fx * fy > MAX_CELLS:
                raise SceneError(
                    f"scene key '{d_key}.h' = {h:g} makes a grid of about {fx:.3g} x {fy:.3g} cells,"
                    f" more than the limit of {MAX_CELLS}",
                    f"{d_key}.h",
                )
            nx, ny = max(1, math.ceil(fx - 1e-9)), max(1, math.ceil(fy - 1e-9))
            return Mesh.rectangle(x, y, nx, ny, diagonal=d.get("diagonal"))
        if "diagonal" in d:
            raise SceneError(f"scene key '{d_key}.diagonal' applies to grading = 'none'", f"{d_key}.diagonal")
        if side not in SIDES:
            raise SceneError(
                f"scene key '{side_key}' = {side!r}: a rectangle's edge sets are {', '.join(SIDES)}", side_key
            )
        along = x if side in ("bottom", "top") else y
        segment = self.contact_segment((min(along), max(along)), d)
        return Mesh.graded_rectangle(x, y, side=side, segment=segment, h_max=h, h_min=d.get("h_min"),
                                     growth=d.get("growth"))

    @staticmethod
    def _ring(body: Mapping[str, Any], d: Mapping[str, Any], body_key: str, d_key: str) -> Mesh:
        """The ring sector of ``body.ring``: uniform at ``h`` (``grading = "auto"`` or ``"none"``), or graded toward
        the arc ``grading = [a0, a1]`` (degrees) of its outer circle to ``h_min``."""
        others = sorted(set(body) & {"mesh", "x", "y", "disc", "plate"})
        if others:
            raise SceneError(f"give either {body_key}.ring or {body_key}.{others[0]}, not both", f"{body_key}.ring")
        if "diagonal" in d:
            raise SceneError(f"scene key '{d_key}.diagonal' applies to a uniform rectangle, not a ring",
                             f"{d_key}.diagonal")
        ring = body["ring"]
        (r_in, r_out), (a0, a1) = ring["radii"], ring["angles"]
        if a1 - a0 > 360.0:
            raise SceneError(f"scene key '{body_key}.ring.angles' = [{a0:g}, {a1:g}] spans more than a full turn (360)",
                             f"{body_key}.ring.angles")
        grading = d.get("grading", "auto")
        if isinstance(grading, tuple) and not a0 <= grading[0] <= grading[1] <= a1:
            raise SceneError(f"scene key '{d_key}.grading' = [{grading[0]:g}, {grading[1]:g}] must be an arc of the "
                             f"ring's outer circle inside its angles [{a0:g}, {a1:g}] (degrees)", f"{d_key}.grading")
        angles = (math.radians(a0), math.radians(a1))
        h = d.get("h", 0.25 * (r_out - r_in))
        if isinstance(grading, str):
            extra = sorted(set(d) & {"h_min", "growth"})
            if extra:
                raise SceneError(f"scene key '{d_key}.{extra[0]}' needs a graded ring: grading = [a0, a1], an arc of "
                                 "its outer circle in degrees", f"{d_key}.{extra[0]}")
            return Mesh.ring_sector(ring["center"], (r_in, r_out), angles, h_max=h, h_min=h)
        return Mesh.ring_sector(ring["center"], (r_in, r_out), angles, h_max=h, h_min=d.get("h_min"),
                                arc=(math.radians(grading[0]), math.radians(grading[1])), growth=d.get("growth"))

    @staticmethod
    def _round(body: Mapping[str, Any], d: Mapping[str, Any], body_key: str, d_key: str) -> Mesh:
        """The disc (or sector) of ``body.disc``, or the plate with a hole of ``body.plate``, uniform at ``h``
        (default a quarter of the radius): a disc's rings of nodes ``ceil(R / h)``; a plate's nodes round the hole
        the multiple of 8 that puts them about ``h`` apart, its cells across about square (growing from the hole to
        the plate's edge). Refinement near a contact is the adaptive loop's (the arcs carry their circles)."""
        kind = "disc" if "disc" in body else "plate"
        others = sorted(set(body) & {"mesh", "x", "y", "ring", "disc", "plate"} - {kind})
        if others:
            raise SceneError(f"give either {body_key}.{kind} or {body_key}.{others[0]}, not both", f"{body_key}.{kind}")
        grading = [] if d.get("grading", "auto") in ("auto", "none") else ["grading"]
        extra = sorted(set(d) & {"diagonal", "h_min", "growth"}) or grading
        if extra:
            raise SceneError(f"scene key '{d_key}.{extra[0]}' applies to a rectangle or a ring, not a {kind} (uniform "
                             f"at {d_key}.h)", f"{d_key}.{extra[0]}")
        shape = body[kind]
        h = d.get("h", 0.25 * shape["radius"])
        if not h > 0.0:
            raise SceneError(f"scene key '{d_key}.h' must be positive, got {h}", f"{d_key}.h")
        if kind == "disc":
            (a0, a1), radius = shape["angles"], shape["radius"]
            if not 0.0 < a1 - a0 <= 360.0:
                raise SceneError(f"scene key '{body_key}.disc.angles' = [{a0:g}, {a1:g}] must increase by at most a "
                                 "full turn (360)", f"{body_key}.disc.angles")
            rings = radius / h
            if not 6 * rings * rings * (a1 - a0) / 360.0 <= MAX_CELLS:
                raise SceneError(f"scene key '{d_key}.h' = {h:g} makes about {rings:.3g} rings of nodes, more than "
                                 f"{MAX_CELLS} triangles", f"{d_key}.h")
            return Mesh.disc(shape["center"], radius, rings=max(1, math.ceil(rings - 1e-9)),
                             angles=(math.radians(a0), math.radians(a1)))
        radius, (a, b) = shape["radius"], shape["half_widths"]
        around = 8 * max(1, math.ceil(2 * math.pi * radius / h / 8 - 1e-9)) if h * MAX_CELLS > radius else 0
        # (the cells across about as deep as wide along the longest ray, to a corner: the mean of the spacings at the
        # hole and at the plate's edge)
        spacing = (2 * math.pi * radius + 4 * (a + b)) / (2 * max(around, 1))
        across = max(2, math.ceil((math.hypot(a, b) - radius) / spacing))
        if not (0 < around and 2 * around * across <= MAX_CELLS):
            raise SceneError(f"scene key '{d_key}.h' = {h:g} makes more than {MAX_CELLS} triangles", f"{d_key}.h")
        return Mesh.plate_with_hole(shape["center"], radius, (a, b), around=around, across=across)

    @property
    def is_two_bodies(self) -> bool:
        """True when the scene has ``[[bodies]]``: two elastic bodies in contact."""
        return "bodies" in self.sections

    def bodies(self) -> list[Body]:
        """The two ``[[bodies]]`` as ``tribo.Body`` values, each graded toward its side of the contact."""
        sides = {}
        for key in ("secondary", "primary"):
            name, _, edge_set = str(self.get("contact", key)).partition(".")
            sides[name] = (edge_set, f"contact.{key}")
        out = []
        for k, entry in enumerate(self.sections["bodies"]["entries"]):
            where = f"bodies[{k}]"
            side, side_key = sides.get(entry["name"], (None, "contact.secondary"))
            uniform = {"mesh", "ring", "disc", "plate"} & set(entry) or entry.get("discretization", {}).get("grading") == "none"
            if side is None and not uniform:
                pair = f"secondary = {self.get('contact', 'secondary')!r}, primary = {self.get('contact', 'primary')!r}"
                raise SceneError(
                    f"body {entry['name']!r} is on neither side of the contact ({pair}), so its mesh cannot be "
                    "graded toward it", "contact.secondary"
                )
            mesh = self._mesh(entry, entry.get("discretization", {}), side, where, f"{where}.discretization", side_key)
            out.append(Body(entry["name"], mesh, **self.materials(mesh, entry["material"], entry, f"{where}.material"),
                            supports=[_support(e) for e in entry["supports"]],
                            tractions=entry.get("loads", {}).get("tractions"),
                            pressures=entry.get("loads", {}).get("pressures")))
        return out

    def materials(self, mesh: Mesh, material: Mapping[str, Any] | None = None, body: Mapping[str, Any] | None = None,
                  where: str = "material") -> dict[str, Any]:
        """The material keywords of ``Problem`` (or ``Body``): ``young`` and ``poisson`` of ``[material]`` (or a
        body's ``material``), or with ``regions`` the materials (the table's own first) and each triangle's
        region: the last entry whose ``group`` (a physical surface of the body's mesh file) or ``box`` (by its
        centroid) holds it."""
        material = self.sections.get("material", {}) if material is None else material
        body = self.sections.get("body", {}) if body is None else body
        entries = material.get("regions") or []
        base = (material.get("young"), material.get("poisson"))
        if not entries:
            return {"young": base[0], "poisson": base[1]}
        centroids = np.asarray(mesh.points)[np.asarray(mesh.triangles)].mean(axis=1)
        regions = np.zeros(mesh.n_triangles, dtype=np.int64)
        groups: dict[str, Any] | None = None
        for k, entry in enumerate(entries):
            key = f"{where}.regions[{k}]"
            if "group" in entry:
                if "mesh" not in body:
                    raise SceneError(f"scene key '{key}.group' needs a mesh file with physical surfaces ([body] "
                                     "mesh); a rectangle's regions are boxes", f"{key}.group")
                groups = read_triangle_groups(self.base_dir / body["mesh"]) if groups is None else groups
                if entry["group"] not in groups:
                    raise SceneError(f"scene key '{key}.group': the mesh file has no physical surface "
                                     f"{entry['group']!r} (it has: {', '.join(sorted(groups)) or 'none'})",
                                     f"{key}.group")
                inside = groups[entry["group"]]
            else:
                x0, y0, x1, y1 = entry["box"]
                inside = ((centroids[:, 0] >= x0) & (centroids[:, 0] <= x1) & (centroids[:, 1] >= y0)
                          & (centroids[:, 1] <= y1))
            if not inside.any():
                raise SceneError(f"scene key '{key}' holds no triangle of the mesh", key)
            regions[inside] = k + 1
        return {"materials": [base, *((e["young"], e["poisson"]) for e in entries)], "regions": regions}

    def build(self) -> Problem:
        """The mesh and the problem the scene describes."""
        o = self.sections.get("obstacle", {})
        d = self.sections.get("discretization", {})
        loads = self.sections.get("loads", {})
        try:
            obstacle = self.obstacle()  # before the mesh, whose grading uses the obstacle's values
            for k, pair in enumerate(self.get("contact", "pairs", [])):
                if "mu" in pair and "mu" not in self.sections.get("friction", {}):
                    key = f"contact.pairs[{k}].mu"
                    raise SceneError(f"scene key '{key}': a pair's own mu needs Coulomb friction; give 'friction.mu' "
                                     "(0: the first pair frictionless)", key)
            if self.is_two_bodies:
                first, second = self.bodies()
                sets = {f"{b.name}.{s}" for b in (first, second) for s in b.mesh.edge_sets}
                for k, pair in enumerate(self.get("contact", "pairs", [])):
                    if pair["edge_set"] not in sets:
                        key = f"contact.pairs[{k}].edge_set"
                        raise SceneError(f"scene key '{key}' = {pair['edge_set']!r}: no body has that edge set (the "
                                         f"sets: {', '.join(sorted(sets))})", key)
                return Problem.two_bodies(
                    first, second, secondary=self.get("contact", "secondary"), primary=self.get("contact", "primary"),
                    gap=obstacle, body_force=loads.get("body_force"), multiplier_ratio=d.get("multiplier_ratio"),
                    multiplier_size=d.get("multiplier_size"), space=d.get("space"),
                    model=self.sections["bodies"]["entries"][0]["material"].get("model"),
                    formulation=self.sections["bodies"]["entries"][0]["material"].get("formulation"),
                    pairs=self.pairs(),
                )
            mesh = self.mesh()
            for k, pair in enumerate(self.get("contact", "pairs", [])):
                if pair["edge_set"] not in mesh.edge_sets:
                    key = f"contact.pairs[{k}].edge_set"
                    raise SceneError(f"scene key '{key}' = {pair['edge_set']!r}: the mesh has no such edge set (it has: "
                                     f"{', '.join(sorted(mesh.edge_sets))})", key)
            return Problem(
                mesh,
                **self.materials(mesh),
                model=self.get("material", "model"),
                formulation=self.get("material", "formulation"),
                clamped=self.get("supports", "clamped"),
                supports=self.supports(),
                contact=self.get("contact", "edge_set"),
                obstacle=obstacle,
                approach=o.get("approach"),
                rotation=o.get("rotation"),
                shift=o.get("shift"),
                tractions=loads.get("tractions"),
                pressures=loads.get("pressures"),
                body_force=loads.get("body_force"),
                multiplier_ratio=d.get("multiplier_ratio"),
                multiplier_size=d.get("multiplier_size"),
                space=d.get("space"),
                pairs=self.pairs(),
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
        bars = bool(self.get("estimate", "error_bars", False))
        solution = problem.solve(progress=progress, on_phase=on_phase, error_bars=bars, **self.solve_kwargs())
        warn_solution(problem, solution, stacklevel=2)
        if bars:
            warn_missing_error_bars(solution, stacklevel=2)
        return problem, solution

    @property
    def has_adapt(self) -> bool:
        """True when the scene has an ``[adapt]`` table."""
        return "adapt" in self.sections

    def solve_adaptive(
        self, problem: Problem | None = None, progress: Callable[[int, float, float], object] | None = None
    ) -> Adaptive:
        """Builds (unless given) and solves adaptively with the ``[adapt]`` table's settings."""
        problem = problem if problem is not None else self.build()
        with _adapt_keys():
            return problem.solve_adaptive(progress=progress, **self.adapt_kwargs(), **self.solve_kwargs())

    def adapt_kwargs(self) -> dict[str, Any]:
        """The ``[adapt]`` table's keywords of the adaptive solve (``write_levels`` is ``tribo run``'s)."""
        return {k: v for k, v in self.sections.get("adapt", {}).items() if k != "write_levels"}

    @property
    def has_history(self) -> bool:
        """True when the scene has a ``[history]`` table."""
        return "history" in self.sections

    def history_steps(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The steps of ``[history]``: approach, shift and load factor per step (the first waypoint is step 0)."""
        columns = self.history_columns()
        return columns["approach"], columns["shift"], columns["load_factor"]

    def history_columns(self) -> dict[str, Any]:
        """The steps of ``[history]`` per column: ``approach``, ``shift``, ``load_factor``, ``angle`` (NaN: the
        obstacle does not turn) and
        ``displacements`` (a dict of the prescribed components the history moves), sampled from the
        waypoints (the first waypoint is step 0)."""
        h = self.sections.get("history", {})
        o = self.sections.get("obstacle", {})
        given = {
            "approach": h.get("approach", o.get("approach", 0.0)),
            "shift": h.get("shift", o.get("shift", 0.0)),
            "load_factor": h.get("load_factor", 1.0),
            "angle": h.get("angle", o["rotation"][1] if "rotation" in o else np.nan),
        }
        moved = h.get("displacements", {})
        lengths = {k: len(v) for k, v in {**given, **moved}.items() if isinstance(v, list)}
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

        columns: dict[str, Any] = {name: sample(v) for name, v in given.items()}
        columns["displacements"] = {name: sample(v) for name, v in moved.items()}
        return columns

    def solve_history(
        self, problem: Problem | None = None, progress: Callable[[int, int, str, float], object] | None = None,
        keep_every: int | None = None,
    ) -> tuple[Problem, History]:
        """Builds (unless given) and solves the ``[history]``; returns the problem and the history. ``keep_every``
        (keep the solutions of every k-th step and the last) applies unless the ``[solver]`` table sets it."""
        problem = problem if problem is not None else self.build()
        c = self.history_columns()
        kw = {**({} if keep_every is None else {"keep_every": keep_every}), **self.solve_kwargs()}
        return problem, problem.solve_history(c["approach"], c["shift"], c["load_factor"], rotation=c["angle"],
                                              displacements=c["displacements"] or None, progress=progress, **kw)

    def solve_history_adaptive(
        self, problem: Problem | None = None, progress: Callable[[int, float, float], object] | None = None
    ) -> AdaptiveHistory:
        """Builds (unless given) and solves the ``[history]`` adaptively with the ``[adapt]`` table's settings."""
        problem = problem if problem is not None else self.build()
        c = self.history_columns()
        kw = {**self.adapt_kwargs(), **self.solve_kwargs()}
        with _adapt_keys():
            return problem.solve_history_adaptive(c["approach"], c["shift"], c["load_factor"], rotation=c["angle"],
                                                  displacements=c["displacements"] or None, progress=progress, **kw)

    def to_dict(self) -> dict[str, Any]:
        """The scene as plain data (for the JSON summary)."""
        out: dict[str, Any] = {"title": self.title, "description": self.description}
        for section, values in self.sections.items():
            out[section] = {k: list(v) if isinstance(v, tuple) else v for k, v in values.items()}
        return out


def _obstacle_of(o: Mapping[str, Any]) -> Obstacle:
    """The obstacle of a table of the keys of ``[obstacle]`` (checked by ``parse_scene``; the core checks the values)."""
    shape = o.get("shape", "flat")
    if shape in ("circle", "parabola"):
        make = Obstacle.circle if shape == "circle" else Obstacle.parabola
        return make(o["radius"], o.get("center", 0.0))
    if shape == "polyline":
        return Obstacle.polyline(o["xi"], o["gap"])
    if shape == "line":
        return Obstacle.line(o["point"], o["normal"])
    if shape in ("disc", "hole"):
        return (Obstacle.disc if shape == "disc" else Obstacle.hole)(o["center"], o["radius"])
    if shape == "profile":
        return Obstacle.profile(o["points"])
    return Obstacle.flat()


def _support(entry: Mapping[str, Any]) -> Support:
    """One checked support entry as a ``tribo.Support``."""
    kind, name = entry["kind"], entry["edge_set"]
    if kind == "clamp":
        return Support.clamp(name)
    if kind == "roller":
        return Support.roller(name)
    if kind == "rotation":
        return Support.rotation(name, entry["center"], entry["angle"])
    return Support.displacement(name, x=entry.get("x"), y=entry.get("y"))


def parse_scene(data: Mapping[str, Any], base_dir: Path | None = None) -> Scene:
    """Checks a scene given as a dict (as tomllib returns it): unknown keys and bad types are errors, and so
    are ``[adapt]`` settings the core refuses (before any mesh is made; ``adapt.on`` and ``max_unknowns``
    against the steps and the first mesh when the loop starts)."""
    scene = Scene(
        sections=check_scene(data),
        title=str(data.get("title", "")),
        description=str(data.get("description", "")),
        base_dir=base_dir if base_dir is not None else Path.cwd(),
    )
    if scene.has_adapt:
        with _adapt_keys():
            check_adapt(**{k: v for k, v in scene.adapt_kwargs().items() if k != "on"})
    return scene


def load_scene(path: str | Path) -> Scene:
    """Reads and checks a TOML scene file."""
    path = Path(path)
    return parse_scene(read_scene_data(path), base_dir=path.resolve().parent)


def read_scene_data(path: Path) -> dict[str, Any]:
    """The TOML data of a scene file, unchecked (``parse_scene`` checks it)."""
    try:
        with path.open("rb") as f:
            data = tomllib.load(f)
    except OSError as e:
        raise SceneError(f"cannot read scene file {path}: {e.strerror}") from e
    except UnicodeDecodeError as e:  # tomllib decodes the bytes as UTF-8 before it parses them
        raise SceneError(f"scene file {path} is not UTF-8 text: {e.reason} at byte {e.start}") from e
    except tomllib.TOMLDecodeError as e:
        raise SceneError(f"scene file {path} is not valid TOML: {e}") from e
    except RecursionError as e:  # tomllib reads nested arrays and inline tables by recursion (defect D32)
        raise SceneError(f"scene file {path} nests arrays or inline tables too deeply to be read") from e
    return data


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


@contextlib.contextmanager
def _adapt_keys() -> Iterator[None]:
    """The core's refusal of an adaptive setting (``adapt_tol``, …, which it checks when the scene is read and
    when the loop starts) as a ``SceneError`` naming the scene key (``adapt.tol``), the core's words kept."""
    try:
        yield
    except TriboError as e:
        name = str(getattr(e, "details", {}).get("name", ""))
        if not name.startswith("adapt_"):
            raise
        # The core names the steps of `on` adapt_steps; the other names are the scene keys' own.
        key = "adapt.on" if name == "adapt_steps" else f"adapt.{name.removeprefix('adapt_')}"
        what = e.details.get("what", str(e))
        value = e.details.get("value")
        shown = "" if value is None else f" = {int(value) if float(value).is_integer() else value}"
        raise SceneError(f"scene key '{key}'{shown}: {what}", key) from e
