"""Plots of a solution (needs matplotlib: ``pip install tribo[plot]``). Not imported by ``tribo``.

Every function takes ``ax=None`` (a new figure is made) and returns the Axes it drew on.

* ``contact_pressure``: λ_n and −σ_n(u_h) along Γ_C, the zone shaded by contact state;
* ``tangential``: λ_t against ±(its bound: μ λ_n for Coulomb, the Tresca threshold);
* ``von_mises``: the deformed mesh coloured by the von Mises stress (recovered nodal stress by default);
* ``sweep_map``, ``sweep_lines``, ``sweep_figure``: an output of a ``tribo.sweep`` table over its axes.

Abscissa ξ on Γ_C: x on a horizontal Γ_C, y on a vertical one (see the core's conventions). λ_n ≥ 0 is
the contact pressure and, at the discrete solution, λ_n ≈ −σ_n(u_h). The axis labels state which way ξ
increases and the normal n and tangent t the components are taken along, and the tangential plot says
which way the obstacle was shifted. With a Tresca threshold, λ_t may sit at ±threshold where there is no
contact: those dofs are shaded "separation" and the legend says why λ_t is at its bound there.
"""

from __future__ import annotations

import math

from collections.abc import Sequence
from typing import Any

import numpy as np
import numpy.typing as npt

from tribo._tribo import STATE_NAMES
from tribo.checks import (
    abscissa_description,
    actors,
    format_vector,
    obstacle_points,
    one_contact_normal,
    shift_description,
)
from tribo.problem import Problem
from tribo.results import History, Solution, at_points

try:
    import matplotlib.pyplot as plt
    from matplotlib.axes import Axes
    from matplotlib.patches import Patch
    from matplotlib.tri import Triangulation
except ImportError as e:  # pragma: no cover - depends on the environment
    raise ImportError("tribo.plot needs matplotlib: pip install 'tribo[plot]'") from e

__all__ = [
    "contact_pressure", "hertz_pressure", "tangential", "von_mises", "history_loop", "history_tractions",
    "sweep_map", "sweep_lines", "sweep_figure", "STATE_COLORS",
]

STATE_COLORS = {"separation": "#eeeeee", "stick": "#b9d7f0", "slip": "#f6c89f"}


def _axes(ax: Axes | None) -> Axes:
    if ax is None:
        _, ax = plt.subplots(figsize=(7.0, 4.0), layout="constrained")
    return ax


def _state_intervals(problem: Problem, solution: Solution) -> list[tuple[float, float, int]]:
    """(start, end, state) runs along Γ_C: a P0 dof owns its segment of T_H, a P1 dof the half segments
    on either side of its point."""
    xi = problem.multiplier_mesh
    states = solution.states
    if problem.space == "P0":
        bounds = xi
    else:
        states = at_points(states, len(xi))
        mid = 0.5 * (xi[1:] + xi[:-1])
        bounds = np.concatenate([[xi[0]], mid, [xi[-1]]])
    runs: list[tuple[float, float, int]] = []
    for j, s in enumerate(states):
        a, b = float(bounds[j]), float(bounds[j + 1])
        if runs and runs[-1][2] == s:
            runs[-1] = (runs[-1][0], b, int(s))
        else:
            runs.append((a, b, int(s)))
    return runs


def _shade(ax: Axes, problem: Problem, solution: Solution) -> list[Patch]:
    seen = set()
    for a, b, s in _state_intervals(problem, solution):
        ax.axvspan(a, b, color=STATE_COLORS[STATE_NAMES[s]], lw=0, zorder=0)
        seen.add(s)
    labels = dict(enumerate(STATE_NAMES))
    if solution.friction == "tresca":
        labels[0] = r"separation (Tresca: $\lambda_t$ may sit at $\pm$threshold here)"
    return [Patch(color=STATE_COLORS[STATE_NAMES[s]], label=labels[s]) for s in sorted(seen)]


def _xi_label(problem: Problem) -> str:
    """The abscissa's label: which way ξ increases (``tribo.checks.abscissa_description``)."""
    return abscissa_description(problem)


def _zoom(ax: Axes, problem: Problem, solution: Solution) -> None:
    """Limits the ξ axis to the contact zone and as much again on either side (the whole side where nothing
    touches or the zone crosses a closed side's cut)."""
    xi = problem.multiplier_mesh
    runs = [(a, b) for a, b, s in _state_intervals(problem, solution) if s != 0]
    if not runs or (solution.closed and runs[0][0] <= xi[0] and runs[-1][1] >= xi[-1]):
        ax.set_xlim(float(xi[0]), float(xi[-1]))
        return
    a, b = runs[0][0], runs[-1][1]
    w = max(b - a, 1e-12)
    ax.set_xlim(max(float(xi[0]), a - w), min(float(xi[-1]), b + w))


def _first_pair(solution: Solution) -> Solution:
    """The first pair's part of ``solution`` (``Solution.pair``): the plots of Γ_C read the problem's multiplier mesh,
    the first pair's. ``ValueError`` for another pair's part."""
    first = solution.pair(0)
    if first.pairs and first.pairs[0].index != 0:
        raise ValueError(f"the plots of Γ_C show the first contact pair; this is pair {first.pairs[0].name!r}")
    return first


def _multiplier_curve(
    problem: Problem, solution: Solution, values: npt.NDArray[np.float64]
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """The multiplier as a curve: P1 through its dofs, P0 as steps over T_H."""
    xi = problem.multiplier_mesh
    if problem.space == "P1":
        return xi, at_points(values, len(xi))
    return np.repeat(xi, 2)[1:-1], np.repeat(values, 2)


def _edge_steps(solution: Solution, values: npt.NDArray[np.float64]) -> tuple[Any, Any]:
    """A per-edge field as steps over the FE nodes of Γ_C."""
    x = solution.node_abscissae
    return np.repeat(x, 2)[1:-1], np.repeat(values, 2)


def hertz_pressure(problem: Problem, solution: Solution) -> tuple[np.ndarray, np.ndarray] | None:
    """The 2D Hertz pressure of the computed normal force for a circle or parabola (rigid, on an elastic
    half-plane: a² = 4PR/(πE*), E* = E/(1 − ν²) in plane strain and E in plane stress, p = (2P/(πa))
    √(1 − (ξ − c)²/a²)), as (ξ, p) over the contact width; between two bodies, for the combined modulus
    1/E* = Σ 1/E*_i of their materials. In axisymmetry the 3D Hertz pressure of a sphere on a half-space
    (a³ = 3PR/(4E*), p = 3P/(2πa²) √(1 − r²/a²), P the force on the whole turn). None for other gaps, without
    contact, or for a body of several materials."""
    o = problem.obstacle
    p_total = solution.normal_force
    if o.radius is None or o.center is None or not p_total > 0.0:
        return None
    per_body = problem._source if problem.primary is not None else [(None, None, problem.materials)]
    if any(len(body[2]) > 1 for body in per_body):
        return None  # a coated body: Hertz's half-plane is no reference (study 21 has one)
    # Each body's one material (the two bodies' (name, mesh, materials, …) as given to Problem.two_bodies).
    strain = problem.model != "plane_stress"
    e_star = 1.0 / sum((1.0 - (nu**2 if strain else 0.0)) / e for body in per_body for e, nu in body[2])
    if problem.model == "axisymmetric":
        # A sphere: the obstacle's centre on the axis, Γ_C across it (a circle off the axis is a torus).
        n = one_contact_normal(problem)
        xi0 = np.asarray(problem.node_abscissae)
        if o.center != 0.0 or n is None or abs(n[0]) > 1e-9 or abs(xi0.min()) > 1e-9 * np.ptp(xi0):
            return None
        a = (3.0 * p_total * o.radius / (4.0 * e_star)) ** (1.0 / 3.0)
        xi = a * np.linspace(0.0, 1.0, 201)
        shape = np.sqrt(np.clip(1.0 - ((xi - o.center) / a) ** 2, 0.0, None))
        return xi, 3.0 * p_total / (2.0 * math.pi * a * a) * shape
    a = math.sqrt(4.0 * p_total * o.radius / (math.pi * e_star))
    xi = o.center + a * np.linspace(-1.0, 1.0, 201)
    return xi, 2.0 * p_total / (math.pi * a) * np.sqrt(np.clip(1.0 - ((xi - o.center) / a) ** 2, 0.0, None))


def contact_pressure(
    problem: Problem, solution: Solution, ax: Axes | None = None, *, zoom: bool = True, hertz: bool = True
) -> Axes:
    """λ_n (the multiplier) and −σ_n(u_h) (per FE edge) along Γ_C, shaded by contact state; for a circle
    or parabola (``hertz``) also the Hertz pressure of the same force, for comparison (it assumes a
    half-plane and no friction). With several contact pairs, the first pair's (``Solution.pair``)."""
    ax, solution = _axes(ax), _first_pair(solution)
    handles = _shade(ax, problem, solution)
    reference = hertz_pressure(problem, solution) if hertz else None
    if reference is not None:
        model = "half-plane" if problem.primary is None else "two half-planes"
        model = "half-space, a sphere" if problem.model == "axisymmetric" else model
        ax.plot(*reference, color="k", lw=1.0, ls=":", label=f"Hertz, same force ({model})")
    x, y = _edge_steps(solution, -solution.sigma_n)
    ax.plot(x, y, color="0.35", lw=1.0, label=r"$-\sigma_n(u_h)$ (per FE edge)")
    x, y = _multiplier_curve(problem, solution, solution.lambda_n)
    ax.plot(x, y, color="C0", lw=1.8, marker="." if problem.space == "P1" else None, ms=3, label=r"$\lambda_n$")
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel(_xi_label(problem))
    n = one_contact_normal(problem)
    shown = format_vector(n) if n else "each edge's"
    ax.set_ylabel(rf"contact pressure $\lambda_n = -\sigma_n$, n = {shown}")
    ax.set_title(
        rf"Normal contact: $\lambda_n$ and $-\sigma_n(u_h)$, total force {solution.normal_force:.4g}"
        + f"\nforce of {' on '.join(actors(problem))} (Fx, Fy) = {format_vector(solution.contact_force)}",
        fontsize="medium",
    )
    if zoom:
        _zoom(ax, problem, solution)
    lines, _ = ax.get_legend_handles_labels()
    ax.legend(handles=list(lines) + handles, loc="upper right", fontsize="small")
    return ax


def tangential(problem: Problem, solution: Solution, ax: Axes | None = None, *, zoom: bool = True) -> Axes:
    """λ_t against ±its bound (μ λ_n at the fixed point for Coulomb, the threshold for Tresca); the first pair's."""
    ax, solution = _axes(ax), _first_pair(solution)
    handles = _shade(ax, problem, solution)
    bound_label = r"$\pm\mu\,\lambda_n$" if solution.friction == "coulomb" else r"$\pm$ threshold"
    x, g = _multiplier_curve(problem, solution, solution.friction_threshold)
    ax.plot(x, g, color="C3", lw=1.0, ls="--", label=bound_label)
    ax.plot(x, -g, color="C3", lw=1.0, ls="--")
    x, y = _multiplier_curve(problem, solution, solution.lambda_t)
    ax.plot(x, y, color="C0", lw=1.8, marker="." if problem.space == "P1" else None, ms=3, label=r"$\lambda_t$ (along $t$)")
    x, y = _edge_steps(solution, -solution.sigma_t)
    ax.plot(x, y, color="0.35", lw=1.0, label=r"$-\sigma_t(u_h)$ (per FE edge)")
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel(_xi_label(problem))
    n = one_contact_normal(problem)
    shown = format_vector((-n[1], n[0])) if n else "each edge's"
    ax.set_ylabel(rf"$\lambda_t = -\sigma_t$ along t = {shown}")
    mu = f", μ = {solution.mu:g}" if solution.mu is not None else ""
    ax.set_title(
        rf"Friction ({solution.friction}{mu}): $\lambda_t$ against its bound" + "\n"
        rf"$\int\lambda_t$ = {solution.tangential_force:.3g}: {' pulls '.join(actors(problem))} by "
        f"{-solution.tangential_force + 0.0:.3g} along t"
        + ("" if problem.primary is not None else f"\n{shift_description(problem, solution)}"),
        fontsize="small",
    )
    if zoom:
        _zoom(ax, problem, solution)
    lines, _ = ax.get_legend_handles_labels()
    ax.legend(handles=list(lines) + handles, loc="upper right", fontsize="small")
    return ax


def von_mises(
    problem: Problem,
    solution: Solution,
    ax: Axes | None = None,
    *,
    scale: float | None = None,
    window: tuple[float, float, float, float] | None = None,
    edges: bool = True,
    obstacle: bool = False,
    recovered: bool = True,
) -> Axes:
    """The mesh deformed by ``scale`` × u (default: the largest displacement drawn as 5 % of the body's
    size), coloured by the von Mises stress of the recovered nodal stress (``Solution.nodal_von_mises``,
    interpolated; ``recovered=False``: the P1 cell stress per triangle, which jumps from cell to cell).
    ``window`` = (xmin, xmax, ymin, ymax) zooms.
    ``obstacle`` draws the obstacle surface after its approach, g(ξ) = g0(ξ) − δ off Γ_C along n (it is
    where the deformed Γ_C should touch it when ``scale`` is 1); two bodies have no rigid obstacle to draw."""
    ax = _axes(ax)
    mesh = problem.mesh
    p, u = mesh.points, solution.displacement
    xmin, ymin, xmax, ymax = mesh.bounding_box
    size = max(xmax - xmin, ymax - ymin)
    umax = float(np.abs(u).max()) if u.size else 0.0
    if scale is None:
        scale = 0.05 * size / umax if umax > 0 else 1.0
    q = p + scale * u
    tri = Triangulation(q[:, 0], q[:, 1], mesh.triangles)
    art = (
        ax.tripcolor(tri, solution.nodal_von_mises, cmap="viridis", shading="gouraud")
        if recovered
        else ax.tripcolor(tri, facecolors=solution.von_mises, cmap="viridis", shading="flat")
    )
    if edges:
        ax.triplot(tri, color="k", lw=0.15, alpha=0.5)
    if obstacle and problem.primary is None:  # between two bodies, the other body is drawn
        # Each pair's obstacle facing its own nodes (their gap along their contact normal); the first's, given by a
        # gap function, as that function between its nodes.
        facing = obstacle_points(problem, solution)
        pieces = [facing[r.nodes] for r in solution.pairs] or [facing]
        if problem.obstacle.kind not in ("line", "disc", "hole", "profile", "distance"):
            ends = solution.pair(0).node_abscissae
            xi = np.linspace(float(ends[0]), float(ends[-1]), 2001)
            g = np.asarray(problem.obstacle.gap0(xi)) - problem.approach
            pieces[0] = problem.contact_points(xi) + np.outer(g, problem.contact_normal)
        moved = format_vector(solution.obstacle_motion)
        for k, surface in enumerate(pieces):
            label = f"obstacle (moved by {moved})" if k == 0 else None
            ax.plot(surface[:, 0], surface[:, 1], color="C3", lw=1.5, label=label)
        ax.legend(loc="upper right", fontsize="small")
    ax.figure.colorbar(art, ax=ax, label="von Mises stress" + (" (recovered, nodal)" if recovered else " (per cell)"))
    ax.set_aspect("equal")
    if window is not None:
        ax.set_xlim(window[0], window[1])
        ax.set_ylim(window[2], window[3])
    ax.set_title(f"Deformed mesh (displacement × {scale:.3g}), von Mises stress")
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    return ax


def history_loop(history: History, ax: Axes | None = None) -> Axes:
    """Q = ∫λ_t against the obstacle's tangential position s along a history, with ±μP for reference; when
    the obstacle does not move tangentially, against its angle where the history turns it, or where the history
    moves prescribed displacements (two bodies), against the component that travels the most (the one a fretting
    cycle moves back and forth)."""
    ax = _axes(ax)
    k = len(history)
    # With several contact pairs, the first pair's forces (its obstacle is the one the steps move).
    first = next(iter(history.pairs.values())) if len(history.pairs) > 1 else None
    q, p = (first["tangential_force"], first["normal_force"]) if first else (history.tangential_force, history.normal_force)
    s = history.shift[:k]
    label = "obstacle tangential position s (along t)"
    spans = {name: float(np.abs(np.diff(v[:k])).sum()) for name, v in history.displacements.items() if k}
    turn = history.rotation[:k]
    if k and np.ptp(s) == 0.0 and not np.isnan(turn).any() and np.ptp(turn) > 0.0:
        s, label = turn, "obstacle's angle θ (rad, about its rotation's centre)"
    elif k and np.ptp(s) == 0.0 and spans and max(spans.values()) > 0.0:
        label = max(spans, key=spans.__getitem__)
        s = history.displacements[label][:k]
        label = f"prescribed displacement {label}"
    ax.plot(s, q, "o-", ms=3, lw=1.2, label="Q = ∫λ_t")
    mu = history.solutions[0].mu if k else None
    if mu is not None:
        ax.plot(s, mu * p, "k--", lw=0.8, label="±μP")
        ax.plot(s, -mu * p, "k--", lw=0.8)
    ax.set_xlabel(label)
    ax.set_ylabel("tangential force Q (along t)")
    ax.set_title("Tangential force along the loading path")
    ax.grid(alpha=0.3)
    ax.legend()
    return ax


def history_tractions(
    history: History, steps: Sequence[int], ax: Axes | None = None, *, problem: Problem | None = None
) -> Axes:
    """λ_t and ±μλ_n (the Coulomb bounds) along Γ_C at the given steps of a history. Each step is labelled by
    what the history moves (the shift s, the load factor) and its tangential force Q; with ``problem``, the
    abscissa says which way it runs."""
    ax = _axes(ax)
    moved = [(name, values) for name, values in (("s", history.shift), ("load factor", history.load_factor))
             if len(values) and float(np.ptp(values)) > 0]
    lead = next(iter(history.pairs.values())) if len(history.pairs) > 1 else None
    q = lead["tangential_force"] if lead else history.tangential_force
    for i, k in enumerate(steps):
        sol = history.solution(k)
        sol = sol.pair(0) if lead else sol  # several pairs: the first's side
        x = sol.multiplier_abscissae
        said = ", ".join([*(f"{name} = {values[k]:.3g}" for name, values in moved), f"Q = {q[k]:.3g}"])
        (line,) = ax.plot(x, sol.lambda_t, "-", lw=1.4, label=f"λ_t, step {k} ({said})")
        ax.plot(x, sol.friction_threshold, ":", color=line.get_color(), lw=1.0,
                label="±μλ_n" if i == 0 else None)
        ax.plot(x, -sol.friction_threshold, ":", color=line.get_color(), lw=1.0)
    zone = history.contact_zone[list(steps)] if len(steps) else np.empty((0, 2))
    zone = zone[np.isfinite(zone).all(axis=1)]
    first = history.solutions[0].pair(0) if history.solutions else None
    if first is not None and first.closed and len(zone) and float(zone[:, 0].min()) < first.node_abscissae[0]:
        ax.set_xlim(float(first.node_abscissae[0]), float(first.node_abscissae[-1]))  # across a loop's cut: all of it
    elif len(zone):
        a, b = float(zone[:, 0].min()), float(zone[:, 1].max())
        pad = 0.3 * (b - a) if b > a else 1.0
        ax.set_xlim(a - pad, b + pad)
    ax.set_xlabel(abscissa_description(problem) if problem is not None else "abscissa ξ along Γ_C")
    ax.set_ylabel("tangential traction λ_t (along t)")
    ax.set_title("Tangential traction and the Coulomb bounds ±μλ_n")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return ax


def _ticks(values: Sequence[Any]) -> list[str]:
    return [format(v, ".4g") if isinstance(v, float) else str(v) for v in values]


def sweep_map(df: Any, x: str, y: str, value: str, ax: Axes | None = None, *,
              limits: tuple[float, float] | None = None, colorbar: bool = True) -> Axes:
    """A sweep's output ``value`` over two of its axes ``x`` and ``y`` (a ``tribo.sweep`` table, one case
    per cell), as coloured cells labelled with their values; cells of cases that did not converge are
    crossed. Other axes must have one value in ``df`` (select them first). ``limits`` fixes the colour scale
    (several maps on one scale); ``colorbar=False`` leaves the colour bar to the caller."""
    ax = _axes(ax)
    xs, ys = sorted(df[x].unique()), sorted(df[y].unique())
    if len(df) != len(df.drop_duplicates([x, y])):
        raise ValueError(f"several cases share each ({x}, {y}): select one value of the other axes first")
    grid = np.full((len(ys), len(xs)), np.nan)
    failed = []
    for _, row in df.iterrows():
        i, j = ys.index(row[y]), xs.index(row[x])
        grid[i, j] = float(row[value]) if row[value] is not None else np.nan
        if row["status"] != "converged":
            failed.append((j, i))
    vmin, vmax = limits if limits is not None else (None, None)
    image = ax.imshow(grid, origin="lower", aspect="auto", cmap="viridis", vmin=vmin, vmax=vmax)
    if colorbar:
        plt.colorbar(image, ax=ax, label=value)
    if grid.size <= 144:
        low, high = image.get_clim()
        middle = 0.5 * (low + high)  # viridis is dark below the middle of its scale
        for (i, j), v in np.ndenumerate(grid):
            if np.isfinite(v):
                ax.text(j, i, f"{v:.3g}", ha="center", va="center", fontsize=9 if grid.shape[1] <= 8 else 8,
                        color="white" if v < middle else "black")
    for j, i in failed:
        ax.plot(j, i, "rx", ms=14, mew=2)
    ax.set_xticks(range(len(xs)), _ticks(xs))
    ax.set_yticks(range(len(ys)), _ticks(ys))
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    ax.set_title(f"{value} over {x} × {y}" + (" (×: not converged)" if failed else ""))
    return ax


def sweep_lines(df: Any, x: str, value: str, hue: str | None = None, ax: Axes | None = None) -> Axes:
    """A sweep's output ``value`` against its axis ``x``, one line per value of the axis ``hue``; cases
    that did not converge are circled in red."""
    ax = _axes(ax)
    groups = [(None, df)] if hue is None else list(df.groupby(hue, sort=True))
    for name, part in groups:
        part = part.sort_values(x)
        ax.plot(part[x], part[value].astype(float), "o-", ms=4, label=None if hue is None else f"{hue} = {name}")
        bad = part[part["status"] != "converged"]
        if len(bad):
            ax.plot(bad[x], bad[value].astype(float), "o", ms=10, mfc="none", mec="red")
    ax.set_xlabel(x)
    ax.set_ylabel(value)
    ax.set_title(f"{value} against {x}")
    ax.grid(alpha=0.3)
    if hue is not None:
        ax.legend(fontsize=8)
    return ax


def sweep_figure(df: Any, axes: Sequence[str], value: str) -> Any:
    """The chart ``tribo sweep --plot`` draws: lines over one axis; a map over two; for more, one map of the
    first two per combination of the others (at most 12), two to a row on one colour scale with one colour
    bar, so that the maps compare and read at page width."""
    axes = list(axes)
    if len(axes) == 1:
        fig, ax = plt.subplots(figsize=(7.0, 4.5), layout="constrained")
        sweep_lines(df, axes[0], value, ax=ax)
        return fig
    rest = axes[2:]
    panels = [((), df)] if not rest else list(df.groupby(rest, sort=True))
    if len(panels) > 12:
        raise ValueError(f"{len(panels)} combinations of {', '.join(rest)}: more than 12 maps; plot a selection")
    cols = min(2, len(panels))
    rows = -(-len(panels) // cols)
    fig, grid = plt.subplots(rows, cols, figsize=(4.6 * cols + 1.0, 3.4 * rows + 0.4), layout="constrained",
                             squeeze=False)
    values = np.array([float(v) for v in df[value] if v is not None], dtype=float)
    finite = values[np.isfinite(values)]
    limits = (float(finite.min()), float(finite.max())) if len(finite) else None
    for ax, (name, part) in zip(grid.flat, panels):
        sweep_map(part, axes[0], axes[1], value, ax=ax, limits=limits, colorbar=not rest)
        if rest:
            names = name if isinstance(name, tuple) else (name,)
            # The axis names without their table (``solver.qp_tol`` → ``qp_tol``): the title stays on one line.
            ax.set_title(", ".join(f"{k.split('.')[-1]} = {v}" for k, v in zip(rest, names)), fontsize=10)
    for ax in list(grid.flat)[len(panels):]:
        ax.set_visible(False)
    if rest:
        fig.colorbar(grid[0, 0].images[0], ax=grid, label=value, shrink=0.8)
        fig.suptitle(f"{value} over {axes[0]} × {axes[1]}", fontsize=11)
    return fig
