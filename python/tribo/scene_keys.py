"""What every scene key means: its meaning, unit and default, beside what its value must be (the checkers of
``tribo.scene_schema``), as one table, and the JSON Schema of scene files built from the same.

``markdown_table()`` renders the table; ``docs/guide/scene-files.md`` holds it between its ``scene-keys``
markers (so that it reads on the repository host too). ``json_schema()`` is the JSON Schema (draft
2020-12) of a scene file as ``tomllib`` reads it: every table and key with its type, range or choices and
its meaning, so that an editor that checks TOML against a schema (Taplo, "Even Better TOML") completes and
checks scene files; it ships as ``scene.schema.json`` beside this module (``SCHEMA_FILE``). The schema checks
keys and types; the scene reader checks the rest (which keys a shape requires, one body or two). Tests check
that both files are the ones this module makes. To write them again after a change:
``python -m tribo.scene_keys docs/guide/scene-files.md python/tribo/scene.schema.json``.

Units: a scene has no unit system; any consistent one works. "length" is the unit of the coordinates,
"stress" that of Young's modulus (force per area in 2D: force per length per unit thickness), "—" a pure
number. Where the core holds a default, the table shows the core's (``tribo.solver_defaults()``), so that
the two cannot disagree.
"""

from __future__ import annotations

import functools
import json
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

from tribo._tribo import solver_defaults
from tribo.scene_schema import BODY_KEYS, BODY_TABLES, MAX_HISTORY_STEPS, SCHEMA, SUPPORT_KINDS, describe_keys

SCHEMA_FILE = Path(__file__).with_name("scene.schema.json")

# table.key → (meaning, unit, default). A default of None is shown from the core's (``solver_defaults``).
_BODY = {
    "x": ("The rectangle's extent along x (with `y`; or `mesh`)", "length", "—"),
    "y": ("The rectangle's extent along y (with `x`; or `mesh`)", "length", "—"),
    "mesh": ("A mesh file meshio reads, relative to the scene file; its named line sets are the edge sets "
             "(a rectangle has `bottom`, `right`, `top`, `left`)", "—", "—"),
    "ring": ("A ring sector `{ center = [x, y], radii = [r_in, r_out], angles = [a0, a1] }` (angles in degrees, "
             "r_in ≥ r_out / 4; or `x`/`y`, or `mesh`): edge sets `outer`, `inner`, `start`, `end`, the arcs on their "
             "circles (refinement and a bent pair's gap follow them)", "length", "—"),
    "disc": ("A disc `{ center = [x, y], radius = R }`, or its sector between `angles = [a0, a1]` (degrees; "
             "`[180, 360]` a half-disc, flat on top), uniform at `h`: edge sets `rim` on its circle, and a sector's "
             "`start`, `end`", "length", "—"),
    "plate": ("A plate with a hole `{ center = [x, y], radius = R, half_widths = [a, b] }`, the plate [x − a, x + a] × "
              "[y − b, y + b]: edge sets `hole` on its circle, `right`, `top`, `left`, `bottom`; its nodes about `h` "
              "apart round the hole, its cells growing toward the plate's edge", "length", "—"),
}
_MATERIAL = {
    "young": ("Young's modulus E (*required*)", "stress", "—"),
    "poisson": ("Poisson's ratio ν (*required*)", "—", "—"),
}
_GRID = {
    "grading": ('Where a rectangle is refined: `"auto"` toward where contact can occur, `"none"` (uniform, size '
                "`h`) or `[a, b]`, a segment of the contact side; a ring is uniform (`\"auto\"`, `\"none\"`) or graded "
                "toward `[a0, a1]`, an arc of its outer circle in degrees; a disc and a plate are uniform (`\"auto\"`, "
                "`\"none\"`)", "—", '`"auto"`'),
    "h": ("The largest cell size (a plate's: its nodes' spacing round the hole)", "length",
          "a quarter of the shorter side (of a disc's, a plate's hole's radius)"),
    "h_min": ("The cell size at the contact zone (graded meshes)", "length", "h / 16"),
    "growth": ("How fast the cells grow away from the contact zone (graded meshes)", "—", "0.15"),
    "diagonal": ("How each square of a uniform mesh is split", "—", '`"right"`'),
}
MEANINGS: dict[str, tuple[str, str, str | None]] = {
    **{f"body.{k}": v for k, v in _BODY.items()},
    **{f"material.{k}": v for k, v in _MATERIAL.items()},
    "material.regions": ("Parts of the body of other materials (`[[material.regions]]`): each `young`, `poisson` and "
                         "`group` (a physical surface of the mesh file) or `box = [x0, y0, x1, y1]` (the triangles "
                         "whose centroid lies in it); a later one holds where two overlap", "—",
                         "none: all of `[material]`"),
    "material.model": ('`"plane_strain"` (a long body), `"axisymmetric"` (the solid of revolution of the mesh about '
                       'the y axis: x = r ≥ 0, the axis held at u_r = 0, tractions per unit area, forces on the whole '
                       'turn) or `"plane_stress"` (a thin plate, forces per unit '
                       "thickness, ν in (−1/2, 1/2))", "—", None),
    "material.formulation": ('`"displacement"` (P1 displacements, which lock as ν → ½), `"mixed"` (P1 displacements '
                             "and pressures with MINI's condensed bubble: free of locking, for rubber and other nearly "
                             'incompressible bodies; every model, ν > 0) or `"auto"` (mixed '
                             "from ν = 0.49 in plane strain and axisymmetry)", "—", None),
    "supports.clamped": ("The edge sets held fixed (u = 0); or `[[supports]]` entries with `kind` (`clamp`, "
                         "`roller`, `displacement` with `x`/`y`, `rotation` with `center` and `angle` in radians) and "
                         "`edge_set`", "—", "— (*required*, one form)"),
    "loads.body_force": ("The body force f per unit area (per unit volume in axisymmetry), in global axes",
                         "stress / length", "[0, 0]"),
    "loads.tractions": ("The traction per unit length (per unit area of the surface in axisymmetry) on each named "
                        "edge set (Γ_N), in global axes", "stress",
                        "none"),
    "loads.pressures": ("The pressure p on each named edge set (Γ_N): the traction −p n along each edge's outward "
                        "normal (a bore, a curved side; p > 0 presses on the body)", "stress", "none"),
    "contact.edge_set": ("The edge set Γ_C that meets the obstacle: one chain of boundary edges, straight or bent, open or "
                         "closed (a full ring's rim; *required* for one body)", "—", "—"),
    "contact.secondary": ("Two bodies: the side that carries the multipliers and the stabilization, "
                          "`body.edge_set`", "—", "—"),
    "contact.primary": ("Two bodies: the other side, `body.edge_set` (on the secondary's line, or bent sides facing "
                        "each other, their gap the geometry's)", "—", "—"),
    "contact.gap": ("Two bodies: the initial gap between the sides, as an obstacle shape", "length",
                    "flat (touching)"),
    "contact.pairs": ("Further contact pairs (`[[contact.pairs]]`): each an `edge_set` of the body (with "
                      "`[[bodies]]`: of either body, `body.set`) against its own "
                      "rigid obstacle, given by the keys of `[obstacle]` (`shape` and its keys, `approach`, `shift`; "
                      "it does not turn) and its own Coulomb coefficient `mu` (default `friction.mu`; it needs "
                      "`friction.mu`); with a `[history]` it stays where it is (the steps move the first pair's "
                      "obstacle)", "—", "none: one pair"),
    "obstacle.shape": ("The rigid obstacle: a gap function of the abscissa on Γ_C (`flat`, `circle`, `parabola`, "
                       "`polyline`) or a shape given by its geometry (`line`, `disc`, `hole`, `profile`)", "—",
                       '`"flat"`'),
    "obstacle.radius": ("The radius R of a circle, a parabola, a disc or a hole (*required* for them)", "length",
                        "—"),
    "obstacle.center": ("The abscissa ξ on Γ_C of a circle's or parabola's lowest point; the centre `[x, y]` of a "
                        "disc or a hole (*required* for them)", "length", "0"),
    "obstacle.point": ("A point `[x, y]` of a line obstacle's surface (*required* for it)", "length", "—"),
    "obstacle.normal": ("A line obstacle's normal `[x, y]`, out of the obstacle toward the body (*required* for "
                        "it)", "—", "—"),
    "obstacle.points": ("A profile's polyline, points `[x, y]` in order, the obstacle on its right from the first to "
                        "the last (*required* for it)", "length", "—"),
    "obstacle.xi": ("A polyline's abscissae on Γ_C, increasing (*required* for it)", "length", "—"),
    "obstacle.gap": ("A polyline's initial gap at each of its abscissae (*required* for it)", "length", "—"),
    "obstacle.approach": ("δ: how far the obstacle moves toward the body (against the outward normal n; a shape given "
                          "by its geometry: the gap lowered by δ everywhere)",
                          "length", "0"),
    "obstacle.shift": ("s: how far the obstacle moves along t = (−n₂, n₁), small sliding", "length", "0"),
    "obstacle.rotation": ("`{ center = [x, y], angle = a }`: the obstacle (a line, disc, hole or profile) turned by a "
                          "radians counterclockwise about the centre, its surface sliding with the turn (a history "
                          "may turn it further: `history.angle`)", "—", "none"),
    "friction.mu": ("Coulomb's friction coefficient μ (0: frictionless)", "—", "frictionless"),
    "friction.threshold": ("Tresca's threshold: the bound of |λ_t| wherever the body slides", "stress", "—"),
    **{f"discretization.{k}": v for k, v in _GRID.items()},
    "discretization.multiplier_ratio": ("H/h: the multiplier cell size over the FE edge length on Γ_C", "—",
                                        None),
    "discretization.multiplier_size": ("H, the multiplier cell size (instead of `multiplier_ratio`)", "length",
                                       "—"),
    "discretization.space": ("The multiplier space: P0, or continuous P1", "—", None),
    "discretization.gamma0": ("γ0 in γ = γ0 h_T (0: the mixed method without stabilization); below the "
                              "admissible bound", "1 / stress", "—"),
    "discretization.gamma0_fraction": ("γ0 as a fraction of its admissible bound", "—", None),
    "history.shift": ("s at each waypoint (or one value for all)", "length", "`obstacle.shift`"),
    "history.approach": ("δ at each waypoint (or one value for all)", "length", "`obstacle.approach`"),
    "history.load_factor": ("The factor on the loads at each waypoint", "—", "1"),
    "history.angle": ("The obstacle's angle at each waypoint, about the centre of `obstacle.rotation` (which it "
                      "needs); the contact frame stays the problem's: small rotations", "radian",
                      "`obstacle.rotation.angle`"),
    "history.displacements": ("Paths of prescribed displacement components (`set.x`, `set.y`; `body.set.x` "
                              "for two bodies)", "length", "unchanged"),
    "history.steps": ("Steps from one waypoint to the next (one count, or one per segment)", "—", "10"),
    "history.plot_steps": ("The steps whose tractions the plots show", "—", "first, middle, last"),
    "history.write_every": ("`tribo run` writes the VTU files of every k-th step and the last", "—",
                            "1 up to 200 steps, then the smallest k within 200"),
    "adapt.tol": ("The relative estimated error of the contact tractions at which the loop stops", "—", "0.01"),
    "adapt.max_unknowns": ("The largest level, in unknowns (displacements, and pressures in the mixed formulation)",
                           "—", "200 000"),
    "adapt.theta": ("Dörfler's θ (the share of the indicators marked), or the fraction of the largest",
                    "—", "0.5"),
    "adapt.marking": ("How triangles are marked", "—", '`"dorfler"`'),
    "adapt.bisection": ("How a marked triangle is bisected", "—", '`"all_edges"`'),
    "adapt.max_levels": ("The most levels", "—", "40"),
    "adapt.algebraic": ("A coarse level's fixed point stops at this fraction of the previous level's estimate",
                        "—", "0.1"),
    "adapt.stop_on": ("The estimate `tol` is read against: `\"hierarchical\"` the smaller of the bound and the "
                      "hierarchical estimate (sharp, not a bound), the bound calibrated by it on the level after; "
                      "`\"enriched\"` the same, and the answer enriched for a level's estimate handed back where its "
                      "own estimate meets `tol` and the level's does not (P1 multipliers, a mesh without curves); "
                      "`\"bound\"` the bound alone (safe, pessimistic)", "—", '`"hierarchical"`'),
    "adapt.on": ("With `[history]`: the steps whose indicators mark", "—", "every step"),
    "adapt.write_levels": ("`tribo run` also writes every level, each but the last (the answer) solved again "
                           "(`levels/`, `adapt.pvd`)", "—",
                           "false"),
    "solver.qp_tol": ("The tolerance of each scaled QP (gap, feasibility)", "—", None),
    "solver.qp_max_iter": ("The iteration cap of each QP", "—", None),
    "solver.qp_kkt_solver": ("clarabel's KKT solver", "—", None),
    "solver.qp_working_set": ("Solve each QP on the dofs near the contact zone first (false: all of Γ_C)", "—",
                              None),
    "solver.qp_method": ("The QP method: clarabel, the active-set method, or chosen", "—", None),
    "solver.fp_tol": ("The Coulomb fixed point stops when λ_n changes by less than this, relatively (Newton: when "
                      "‖C‖ / ‖λ_n‖ is)", "—", None),
    "solver.fp_max_iter": ("The iteration cap of the Coulomb fixed point", "—", None),
    "solver.fp_relaxation": ("The relaxation ω ∈ (0, 1] of the fixed point", "—", None),
    "solver.coulomb": ("The Coulomb method: the fixed point (the reference), semismooth Newton, or auto (the "
                       "fixed point where H is not formed, else Newton falling back to the fixed point)", "—", None),
    "solver.coulomb_check": ("Solve a converged Coulomb problem again by the other method and say whether the two "
                             "answers agree (two answers: λ is not unique there)", "—", None),
    "solver.memory_budget": ("The bytes a solve may take (factorization, dense parts, a history's solutions)",
                             "bytes", "what the process may still allocate"),
    "solver.condensation": ("How H is formed", "—", None),
    "solver.keep_every": ("A history keeps the whole solution of every k-th step and of the last", "—", None),
    "estimate.error_bars": ("Also solve the problem enriched everywhere and report the error bars of the forces "
                            "and zone widths", "—", "false"),
    "bodies.name": ("The body's name (*required*)", "—", "—"),
    **{f"bodies.{k}": v for k, v in _BODY.items()},
    **{f"bodies.material.{k}": v for k, v in _MATERIAL.items()},
    "bodies.material.model": ('`"plane_strain"`, `"plane_stress"` or `"axisymmetric"`: both bodies take the same',
                              "—", None),
    "bodies.material.formulation": ('`"auto"` (mixed when either body reaches ν = 0.49 in plane strain or axisymmetry), '
                                    '`"displacement"` or `"mixed"`: both bodies take the same', "—", None),
    "bodies.material.regions": ("Parts of the body of other materials (`[[bodies.material.regions]]`), as "
                                "`[[material.regions]]`", "—", "none: all of the body's `material`"),
    "bodies.loads.tractions": ("The traction per unit length on each named edge set of the body", "stress",
                               "none"),
    "bodies.loads.pressures": ("The pressure on each named edge set of the body, along each edge's outward normal",
                               "stress", "none"),
    **{f"bodies.discretization.{k}": v for k, v in _GRID.items()},
    "bodies.supports": ("The body's supports, as `[[supports]]` entries (*required*; `[]`: held by the contact "
                        "alone)", "—", "—"),
}

BEGIN = "<!-- scene-keys: generated by `python -m tribo.scene_keys`; a test checks it -->"
END = "<!-- end scene-keys -->"


def rows() -> list[tuple[str, str, str, str, str, str]]:
    """(table, key, meaning, unit, default, value) for every key the scene reader takes, in its order.

    Raises KeyError for a key without a meaning (a test keeps them in step)."""
    out = []
    for table, key, value in describe_keys():
        meaning, unit, default = _meaning(f"{table}.{key}")
        out.append((f"[[{table}]]" if table == "bodies" else f"[{table}]", f"`{key}`", meaning, unit, default, value))
    return out


def _meaning(name: str) -> tuple[str, str, str]:
    meaning, unit, default = MEANINGS[name]
    return meaning, unit, default if default is not None else _show(_core_defaults()[name.split(".")[-1]])


@functools.cache
def _core_defaults() -> dict[str, Any]:
    """The core's defaults (``tribo.solver_defaults()``), read once for the whole table."""
    return solver_defaults()


def _show(value: object) -> str:
    if isinstance(value, bool):
        return str(value).lower()
    if isinstance(value, str):
        return f'`"{value}"`'
    return f"{value:g}" if isinstance(value, float) else str(value)


def markdown_table() -> str:
    """The table of every scene key in Markdown, between the ``BEGIN`` and ``END`` markers."""
    lines = [BEGIN, "", "| table | key | meaning | unit | default | value |", "|---|---|---|---|---|---|"]
    lines += ["| " + " | ".join(cell.replace("|", "\\|") for cell in row) + " |" for row in rows()]
    return "\n".join([*lines, "", END])


_NUMBER = {"type": "number"}
_PAIR = {"type": "array", "items": _NUMBER, "minItems": 2, "maxItems": 2}
_PATH = {"oneOf": [_NUMBER, {"type": "array", "items": _NUMBER, "minItems": 2}]}
_STEPS = {"type": "integer", "minimum": 1, "maximum": MAX_HISTORY_STEPS}
# The JSON Schema of each checker of ``tribo.scene_schema`` by its name (those the factories make carry theirs).
_BY_CHECKER: dict[str, dict[str, Any]] = {
    "_number": _NUMBER,
    "_integer": {"type": "integer"},
    "_boolean": {"type": "boolean"},
    "_string": {"type": "string"},
    "_pair": _PAIR,
    "_range": _PAIR,
    "_center": {"oneOf": [_NUMBER, _PAIR]},
    "_numbers": {"type": "array", "items": _NUMBER},
    "_path": _PATH,
    "_counts": {"oneOf": [_STEPS, {"type": "array", "items": _STEPS, "minItems": 1}]},
    "_every": {"type": "integer", "minimum": 1},
    "_steps": {"type": "array", "items": {"type": "integer", "minimum": 0}},
    "_names": {"oneOf": [{"type": "string"}, {"type": "array", "items": {"type": "string"}, "minItems": 1}]},
    "_grading": {"oneOf": [{"enum": ["auto", "none"]}, _PAIR]},
    "_pairs": {"type": "object", "additionalProperties": _PAIR},
    "_pressures": {"type": "object", "additionalProperties": _NUMBER},
    "_points": {"type": "array", "items": _PAIR, "minItems": 2},
    "_paths": {"type": "object", "additionalProperties": _PATH},
}


def _key(name: str, check: Callable[..., Any]) -> dict[str, Any]:
    """The schema of one key: its checker's, with its meaning, unit and default as the description."""
    if check.__name__ == "_shape":
        shape = {k: _key(f"obstacle.{k}", c) for k, c in SCHEMA["obstacle"].items() if k not in ("approach", "shift")}
        own: dict[str, Any] = {"type": "object", "additionalProperties": False, "properties": shape}
    elif check.__name__ == "_contact_pairs":  # an edge set and the keys of [obstacle] but its rotation
        keys = {k: _key(f"obstacle.{k}", c) for k, c in SCHEMA["obstacle"].items() if k != "rotation"}
        keys["edge_set"] = _key("contact.edge_set", SCHEMA["contact"]["edge_set"])
        own_mu = "The pair's own Coulomb coefficient μ (it needs friction.mu). Unit: —. Default: friction.mu."
        keys["mu"] = {**_key("friction.mu", SCHEMA["friction"]["mu"]), "description": own_mu}
        own = {"type": "array", "items": {"type": "object", "required": ["edge_set"], "additionalProperties": False,
                                          "properties": keys}}
    else:
        own = getattr(check, "json_schema", None) or _BY_CHECKER[check.__name__]
    return {**own, "description": _description(name)}


def _description(name: str) -> str:
    meaning, unit, default = _meaning(name)
    return f"{meaning}. Unit: {unit}. Default: {default}.".replace("`", "")


def _table(prefix: str, keys: dict[str, Callable[..., Any]]) -> dict[str, Any]:
    properties = {k: _key(f"{prefix}.{k}", c) for k, c in keys.items()}
    return {"type": "object", "additionalProperties": False, "properties": properties}


def json_schema() -> dict[str, Any]:
    """The JSON Schema (draft 2020-12) of a scene file as ``tomllib`` reads it (see the module documentation)."""
    tables = {t: _table(t, keys) for t, keys in SCHEMA.items()}
    tables["material"]["required"] = ["young", "poisson"]
    support = {"type": "object", "required": ["kind", "edge_set"], "additionalProperties": False,
               "properties": {"kind": {"enum": list(SUPPORT_KINDS)}, "edge_set": {"type": "string"}, "x": _NUMBER,
                              "y": _NUMBER, "center": _PAIR, "angle": _NUMBER}}
    supports = {"type": "array", "items": support, "description": _description("bodies.supports")}
    # The reader takes an empty list too (a body held by the contact alone), so the schema does.
    tables["supports"] = {"oneOf": [tables["supports"], supports]}
    body = _table("bodies", BODY_KEYS)
    body["properties"] |= {t: _table(f"bodies.{t}", keys) for t, keys in BODY_TABLES.items()} | {"supports": supports}
    body["required"] = ["name", "material", "supports"]
    tables["bodies"] = {"type": "array", "items": body, "minItems": 2, "maxItems": 2,
                        "description": "Two elastic bodies in contact, instead of [body], [material], [supports] "
                                       "and [obstacle]."}
    text = {"type": "string"}
    return {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": "tribo scene file",
        "description": "A scene of tribo (tribo run SCENE.toml): every table and key, as tribo.scene_keys makes it.",
        "type": "object",
        "additionalProperties": False,
        "properties": {"title": text, "description": text, **tables},
    }


def rewrite(path: Path) -> bool:
    """Writes ``path`` again: the JSON Schema for a ``.json`` file, else the table between the markers of the
    page; True if it changed."""
    text = path.read_text(encoding="utf-8") if path.exists() else ""
    if path.suffix == ".json":
        new = json.dumps(json_schema(), indent=1, ensure_ascii=False) + "\n"
    else:
        start, end = text.index(BEGIN), text.index(END) + len(END)
        new = text[:start] + markdown_table() + text[end:]
    path.write_text(new, encoding="utf-8")
    return new != text


if __name__ == "__main__":
    for name in sys.argv[1:]:
        print(f"{name}: {'rewritten' if rewrite(Path(name)) else 'unchanged'}")
