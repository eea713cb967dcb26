"""What every scene key means: its meaning, unit and default, beside what its value must be (the checkers of
``tribo.scene_schema``), as one table.

``markdown_table()`` renders it; ``docs/guide/scene-files.md`` holds the rendered table between its
``scene-keys`` markers (so that it reads on the repository host too) and a test checks that it is the one
this module renders. To write it again after a change: ``python -m tribo.scene_keys docs/guide/scene-files.md``.

Units: a scene has no unit system; any consistent one works. "length" is the unit of the coordinates,
"stress" that of Young's modulus (force per area in 2D: force per length per unit thickness), "—" a pure
number. Where the core holds a default, the table shows the core's (``tribo.solver_defaults()``), so that
the two cannot disagree.
"""

from __future__ import annotations

import sys
from pathlib import Path

from tribo._tribo import solver_defaults
from tribo.scene_schema import describe_keys

# table.key → (meaning, unit, default). A default of None is shown from the core's (``solver_defaults``).
_BODY = {
    "x": ("The rectangle's extent along x (with `y`; or `mesh`)", "length", "—"),
    "y": ("The rectangle's extent along y (with `x`; or `mesh`)", "length", "—"),
    "mesh": ("A mesh file meshio reads, relative to the scene file; its named line sets are the edge sets "
             "(a rectangle has `bottom`, `right`, `top`, `left`)", "—", "—"),
}
_MATERIAL = {
    "young": ("Young's modulus E (*required*)", "stress", "—"),
    "poisson": ("Poisson's ratio ν (*required*; plane strain)", "—", "—"),
}
_GRID = {
    "grading": ('Where a rectangle is refined: `"auto"` toward where contact can occur, `"none"` (uniform, size '
                "`h`) or `[a, b]`, a segment of the contact side", "—", '`"auto"`'),
    "h": ("The largest cell size", "length", "a quarter of the shorter side"),
    "h_min": ("The cell size at the contact zone (graded meshes)", "length", "h / 16"),
    "growth": ("How fast the cells grow away from the contact zone (graded meshes)", "—", "0.15"),
    "diagonal": ("How each square of a uniform mesh is split", "—", '`"right"`'),
}
MEANINGS: dict[str, tuple[str, str, str | None]] = {
    **{f"body.{k}": v for k, v in _BODY.items()},
    **{f"material.{k}": v for k, v in _MATERIAL.items()},
    "supports.clamped": ("The edge sets held fixed (u = 0); or `[[supports]]` entries with `kind` (`clamp`, "
                         "`roller`, `displacement` with `x`/`y`) and `edge_set`", "—", "— (*required*, one form)"),
    "loads.body_force": ("The body force f per unit area, in global axes", "stress / length", "[0, 0]"),
    "loads.tractions": ("The traction per unit length on each named edge set (Γ_N), in global axes", "stress",
                        "none"),
    "contact.edge_set": ("The straight edge set Γ_C that meets the obstacle (*required* for one body)", "—", "—"),
    "contact.secondary": ("Two bodies: the side that carries the multipliers and the stabilization, "
                          "`body.edge_set`", "—", "—"),
    "contact.primary": ("Two bodies: the other side, `body.edge_set`", "—", "—"),
    "contact.gap": ("Two bodies: the initial gap between the sides, as an obstacle shape", "length",
                    "flat (touching)"),
    "obstacle.shape": ("The rigid obstacle's profile along Γ_C", "—", '`"flat"`'),
    "obstacle.radius": ("The radius R of a circle or parabola (*required* for them)", "length", "—"),
    "obstacle.center": ("The abscissa ξ on Γ_C of a circle's or parabola's lowest point", "length", "0"),
    "obstacle.xi": ("A polyline's abscissae on Γ_C, increasing (*required* for it)", "length", "—"),
    "obstacle.gap": ("A polyline's initial gap at each of its abscissae (*required* for it)", "length", "—"),
    "obstacle.approach": ("δ: how far the obstacle moves toward the body (against the outward normal n)",
                          "length", "0"),
    "obstacle.shift": ("s: how far the obstacle moves along t = (−n₂, n₁), small sliding", "length", "0"),
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
    "history.displacements": ("Paths of prescribed displacement components (`set.x`, `set.y`; `body.set.x` "
                              "for two bodies)", "length", "unchanged"),
    "history.steps": ("Steps from one waypoint to the next (one count, or one per segment)", "—", "10"),
    "history.plot_steps": ("The steps whose tractions the plots show", "—", "first, middle, last"),
    "history.write_every": ("`tribo run` writes the VTU files of every k-th step and the last", "—",
                            "1 up to 200 steps, then the smallest k within 200"),
    "adapt.tol": ("The relative estimated error of the contact tractions at which the loop stops", "—", "0.01"),
    "adapt.max_unknowns": ("The largest level, in displacement unknowns", "—", "200 000"),
    "adapt.theta": ("Dörfler's θ (the share of the indicators marked), or the fraction of the largest",
                    "—", "0.5"),
    "adapt.marking": ("How triangles are marked", "—", '`"dorfler"`'),
    "adapt.bisection": ("How a marked triangle is bisected", "—", '`"all_edges"`'),
    "adapt.max_levels": ("The most levels", "—", "40"),
    "adapt.algebraic": ("A coarse level's fixed point stops at this fraction of the previous level's estimate",
                        "—", "0.1"),
    "adapt.stop_on": ("The estimate `tol` is read against: the bound (safe, pessimistic) or the smaller of it "
                      "and the hierarchical estimate (sharp, not a bound)", "—", '`"bound"`'),
    "adapt.on": ("With `[history]`: the steps whose indicators mark", "—", "every step"),
    "adapt.write_levels": ("`tribo run` also writes every level, solved again (`levels/`, `adapt.pvd`)", "—",
                           "false"),
    "solver.qp_tol": ("The tolerance of each scaled QP (gap, feasibility)", "—", None),
    "solver.qp_max_iter": ("The iteration cap of each QP", "—", None),
    "solver.qp_kkt_solver": ("clarabel's KKT solver", "—", None),
    "solver.qp_working_set": ("Solve each QP on the dofs near the contact zone first (false: all of Γ_C)", "—",
                              None),
    "solver.qp_method": ("The QP method: clarabel, the active-set method, or chosen", "—", None),
    "solver.fp_tol": ("The Coulomb fixed point stops when λ_n changes by less than this, relatively", "—", None),
    "solver.fp_max_iter": ("The iteration cap of the Coulomb fixed point", "—", None),
    "solver.fp_relaxation": ("The relaxation ω ∈ (0, 1] of the fixed point", "—", None),
    "solver.memory_budget": ("The bytes a solve may take (factorization, dense parts, a history's solutions)",
                             "bytes", "what the process may still allocate"),
    "solver.condensation": ("How H is formed", "—", None),
    "solver.keep_every": ("A history keeps the whole solution of every k-th step and of the last", "—", None),
    "estimate.error_bars": ("Also solve the problem enriched everywhere and report the error bars of the forces "
                            "and zone widths", "—", "false"),
    "bodies.name": ("The body's name (*required*)", "—", "—"),
    **{f"bodies.{k}": v for k, v in _BODY.items()},
    **{f"bodies.material.{k}": v for k, v in _MATERIAL.items()},
    "bodies.loads.tractions": ("The traction per unit length on each named edge set of the body", "stress",
                               "none"),
    **{f"bodies.discretization.{k}": v for k, v in _GRID.items()},
    "bodies.supports": ("The body's supports, as `[[supports]]` entries (*required*; `[]`: held by the contact "
                        "alone)", "—", "—"),
}

BEGIN = "<!-- scene-keys: generated by `python -m tribo.scene_keys`; a test checks it -->"
END = "<!-- end scene-keys -->"


def rows() -> list[tuple[str, str, str, str, str, str]]:
    """(table, key, meaning, unit, default, value) for every key the scene reader takes, in its order.

    Raises KeyError for a key without a meaning (a test keeps them in step)."""
    defaults = solver_defaults()
    out = []
    for table, key, value in describe_keys():
        meaning, unit, default = MEANINGS[f"{table}.{key}"]
        shown = default if default is not None else _show(defaults[key])
        out.append((f"[[{table}]]" if table == "bodies" else f"[{table}]", f"`{key}`", meaning, unit, shown, value))
    return out


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


def rewrite(path: Path) -> bool:
    """Replaces the table between the markers of ``path`` with ``markdown_table()``; True if it changed."""
    text = path.read_text(encoding="utf-8")
    start, end = text.index(BEGIN), text.index(END) + len(END)
    new = text[:start] + markdown_table() + text[end:]
    path.write_text(new, encoding="utf-8")
    return new != text


if __name__ == "__main__":
    for name in sys.argv[1:]:
        print(f"{name}: {'rewritten' if rewrite(Path(name)) else 'unchanged'}")
