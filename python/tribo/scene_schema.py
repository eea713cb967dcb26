"""The scene schema: the tables a scene may have, the keys of each, the type and range of every value,
and ``check_scene``, which checks a scene dict (as ``tomllib`` returns it) against them. ``tribo.scene``
builds the checked scene into a mesh and a problem and solves it.

A scene has these tables (every key is optional unless marked *required*; see ``scenes/demo.toml``):

``[body]``
    ``x``, ``y``: the rectangle's ranges, e.g. ``x = [-2.0, 2.0]``; or ``mesh``: a mesh file meshio reads
    (a path relative to the scene file), whose named line sets are the edge sets; or ``disc = { center = [x, y],
    radius = R, angles = [a0, a1] }``: a disc or its sector (angles in degrees, default a whole turn), uniform at
    ``h``, its edge sets ``rim``, ``start``, ``end``; or ``plate = { center = [x, y], radius = R, half_widths = [a,
    b] }``: a plate with a hole, its nodes about ``h`` apart round the hole, its edge sets ``hole``, ``right``,
    ``top``, ``left``, ``bottom``; or ``ring = { center = [x,
    y], radii = [r_in, r_out], angles = [a0, a1] }``: a ring sector (angles in degrees), its edge sets ``outer``,
    ``inner``, ``start``, ``end`` and its arcs on their circles. One of these is required. A rectangle has the
    edge sets ``bottom``, ``right``, ``top``, ``left``.
``[material]``
    ``young``, ``poisson`` (*required*); ``model``: ``"plane_strain"`` (default), ``"plane_stress"`` or
    ``"axisymmetric"``; ``formulation``: ``"auto"`` (default: mixed from ν = 0.49 in plane strain and axisymmetry),
    ``"displacement"`` or ``"mixed"`` (displacements and pressures, free of locking as ν → ½; every model);
    ``[[material.regions]]``: parts of the body of other materials, each with ``young``, ``poisson`` and
    ``group`` (a physical surface of the mesh file) or ``box = [x0, y0, x1, y1]`` (the triangles whose
    centroid lies in it; put the interface on a grid line), a later one holding where two overlap.
``[supports]`` or ``[[supports]]`` (*required*, one of the two forms)
    ``[supports]`` with ``clamped``: an edge set name or a list of names (u = 0 there). Or a list of
    ``[[supports]]`` entries, each with ``kind`` and ``edge_set``: ``kind = "clamp"`` (u = 0),
    ``"roller"`` (u·n = 0 on a straight set of any direction, tangential component free: a symmetry
    line), ``"displacement"`` with ``x`` and/or ``y`` (prescribed components; one left out is free) or
    ``"rotation"`` with ``center = [x, y]`` and ``angle`` (radians: a small rigid rotation of the set).
    Conditions meeting at a node combine (a clamp and a roller at a corner clamp it); contradictory ones
    are an error that names the node.
``[loads]``
    ``body_force = [fx, fy]``; ``[loads.tractions]``: ``edge_set = [tx, ty]`` per loaded edge set;
    ``[loads.pressures]``: ``edge_set = p`` (the traction −p n along each edge's outward normal).
``[contact]``
    ``edge_set`` (*required*): the edge set Γ_C, one chain of edges (straight, or bent against an
    obstacle given by its geometry; open, or closed: a full ring's rim). ``[[contact.pairs]]``: further pairs, each
    an ``edge_set`` against its own rigid obstacle given by the keys of ``[obstacle]`` (``shape`` and its keys,
    ``approach``, ``shift``; it does not turn, nor move in a ``[history]``).
``[obstacle]``
    ``shape``: ``"flat"`` (default), ``"circle"``, ``"parabola"`` (both with ``radius`` *required* and
    ``center``, an abscissa on Γ_C, default 0) or ``"polyline"`` (``xi`` and ``gap`` lists, *required*):
    gap functions of the abscissa; or, given by its geometry, ``"line"`` (``point`` and ``normal``, out of
    the obstacle, *required*), ``"disc"`` or ``"hole"`` (``center = [x, y]`` and ``radius``, *required*),
    ``"profile"`` (``points``, a list of at least two points [x, y], *required*: the obstacle on the right of
    the polyline from the first to the last, its ends extended);
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
    contact zone; default h / 16), ``growth`` (default 0.15: the largest growth whose own bias in λ_n
    stays under 1 %, measured; the core's ``Grading::DEFAULT_GROWTH``), ``diagonal`` (uniform mesh only).
    For any body: ``multiplier_ratio`` (H/h) or ``multiplier_size`` (H), ``space`` (``"P0"``/``"P1"``),
    ``gamma0`` or ``gamma0_fraction`` (of the admissible bound).
``[history]``
    A quasi-static loading history (``tribo run`` then solves it step by step, see ``tribo.history``):
    piecewise-linear paths through waypoints. ``shift``, ``approach`` and ``load_factor`` are each a
    number (the same at every waypoint) or a list of waypoint values (lists have one length, at least 2);
    unset, they take ``obstacle.shift``, ``obstacle.approach`` and 1. ``angle``, a path too, turns an obstacle
    that has an ``obstacle.rotation`` (radians about its centre; default its angle). ``steps`` (default 10) is the
    number of steps from one waypoint to the next (one count, or a list with one per segment); the first
    waypoint is step 0. ``plot_steps``: the steps whose tractions the plots show (default: the first, the
    middle and the last). ``displacements``: a table of prescribed displacement components
    (``"set.x"``/``"set.y"`` of a ``displacement`` support; ``"body.set.x"`` between two bodies), each a
    path of waypoints like ``shift``; a component left out keeps its value. ``write_every``: ``tribo run``
    writes the VTU files of every k-th step and the last (default: every step up to 200 steps, beyond that
    the smallest k that keeps them within 200; ``history.csv`` has every step).
``[adapt]``
    Adaptive refinement (``tribo run`` then calls ``Problem.solve_adaptive`` from the scene's mesh, see
    ``tribo.adaptive``): ``tol`` (the relative estimated error of the contact tractions at which to stop,
    default 0.01), ``max_unknowns`` (default 200 000), ``theta`` (Dörfler's θ, default 0.5), ``marking``
    (``"dorfler"``/``"maximum"``), ``bisection`` (``"all_edges"``, the default, or ``"refinement_edge"``),
    ``max_levels`` (default 40), ``algebraic`` (default 0.1: a coarse level's
    fixed point stops at that fraction of the previous level's estimate), ``stop_on`` (``"hierarchical"``, the
    default: the smaller of the residual bound and the sharp hierarchical estimate, not a guaranteed bound, at
    the cost of an enriched solve on the levels near ``tol``, the bound calibrated by it on the level after;
    ``"enriched"``: the same, and the enriched answer handed back where its own estimate meets ``tol``;
    ``"bound"``: the residual bound alone, safe but pessimistic). The core checks the values. With a
    ``[history]``, every level solves the whole history (``Problem.solve_history_adaptive``) and is refined on
    the largest indicators over the steps ``on`` (a list of step numbers; default all of them), and the
    history's outputs are those of the last mesh. ``write_levels`` (true/false, default false): ``tribo run``
    also writes every level, each but the last (the answer) solved again to full tolerance (a solve, or a
    history, per level: it costs about what the loop did), as ``levels/level_NNN.vtu`` with the ParaView series ``adapt.pvd``; by default only
    the last level is written (the ``result`` files).
``[solver]``
    Any solver setting by the name ``Problem.solve`` takes (``tribo.solver_settings()`` lists them with
    their kinds and defaults): ``qp_tol``, ``qp_max_iter``, ``qp_kkt_solver`` (``"faer"``/``"qdldl"``),
    ``qp_working_set`` (true/false), ``fp_tol``, ``fp_max_iter``, ``fp_relaxation``, ``coulomb``
    (``"fixed_point"``, ``"newton"`` or ``"auto"``), ``coulomb_check`` (true/false). Unset keys take the
    core's defaults. The table of keys is built from the core's, so it cannot drift from it.
``[estimate]``
    ``error_bars`` (true/false, default false): also solve the problem enriched (every triangle bisected and
    those along the contact zone again, T_H halved with them; 8-9 times the unknowns) and report the error bars
    of the normal and tangential forces and of the contact and stick widths (``P = 0.851 ± 0.0004`` in
    ``tribo run``, the ``*_error`` keys of ``estimate`` in ``summary.json``): 1.5 times their change under the
    enrichment, sharp but not guaranteed bounds. With ``[adapt]``, the last level's hierarchical estimate brings
    them (the same enriched solve); where it has none (the loop stopped on the bound, or handed back an enriched
    answer), ``tribo run`` solves the last level again with them. Not with a ``[history]``.
``[[bodies]]``
    Two elastic bodies in contact, instead of ``[body]``, ``[material]``, ``[supports]`` and ``[obstacle]``.
    Exactly two entries, each with ``name`` (*required*), ``x``/``y``, ``mesh``, ``ring``, ``disc`` or ``plate`` as
    ``[body]``,
    ``material = { young, poisson }`` (*required*; ``model`` the same for both, and ``[[bodies.material.regions]]``
    as ``[[material.regions]]``), ``supports`` (*required*: a list of tables as the
    ``[[supports]]`` entries; a motion they leave free is held by the contact, and ``[]`` leaves the body
    to the contact alone, e.g. a punch pushed by its ``loads``), ``loads = { tractions = { edge_set = [tx,
    ty] } }`` and ``discretization`` with the rectangle's keys (``grading``, ``h``, ``h_min``, ``growth``, ``diagonal``; ``grading = "auto"``
    refines toward the contact: the whole side for a flat gap, ``[c − 2a, c + 2a]`` with ``a = √(2Rδ)`` for a
    curved one, δ the largest prescribed displacement of the scene). ``[contact]`` then names the sides as
    ``secondary = "body.edge_set"`` (it carries the multipliers and the stabilization) and ``primary`` (straight
    sides on one line, or bent sides facing each other: a ring in a ring, whose gap is the arcs'), and
    ``gap`` the initial gap between them as an obstacle shape (``{ shape = "parabola", radius = 1.0 }``;
    default flat: touching). ``[loads]`` keeps ``body_force`` (both bodies); ``[discretization]`` keeps the
    multiplier and γ0 keys. The bodies move through their prescribed displacements: a ``[history]`` moves
    them with ``displacements`` (``approach`` and ``shift`` do not apply).

Top-level ``title`` and ``description`` are free text. An unknown key or a value of the wrong type is a
``SceneError`` that names the key (``scene key 'obstacle.radus' is not known``). Numbers must be finite
(TOML allows ``nan`` and ``inf``), counts lie in the core's range (``tribo.solver_settings()``), ranges
``x``, ``y`` increase, and a uniform grid has at most ``MAX_CELLS`` cells.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from tribo._tribo import MAX_CELLS as _MAX_CELLS
from tribo._tribo import choices, solver_settings
from tribo.scene_values import (
    MAX_HISTORY_STEPS,
    Checker,
    SceneError,
    _boolean,
    _center,
    _choice,
    _count,
    _counts,
    _disc,
    _every,
    _grading,
    _names,
    _number,
    _numbers,
    _pair,
    _pairs,
    _plate,
    _points,
    _path,
    _paths,
    _pressures,
    _range,
    _ring,
    _rotation,
    _steps,
    _string,
)

__all__ = [
    "BODY_KEYS",
    "BODY_TABLES",
    "CHOICES",
    "MAX_CELLS",
    "MAX_HISTORY_STEPS",
    "RENAMED",
    "REQUIRED",
    "SCHEMA",
    "SHAPE_KEYS",
    "SHAPE_REQUIRED",
    "SIDES",
    "SUPPORT_KINDS",
    "Checker",
    "SceneError",
    "check_scene",
]

CHOICES = choices()
SIDES = tuple(CHOICES["side"])

# Keys renamed so that a scene key, a Python keyword and the core's setting name are one name.
RENAMED = {
    "solver.kkt_solver": "solver.qp_kkt_solver",
    "solver.working_set": "solver.qp_working_set",
    "solver.relaxation": "solver.fp_relaxation",
}


# The keys of [obstacle] that move it rather than shape it.
MOTION_KEYS = ("approach", "shift", "rotation")


def _shape(key: str, v: Any) -> dict[str, Any]:
    """An obstacle shape as a table (the initial gap between two bodies): the keys of ``[obstacle]`` that
    describe a shape, checked as there."""
    if not isinstance(v, dict):
        raise SceneError(f"scene key '{key}' must be a table with shape and its keys", key)
    out: dict[str, Any] = {}
    for name, value in v.items():
        check = SCHEMA["obstacle"].get(name) if name not in MOTION_KEYS else None
        if check is None:
            known = ", ".join(k for k in SCHEMA["obstacle"] if k not in MOTION_KEYS)
            raise SceneError(f"scene key '{key}.{name}' is not known (known keys: {known})", f"{key}.{name}")
        out[name] = check(f"{key}.{name}", value)
    _check_obstacle(out, key)
    return out


def _regions(key: str, v: Any) -> list[dict[str, Any]]:
    """A list of tables ``[[material.regions]]``: each a part of the body of another material, with ``young``,
    ``poisson`` and where it lies, ``group`` (a physical surface of the mesh file) or ``box = [x0, y0, x1,
    y1]`` (the triangles whose centroid lies in it).

    The rest of the body is of ``[material]``; where two regions overlap, the later one holds."""
    if not isinstance(v, list) or not all(isinstance(e, dict) for e in v):
        raise SceneError(f"scene key '{key}' must be a list of tables [[{key}]], got {v!r}", key)
    out = []
    for k, entry in enumerate(v):
        where = f"{key}[{k}]"
        for name in entry:
            if name not in ("young", "poisson", "group", "box"):
                raise SceneError(f"scene key '{where}.{name}' is not known (known keys: young, poisson, group, "
                                 "box)", f"{where}.{name}")
        for name in ("young", "poisson"):
            if name not in entry:
                raise SceneError(f"scene key '{where}.{name}' is required", f"{where}.{name}")
        if ("group" in entry) == ("box" in entry):
            raise SceneError(f"scene key '{where}' needs one of group and box (where the material lies)", where)
        region: dict[str, Any] = {name: _number(f"{where}.{name}", entry[name]) for name in ("young", "poisson")}
        if "group" in entry:
            region["group"] = _string(f"{where}.group", entry["group"])
        else:
            box = _numbers(f"{where}.box", entry["box"])
            if len(box) != 4 or not (box[0] < box[2] and box[1] < box[3]):
                raise SceneError(f"scene key '{where}.box' must be [x0, y0, x1, y1] with x0 < x1 and y0 < y1, got "
                                 f"{entry['box']!r}", f"{where}.box")
            region["box"] = box
        out.append(region)
    return out


_regions.json_schema = {  # type: ignore[attr-defined]
    "type": "array",
    "items": {
        "type": "object", "required": ["young", "poisson"], "additionalProperties": False,
        "oneOf": [{"required": ["group"]}, {"required": ["box"]}],
        "properties": {"young": {"type": "number"}, "poisson": {"type": "number"}, "group": {"type": "string"},
                       "box": {"type": "array", "items": {"type": "number"}, "minItems": 4, "maxItems": 4}},
    },
}


def _contact_pairs(key: str, v: Any) -> list[dict[str, Any]]:
    """A list of tables ``[[contact.pairs]]``: each a further contact pair, an ``edge_set`` of the body against its own
    rigid obstacle, given by the keys of ``[obstacle]`` (its shape, their keys, approach, shift), and its own ``mu``."""
    if not isinstance(v, list) or not all(isinstance(e, dict) for e in v):
        raise SceneError(f"scene key '{key}' must be a list of tables [[{key}]], got {v!r}", key)
    out = []
    for k, entry in enumerate(v):
        where = f"{key}[{k}]"
        if "edge_set" not in entry:
            raise SceneError(f"scene key '{where}.edge_set' is required", f"{where}.edge_set")
        pair: dict[str, Any] = {"edge_set": _string(f"{where}.edge_set", entry["edge_set"])}
        for name, value in entry.items():
            check = {**SCHEMA["obstacle"], "mu": _number}.get(name) if name not in ("edge_set", "rotation") else None
            if name == "rotation":
                raise SceneError(f"scene key '{where}.rotation': a further pair's obstacle does not turn", f"{where}.rotation")
            if check is None and name != "edge_set":
                known = ", ".join(["edge_set", *(n for n in SCHEMA["obstacle"] if n != "rotation"), "mu"])
                raise SceneError(f"scene key '{where}.{name}' is not known (known keys: {known})", f"{where}.{name}")
            if check is not None:
                pair[name] = check(f"{where}.{name}", value)
        _check_obstacle(pair, where)
        out.append(pair)
    return out




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
    "body": {"x": _range, "y": _range, "mesh": _string, "ring": _ring, "disc": _disc, "plate": _plate},
    "material": {"young": _number, "poisson": _number, "model": _choice(*CHOICES["model"]),
                 "formulation": _choice(*CHOICES["formulation"]), "regions": _regions},
    "supports": {"clamped": _names},
    "loads": {"body_force": _pair, "tractions": _pairs, "pressures": _pressures},
    "contact": {"edge_set": _string, "secondary": _string, "primary": _string, "gap": _shape, "pairs": _contact_pairs},
    "obstacle": {
        "shape": _choice("flat", "circle", "parabola", "polyline", "line", "disc", "hole", "profile"),
        "radius": _number,
        "center": _center,
        "point": _pair,
        "normal": _pair,
        "points": _points,
        "xi": _numbers,
        "gap": _numbers,
        "approach": _number,
        "shift": _number,
        "rotation": _rotation,
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
    "history": {
        "shift": _path,
        "approach": _path,
        "angle": _path,
        "load_factor": _path,
        "displacements": _paths,
        "steps": _counts,
        "plot_steps": _steps,
        "write_every": _every,
    },
    "adapt": {
        "tol": _number,
        "max_unknowns": _count(2**62),
        "theta": _number,
        "marking": _choice(*CHOICES["marking"]),
        "bisection": _choice(*CHOICES["bisection"]),
        "max_levels": _count(2**62),
        "algebraic": _number,
        "stop_on": _choice(*CHOICES["stop_on"]),
        "on": _steps,
        "write_levels": _boolean,
    },
    "solver": {name: _setting_checker(spec) for name, spec in solver_settings().items()},
    "estimate": {"error_bars": _boolean},
}
REQUIRED = {"material": ("young", "poisson"), "contact": ("edge_set",)}


def describe_keys() -> list[tuple[str, str, str]]:
    """Every key a scene file takes, as (table, key, what its value must be), from the checkers of ``SCHEMA``
    and of ``[[bodies]]`` entries (the documentation site renders this table, so it cannot drift)."""
    def first_line(check: Checker) -> str:
        # The first paragraph, whole (a row cut mid-sentence showed raw markup), in Markdown's quotes.
        paragraph = (check.__doc__ or "").strip().split("\n\n")[0]
        return " ".join(paragraph.split()).replace("``", "`")

    rows = [(table, key, first_line(check)) for table, keys in SCHEMA.items() for key, check in keys.items()]
    rows += [("bodies", key, first_line(check)) for key, check in BODY_KEYS.items()]
    rows += [("bodies", f"{table}.{key}", first_line(check)) for table, keys in BODY_TABLES.items()
             for key, check in keys.items()]
    rows.append(("bodies", "supports", "A list of support tables, as [[supports]] entries ([]: held by the contact)."))
    return rows
# The keys of one [[bodies]] entry: plain values, and the sub-tables with their keys.
BODY_KEYS: dict[str, Checker] = {"name": _string, "x": _range, "y": _range, "mesh": _string, "ring": _ring,
                                 "disc": _disc, "plate": _plate}
BODY_TABLES: dict[str, dict[str, Checker]] = {
    "material": {"young": _number, "poisson": _number, "model": _choice(*CHOICES["model"]),
                 "formulation": _choice(*CHOICES["formulation"]), "regions": _regions},
    "loads": {"tractions": _pairs, "pressures": _pressures},
    "discretization": {k: SCHEMA["discretization"][k] for k in ("grading", "h", "h_min", "growth", "diagonal")},
}
# What [[bodies]] replaces, and the keys of the other tables that are per body or do not apply to two bodies.
ONE_BODY_TABLES = ("body", "material", "supports", "obstacle")
NOT_FOR_TWO_BODIES = {
    "contact": ("edge_set",),
    "loads": ("tractions", "pressures"),
    "discretization": tuple(BODY_TABLES["discretization"]),
    "history": ("approach", "shift", "angle"),
}
# The keys of one [[supports]] entry, by kind (besides kind and edge_set).
SUPPORT_KINDS: dict[str, tuple[str, ...]] = {"clamp": (), "roller": (), "displacement": ("x", "y"),
                                             "rotation": ("center", "angle")}
# The keys of [obstacle] that describe its shape: those each shape takes, and those it requires.
SHAPE_KEYS = {"flat": (), "circle": ("radius", "center"), "parabola": ("radius", "center"), "polyline": ("xi", "gap"),
              "line": ("point", "normal"), "disc": ("center", "radius"), "hole": ("center", "radius"),
              "profile": ("points",)}
SHAPE_REQUIRED = {"flat": (), "circle": ("radius",), "parabola": ("radius",), "polyline": ("xi", "gap"),
                  "line": ("point", "normal"), "disc": ("center", "radius"), "hole": ("center", "radius"),
                  "profile": ("points",)}
# The shapes given by their geometry (for a contact side of any shape), whose center is a point [x, y].
GEOMETRY_SHAPES = ("line", "disc", "hole", "profile")
# The most cells (nx · ny) a uniform rectangle may have: the limit of the core's Mesh.rectangle, checked here
# before nx and ny are rounded to integers (an absurd h would overflow the binding's conversion).
MAX_CELLS = _MAX_CELLS  # the core's limit (tribo.generate::MAX_CELLS)


def _check_obstacle(o: Mapping[str, Any], table: str = "obstacle") -> None:
    """The shape keys of [obstacle] (or of a gap ``table``): each one the shape requires is given, and none
    it does not take; a rotation turns a shape given by its geometry only."""
    shape = o.get("shape", "flat")
    if "rotation" in o and shape not in GEOMETRY_SHAPES:
        raise SceneError(f"scene key '{table}.rotation' turns an obstacle given by its geometry (line, disc, hole, "
                         f"profile), not a {shape}", f"{table}.rotation")
    for key in sorted(set(o) & {k for keys in SHAPE_KEYS.values() for k in keys}):
        if key not in SHAPE_KEYS[shape]:
            raise SceneError(f"scene key '{table}.{key}' does not apply to a {shape} obstacle", f"{table}.{key}")
    for key in SHAPE_REQUIRED[shape]:
        if key not in o:
            raise SceneError(f"scene key '{table}.{key}' is required for a {shape}", f"{table}.{key}")
    if "center" in o and isinstance(o["center"], tuple) != (shape in GEOMETRY_SHAPES):
        what = "two numbers [x, y]" if shape in GEOMETRY_SHAPES else "a number (an abscissa on Γ_C)"
        raise SceneError(f"scene key '{table}.center' must be {what} for a {shape}", f"{table}.center")
    if table == "contact.gap" and shape in GEOMETRY_SHAPES:
        raise SceneError(f"scene key '{table}.shape': the gap between two bodies is a function of the abscissa "
                         f"(flat, circle, parabola or polyline), not a {shape}", f"{table}.shape")


def _body_entry(index: int, entry: Any) -> dict[str, Any]:
    """One ``[[bodies]]`` entry, every key checked: the values of ``BODY_KEYS``, the sub-tables of
    ``BODY_TABLES`` and the list ``supports``."""
    where = f"bodies[{index}]"
    if not isinstance(entry, dict):
        raise SceneError(f"scene key '{where}' must be a table with name, material and supports", where)
    out: dict[str, Any] = {}
    for key, value in entry.items():
        at = f"{where}.{key}"
        if key in BODY_KEYS:
            out[key] = BODY_KEYS[key](at, value)
        elif key in BODY_TABLES:
            if not isinstance(value, dict):
                raise SceneError(f"scene key '{at}' must be a table", at)
            known = BODY_TABLES[key]
            for k in value:
                if k not in known:
                    raise SceneError(f"scene key '{at}.{k}' is not known (known keys: {', '.join(known)})", f"{at}.{k}")
            out[key] = {k: known[k](f"{at}.{k}", v) for k, v in value.items()}
        elif key == "supports":
            if not isinstance(value, list):
                raise SceneError(f"scene key '{at}' must be a list of support tables ([] : held by the contact alone)", at)
            out[key] = [_support_entry(k, e, at) for k, e in enumerate(value)]
        else:
            known_keys = ", ".join([*BODY_KEYS, *BODY_TABLES, "supports"])
            raise SceneError(f"scene key '{at}' is not known (known keys of a body: {known_keys})", at)
    for key in ("name", "material", "supports"):
        if key not in out:
            raise SceneError(f"scene key '{where}.{key}' is required", f"{where}.{key}")
    for key in ("young", "poisson"):
        if key not in out["material"]:
            raise SceneError(f"scene key '{where}.material.{key}' is required", f"{where}.material.{key}")
    if not {"mesh", "ring", "disc", "plate"} & set(out) and not ("x" in out and "y" in out):
        raise SceneError(f"scene key '{where}.x' and '{where}.y' (a rectangle), '{where}.ring', '{where}.disc', "
                         f"'{where}.plate' or '{where}.mesh' is required", where)
    return out


def _check_two_bodies(data: Mapping[str, Any], sections: dict[str, dict[str, Any]]) -> None:
    """The tables of a two-body scene: two named bodies, the pair named, nothing of one body."""
    bodies = sections["bodies"]["entries"]
    if len(bodies) != 2:
        raise SceneError(f"scene key 'bodies' must hold two bodies, got {len(bodies)}", "bodies")
    if bodies[0]["name"] == bodies[1]["name"]:
        raise SceneError(f"scene key 'bodies': both bodies are named {bodies[0]['name']!r}", "bodies[1].name")
    for name in ONE_BODY_TABLES:
        if name in data:
            raise SceneError(f"scene key '{name}' is for one body: with [[bodies]], each body has its own", name)
    for table, keys in NOT_FOR_TWO_BODIES.items():
        for key in keys:
            if key in sections.get(table, {}):
                raise SceneError(
                    f"scene key '{table}.{key}' does not apply to two bodies (see [[bodies]] in the scene format)",
                    f"{table}.{key}",
                )
    for key, default in (("model", "plane_strain"), ("formulation", "auto")):
        values = [b["material"].get(key, default) for b in bodies]
        if values[0] != values[1]:
            raise SceneError(f"scene key 'bodies[1].material.{key}': both bodies take one {key}, got {values[0]!r} "
                             f"and {values[1]!r}", f"bodies[1].material.{key}")
    for key in ("secondary", "primary"):
        if key not in sections.get("contact", {}):
            raise SceneError(f"scene key 'contact.{key}' is required with [[bodies]] ('body.edge_set')", f"contact.{key}")


def _support_entry(index: int, entry: Any, table: str = "supports") -> dict[str, Any]:
    """One ``[[supports]]`` entry (or one of a body's ``supports``): ``kind``, ``edge_set`` and the keys of
    its kind, checked."""
    where = f"{table}[{index}]"
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
        out[key] = (_pair if key == "center" else _number)(f"{where}.{key}", value)
    if kind == "displacement" and "x" not in out and "y" not in out:
        raise SceneError(f"scene key '{where}' (a displacement) needs x, y or both", f"{where}.x")
    for key in SUPPORT_KINDS[kind] if kind == "rotation" else ():
        if key not in out:
            raise SceneError(f"scene key '{where}.{key}' is required for a rotation", f"{where}.{key}")
    return out


def _check_one_body(sections: dict[str, dict[str, Any]]) -> None:
    """The tables a one-body scene needs, and no key of the two-body form."""
    for name, keys in REQUIRED.items():
        for key in keys:
            if key not in sections.get(name, {}):
                raise SceneError(f"scene key '{name}.{key}' is required", f"{name}.{key}")
    if "supports" not in sections:
        raise SceneError("scene key 'supports' is required: [supports] clamped = … or [[supports]] entries", "supports")
    body = sections.get("body", {})
    if not {"mesh", "ring", "disc", "plate"} & set(body) and not ("x" in body and "y" in body):
        raise SceneError("scene key 'body.x' and 'body.y' (a rectangle), 'body.ring', 'body.disc', 'body.plate' or "
                         "'body.mesh' is required", "body")
    for key in ("secondary", "primary", "gap"):
        if key in sections.get("contact", {}):
            raise SceneError(f"scene key 'contact.{key}' names a side of two bodies: it needs [[bodies]]", f"contact.{key}")
    _check_obstacle(sections.get("obstacle", {}))


def check_scene(data: Mapping[str, Any]) -> dict[str, dict[str, Any]]:
    """The tables of a scene given as a dict (as tomllib returns it), each key checked and converted:
    unknown keys and bad types are errors. ``title`` and ``description`` are checked, not returned."""
    sections: dict[str, dict[str, Any]] = {}
    for name, table in data.items():
        if name in ("title", "description"):
            if not isinstance(table, str):
                raise SceneError(f"scene key '{name}' must be a string", name)
            continue
        if name == "bodies":
            if not isinstance(table, list):
                raise SceneError("scene key 'bodies' must be a list of tables: [[bodies]]", name)
            sections[name] = {"entries": [_body_entry(k, e) for k, e in enumerate(table)]}
            continue
        if name not in SCHEMA:
            raise SceneError(f"scene key '{name}' is not known (known tables: {', '.join([*SCHEMA, 'bodies'])})", name)
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
    if "bodies" in sections:
        _check_two_bodies(data, sections)
    else:
        _check_one_body(sections)
    f = sections.get("friction", {})
    if "mu" in f and "threshold" in f:
        raise SceneError("scene keys 'friction.mu' and 'friction.threshold' exclude each other", "friction")
    if sections.get("estimate", {}).get("error_bars") and "history" in sections:
        raise SceneError("scene key 'estimate.error_bars' is for one solve or an adaptive one, not a [history]",
                         "estimate.error_bars")
    if "angle" in sections.get("history", {}) and "rotation" not in sections.get("obstacle", {}):
        raise SceneError("scene key 'history.angle' turns the obstacle about the centre of 'obstacle.rotation', which "
                         "the scene does not give (give it with angle = 0)", "history.angle")
    if "on" in sections.get("adapt", {}) and "history" not in sections:
        raise SceneError("scene key 'adapt.on' names steps of a [history], and the scene has none", "adapt.on")
    d = sections.get("discretization", {})
    for a, b in (("multiplier_ratio", "multiplier_size"), ("gamma0", "gamma0_fraction")):
        if a in d and b in d:
            raise SceneError(
                f"scene keys 'discretization.{a}' and 'discretization.{b}' exclude each other", f"discretization.{a}"
            )
    return sections
