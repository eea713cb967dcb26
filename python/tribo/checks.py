"""Warnings where a solved scene is probably not what its author meant, and the conventions its results
are stated in.

``check_solution(problem, solution)`` returns the reasons to doubt a scene (and ``warn_solution`` emits
each as a ``SceneWarning``, a ``UserWarning``); ``Scene.solve`` and ``tribo run`` call it, and the command
line prints each as a ``tribo: warning: …`` line. The rules and their thresholds:

* **Nothing touches**: no multiplier dof is in contact, so the contact force is zero. The obstacle's
  approach does not close the initial gap (or the load pulls the body away).
* **Few multiplier dofs in contact**: fewer than ``MIN_CONTACT_DOFS`` = 10. The ends of the contact zone
  are located only to within one multiplier cell, so with k dofs across it its width is uncertain by
  about 2/k of itself; below 10 that is more than 20 %, and the Hertz study shows λ_n errors of tens of
  per cent at such resolutions (``docs/convergence.md``). Refine near the contact (``h_min``) or use
  more multiplier points (``multiplier_ratio``).
* **Large approach**: the approach δ exceeds ``MAX_APPROACH_FRACTION`` = 5 % of the body's extent along n.
  δ/L is at least the mean strain the contact imposes across the body, and tribo's model is small strain:
  its strain measure neglects terms of relative size about the strain itself, so past a few per cent the
  answer carries an error of that order no mesh removes (and a δ comparable to the body is often a unit
  mistake).

* **A contact side that a support also holds**: a node of Γ_C (or of the primary side of two bodies) other
  than its two ends lies on a clamped edge set or under a clamp or prescribed displacement (the core refuses
  a support on an edge of Γ_C; the primary side, and nodes shared without an edge, reach this check). Such a node cannot move, so what the contact does
  there is decided by the support (a clamped Hertz top face carries a contact force that only the supports
  balance): almost always a support named on the wrong side. The ends are exempt: a contact side commonly
  meets a clamped side at a corner.
* **A contact zone cut by the end of Γ_C**: the first or last multiplier dof is in contact at an end of Γ_C
  where the body's boundary goes on straight (the next boundary edge is collinear with the last edge of
  Γ_C). The contact could spread past that end, and the answer depends on where the contact side was cut;
  at a corner of the body (a block on a foundation) the zone may end there, and nothing is said.
* **ν close to ½** in plane strain or axisymmetry with P1 displacements: ``poisson`` ≥ ``MAX_POISSON`` = 0.49. P1 triangles lock as ν → ½ (λ/μ = 2ν/(1 − 2ν)
  is 49 there): on Hertz (33k unknowns, the Python guide's measurement, which a test recomputes), λ_n is 4.0 %
  off at ν = 0.49 and 17 % at 0.499, against 0.76 % at ν = 0.3, and
  at 0.4999 a punch reports a normal force twice that of ν = 0.3 — far beyond the 3 % the change of E*
  explains. No mesh near the contact repairs it; the mixed formulation (``formulation='mixed'``, which the
  default ``'auto'`` takes there in plane strain and axisymmetry) does, and nothing is said under it.
* **A shift large for small sliding**: the obstacle is not flat and ``|s|`` exceeds ``MAX_SHIFT_FRACTION`` =
  10 % of the contact width. tribo's friction is small sliding: the gap is that of the obstacle where it
  started, so the answer places the contact zone where it was before the shift. The physical zone moves
  with the obstacle by about s; past a tenth of its width, the answer's zone is off by more than that.
  A flat obstacle's gap does not change as it slides, and nothing is said.

``conventions(problem, solution)`` gives the directions and signs every output is read in (written into
``summary.json``, the CSV files and the plots).
"""

from __future__ import annotations

import math
import warnings
from typing import Any

import numpy as np

from tribo.problem import Problem
from tribo.results import Solution

__all__ = [
    "MAX_APPROACH_FRACTION",
    "MAX_POISSON",
    "MAX_SHIFT_FRACTION",
    "MIN_CONTACT_DOFS",
    "SceneWarning",
    "abscissa_description",
    "actors",
    "check_solution",
    "conventions",
    "format_vector",
    "shift_description",
    "warn_missing_error_bars",
    "warn_solution",
]

MIN_CONTACT_DOFS = 10
MAX_APPROACH_FRACTION = 0.05
MAX_POISSON = 0.49
MAX_SHIFT_FRACTION = 0.1
STRAIGHT = float(np.sqrt(np.finfo(float).eps))


class SceneWarning(UserWarning):
    """A solved scene that is probably not what its author meant (the solve itself is fine)."""


def _g(x: float) -> str:
    """A number for people: three significant digits, no ``-0``."""
    return f"{x + 0.0:.3g}"


def body_extent_along_normal(problem: Problem) -> float:
    """The extent of the body along the normal n of Γ_C: max − min of x · n over its nodes."""
    along = problem.mesh.points @ np.asarray(problem.contact_normal)
    return float(along.max() - along.min())


def check_solution(problem: Problem, solution: Solution) -> list[str]:
    """The reasons to doubt a solved scene, as sentences (empty when there are none)."""
    reasons = []
    # Pair by pair (``Solution.pair``), named where there are several.
    for k, pr in enumerate(solution.pairs or [None]):
        part = solution.pair(k) if pr is not None else solution
        which = f"pair '{pr.name}': " if pr is not None and len(solution.pairs) > 1 else ""
        in_contact = int(np.count_nonzero(part.states != 0))
        if in_contact == 0:
            closest = float(part.gap.min()) if len(part.gap) else float("nan")
            reasons.append(
                f"{which}nothing touches: no multiplier dof is in contact and the contact force is zero "
                f"(smallest gap after the approach {_g(closest)}"
                + (f"; approach {_g(problem.approach)})" if k == 0 else ")")
            )
        elif in_contact < MIN_CONTACT_DOFS:
            reasons.append(
                f"{which}the contact zone holds only {in_contact} multiplier dof{'s' if in_contact > 1 else ''} "
                f"(fewer than {MIN_CONTACT_DOFS}): its extent and pressure are barely resolved; refine near the "
                "contact (h_min) or use more multiplier points (multiplier_ratio)"
            )
    first = solution.pair(0)  # the problem's multiplier mesh and contact nodes are the first pair's
    extent = body_extent_along_normal(problem)
    if extent > 0 and abs(problem.approach) > MAX_APPROACH_FRACTION * extent:
        reasons.append(
            f"the approach {_g(problem.approach)} is {_g(abs(problem.approach) / extent * 100)} % of the body's "
            f"extent along n ({_g(extent)}), more than {_g(MAX_APPROACH_FRACTION * 100)} %: beyond small "
            "strain (check the units)"
        )
    reasons += _held_contact(problem) + _cut_zone(problem, first) + _non_unique_multipliers(problem, first)
    reasons += _faceted_without_curve(problem)
    nu = max([problem.poisson, *(m[1] for m in getattr(problem, "materials", ()))])  # a body of several materials
    if nu >= MAX_POISSON and problem.model != "plane_stress" and getattr(problem, "formulation", "") != "mixed":
        reasons.append(
            f"ν = {nu:.6g} is close to ½: P1 triangles lock "
            f"(λ/μ = {_g(2 * nu / (1 - 2 * nu))}), so the body is too stiff and the contact pressure and force are too large, by more than any "
            "estimate here shows (Hertz at 33k unknowns: 4.0 % at ν = 0.49, 17 % at 0.499); no refinement repairs it"
            + ": use formulation='mixed'"
        )
    r = solution.report
    if r.coulomb_check == "differ":
        other = "Newton" if r.coulomb_method == "fixed_point" else "the fixed point"
        reasons.append(
            f"two answers: {other} converges to another solution of this Coulomb problem, λ_n "
            f"{_g(100 * (r.check_distance or math.nan))} % away (the two agree to {_g(100 * (r.check_allowed or math.nan))} % "
            "where the answer is unique): the discrete problem has several solutions here (μ or ν large, a coarse "
            "contact zone), or λ is not determined to better than that"
        )
    t = np.asarray(problem.contact_tangent)
    shift = float(np.dot(solution.obstacle_motion, t))
    width = solution.contact_width
    if problem.primary is None and problem.obstacle.kind != "flat" and width > 0 and abs(shift) > MAX_SHIFT_FRACTION * width:
        reasons.append(
            f"the shift s = {_g(shift)} is {_g(abs(shift) / width * 100)} % of the contact width ({_g(width)}), more "
            f"than {_g(MAX_SHIFT_FRACTION * 100)} %: tribo's contact is small sliding (the gap is the obstacle's where "
            "it started), so the contact zone is where it was before the shift, not where the moved obstacle puts it"
        )
    return reasons


def _held_nodes(problem: Problem) -> set[int]:
    """The nodes that a clamp holds, or a prescribed displacement that prescribes every component the contact
    normal has (one that prescribes only the tangential component leaves the node free to close the gap)."""
    n = problem.contact_normal

    def holds(support: Any) -> bool:
        x, y = support.value
        return support.kind in ("clamp", "rotation") or (
            support.kind == "displacement" and (x is not None or n[0] == 0) and (y is not None or n[1] == 0)
        )

    sets = list(problem.clamped) + [s.edge_set for s in problem.supports if holds(s)]
    edges = problem.mesh.edge_sets
    return {int(v) for name in sets if name in edges for v in np.asarray(edges[name]).ravel()}


def _held_contact(problem: Problem) -> list[str]:
    """The reasons to doubt a contact side (the secondary one, or the primary one of two bodies) that a
    support also holds inside its ends (none if both are free there)."""
    sides = [problem.contact, *problem.pairs[1:]] + ([problem.primary] if problem.primary is not None else [])
    held_nodes, reasons = _held_nodes(problem), []
    for side in sides:
        edges = np.asarray(problem.mesh.edge_sets[side]).reshape(-1, 2)
        nodes, counts = np.unique(edges, return_counts=True)
        inside = {int(v) for v in nodes[counts >= 2]}  # a chain's two ends belong to one edge each
        held = inside & held_nodes
        if held:
            reasons.append(
                f"the contact side '{side}' is also held by a support at {len(held)} of its {len(nodes)} nodes "
                "(not counting its ends): those nodes cannot move, so the supports, not the contact, decide the "
                "answer there (a support named on the wrong side?)"
            )
    return reasons


def _non_unique_multipliers(problem: Problem, solution: Solution) -> list[str]:
    """The classic method (γ0 = 0) with more multiplier dofs across the contact zone (from the first dof in contact
    to the last) than FE nodes under them: the normal rows of B that those dofs test have at most one column per
    FE node there, so H restricted to them is singular and λ_n need not be unique (the multipliers checkerboard,
    study 1a). One body only (a primary side adds columns to B)."""
    if solution.report.gamma0 != 0.0 or problem.primary is not None:
        return []
    active = np.flatnonzero(np.asarray(solution.states) != 0)
    if len(active) == 0:
        return []
    points, nodes = np.asarray(problem.multiplier_mesh), np.asarray(problem.node_abscissae)
    # The support of the dofs in contact: for P1 the cells beside each point, for P0 the cell itself.
    first, last = int(active.min()), int(active.max())
    lo = points[max(first - 1, 0)] if problem.space == "P1" else points[first]
    hi = points[min(last + 1, len(points) - 1)] if problem.space == "P1" else points[last + 1]
    # FE nodes whose hat function reaches inside (lo, hi).
    left = np.concatenate([[nodes[0]], nodes[:-1]])
    right = np.concatenate([nodes[1:], [nodes[-1]]])
    under = int(np.count_nonzero((left < hi) & (right > lo)))
    count = last - first + 1  # every dof between the first and the last in contact (a checkerboard's zeros too)
    if count <= under:
        return []
    return [
        f"γ0 = 0 (the classic method) with {count} multiplier dofs across the contact zone over {under} FE nodes under "
        "them: H is singular there, so λ_n need not be unique (two QP methods may return two λ_n, and with "
        "friction two displacements) and its oscillation is not the pressure's (the checkerboard of study 1a); use "
        "γ0 > 0 (the default) or a multiplier mesh no finer than the FE edges (multiplier_ratio ≥ 1)"
    ]


def _chain(edges: np.ndarray) -> list[int]:
    """The nodes of a chain of edges in order, from one of its ends (any node of a loop)."""
    around: dict[int, list[int]] = {}
    for a, b in edges.tolist():
        around.setdefault(a, []).append(b)
        around.setdefault(b, []).append(a)
    start = min((n for n, m in around.items() if len(m) == 1), default=int(edges[0][0]))
    nodes, seen = [start], {start}
    while (nxt := [m for m in around[nodes[-1]] if m not in seen]):
        nodes.append(nxt[0])
        seen.add(nxt[0])
    return nodes


def _faceted_without_curve(problem: Problem) -> list[str]:
    """A contact side that looks like the faceted arc of a curve (three or more kinks, none sharper than 30°)
    and whose edge set carries no curve: refinement keeps its chords, and the estimates cannot see them; between
    two bodies the facets' gaps also enter the contact."""
    reasons = []
    for side in [problem.contact, *problem.pairs[1:]] + ([problem.primary] if problem.primary is not None else []):
        if side in problem.mesh.curves:
            continue
        p = np.asarray(problem.mesh.points)[_chain(np.asarray(problem.mesh.edge_sets[side]))]
        d = np.diff(p, axis=0)
        d /= np.hypot(d[:, 0], d[:, 1])[:, None]
        turn = np.degrees(np.arccos(np.clip(np.sum(d[1:] * d[:-1], axis=1), -1.0, 1.0)))
        kinks = turn[turn > 1e-6]
        if len(kinks) < 3 or kinks.max() >= 30.0:
            continue
        pair = (" Between two bodies the facets also stand in the gap: on a conforming interface (a shrink fit) "
                "that is a pressure error of about h/(8δ) relative, δ the interference; give both sides their "
                "curves") if problem.primary is not None else ""
        reasons.append(
            f"the contact side '{side}' bends at {len(kinks)} nodes by up to {_g(float(kinks.max()))}° and its "
            "edge set carries no curve: if it stands for a curved boundary, its chords stand off the curve by up to "
            "h²/8R between nodes, adaptive refinement keeps them (new nodes on the chords), and the estimates cannot "
            f"see that; give the set its curve (Mesh.with_curve) or mesh it finely enough.{pair}"
        )
    return reasons


def _cut_zone(problem: Problem, solution: Solution) -> list[str]:
    """The reason to doubt a contact zone that reaches an end of Γ_C where the body's boundary goes on
    straight (none at a corner, or when the zone stops short of the ends)."""
    states, nodes = solution.states, np.asarray(problem.contact_nodes)
    if len(states) == 0 or len(nodes) < 2 or (states[0] == 0 and states[-1] == 0) or nodes[0] == nodes[-1]:
        return []  # (a closed side has no end)
    tri = np.asarray(problem.mesh.triangles)
    edges = np.sort(np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]]), axis=1)
    unique, counts = np.unique(edges, axis=0, return_counts=True)
    boundary = unique[counts == 1]
    points = np.asarray(problem.mesh.points)
    reasons = []
    for touching, end, inner in ((states[0] != 0, nodes[0], nodes[1]), (states[-1] != 0, nodes[-1], nodes[-2])):
        if not touching:
            continue
        last = points[end] - points[inner]
        for a, b in boundary[(boundary == end).any(axis=1)]:
            other = b if a == end else a
            if other == inner:
                continue
            beyond = points[other] - points[end]
            cross = last[0] * beyond[1] - last[1] * beyond[0]
            # Straight as the core judges a line straight (to √ε of the lengths, `mesh/line.rs`).
            straight = abs(cross) <= STRAIGHT * np.linalg.norm(last) * np.linalg.norm(beyond)
            if np.dot(last, beyond) > 0 and straight:
                xi = float(problem.node_abscissae[0 if end == nodes[0] else -1])
                reasons.append(
                    f"the contact zone reaches the end of the contact side '{problem.contact}' at ξ = {_g(xi)}, where "
                    "the body's boundary goes on straight: the contact could spread past it, and the answer depends "
                    "on where the side was cut (extend the contact edge set)"
                )
    return reasons


def warn_missing_error_bars(solution: Solution, stacklevel: int = 2) -> bool:
    """Emits a ``SceneWarning`` when error bars were asked for and the solution has none (the solve or the
    enriched solve did not converge, the enriched problem did not fit the memory budget, or several contact pairs,
    which the error bars do not take yet: the log says which); returns whether it did."""
    if solution.report.status == "converged" and math.isnan(solution.report.estimate.get("normal_force_error", math.nan)):
        warnings.warn("error bars were asked for, but the enriched solve gave none (it did not converge, did not "
                      "fit the memory budget, or the problem has several contact pairs; the log says which)",
                      SceneWarning, stacklevel=stacklevel + 1)
        return True
    return False


def warn_solution(problem: Problem, solution: Solution, stacklevel: int = 2) -> list[str]:
    """Emits each reason of ``check_solution`` as a ``SceneWarning``; returns them."""
    reasons = check_solution(problem, solution)
    for r in reasons:
        warnings.warn(r, SceneWarning, stacklevel=stacklevel + 1)
    return reasons


def obstacle_points(problem: Problem, solution: Solution) -> np.ndarray:
    """Where the obstacle's surface is, facing each FE node of Γ_C: the node moved by the gap g = g0 − δ
    along its contact normal n, (n_c, 2); each pair's nodes facing its own obstacle."""
    out = []
    for k, nodes in [(r.index, r.nodes) for r in solution.pairs] or [(0, slice(None))]:
        xi = solution.node_abscissae[nodes]
        out.append(problem.contact_points(xi, k) + np.asarray(solution.gap[nodes])[:, None] * problem.contact_normals(xi, k))
    return np.concatenate(out)


def format_vector(v: tuple[float, float] | np.ndarray) -> str:
    """A 2-vector for people: ``(-0.004, -0.01)``."""
    return f"({_g(float(v[0]))}, {_g(float(v[1]))})"


def actors(problem: Problem) -> tuple[str, str]:
    """Who exerts the contact force on whom, in words: ("the obstacle", "the body") against the rigid
    obstacle, ("'upper.bottom'", "the secondary body") between two bodies (the primary side on the side that
    carries the multipliers). Every output that names the contact force reads them from here."""
    if problem.primary is None:
        return "the obstacle", "the body"
    return f"'{problem.primary}'", "the secondary body"


def shift_description(problem: Problem, solution: Solution | None = None) -> str:
    """Which way the obstacle was shifted, in words: ``s = 0.004 along t = (-1, 0): toward −x``. The shift
    is the solution's (a step of a history moves the obstacle by its own), else the problem's."""
    t = problem.contact_tangent
    if solution is None:
        s = problem.shift
    else:
        motion = np.asarray(solution.obstacle_motion)
        s = float(np.dot(motion, t)) + 0.0
        s = 0.0 if abs(s) <= 1e-12 * float(np.abs(motion).max()) else s  # the approach's round-off along t
    if s == 0:
        return "no shift"
    d = (s * t[0], s * t[1])
    where = f"by {format_vector(d)}"
    for comp, other, axis in ((d[0], d[1], "x"), (d[1], d[0], "y")):
        if abs(other) <= 1e-12 * abs(comp):
            where = f"toward {'+' if comp > 0 else '−'}{axis}"
    return f"s = {_g(s)} along t = {format_vector(t)}: the obstacle moved {where}"


def one_contact_normal(problem: Problem) -> tuple[float, float] | None:
    """The contact normal n when it is one along all of Γ_C (a straight side against a gap function, or any side
    against a line), else None (each edge has its own: ``Problem.contact_normals``)."""
    normals = np.asarray(problem.contact_normals(problem.node_abscissae))
    return (float(normals[0][0]), float(normals[0][1])) if bool(np.all(normals == normals[0])) else None


def _is_bent(problem: Problem) -> bool:
    """Whether Γ_C leaves the line through its ends (a chain of edges, not one segment)."""
    p = np.asarray(problem.mesh.points)[np.asarray(problem.contact_nodes)]
    chord = p[-1] - p[0]
    length = float(np.hypot(*chord))
    off = np.abs((p[:, 0] - p[0, 0]) * chord[1] - (p[:, 1] - p[0, 1]) * chord[0]) / max(length, 1e-300)
    return bool(length == 0.0 or off.max() > 1e-8 * length)


def abscissa_description(problem: Problem) -> str:
    """Which way the abscissa ξ of Γ_C runs, in words: ``abscissa ξ along Γ_C, increasing with x (along
    −t)``; every output that plots or lists positions on Γ_C reads it from here."""
    if _is_bent(problem):
        return "arclength ξ along Γ_C, from its end with the smaller x (the smaller y if its ends share x)"
    t = problem.contact_tangent
    axis = "x" if abs(t[0]) >= abs(t[1]) else "y"
    return f"abscissa ξ along Γ_C, increasing with {axis} (along {'+t' if problem.tangent_sign > 0 else '−t'})"


def conventions(problem: Problem, solution: Solution) -> dict[str, str]:
    """The directions and signs of every output, as sentences keyed by the quantity."""
    n, t = problem.contact_normal, problem.contact_tangent
    motion = solution.obstacle_motion
    single = one_contact_normal(problem)
    one = single is not None
    if single is not None:  # the contact normal (the obstacle's where it is given by its geometry)
        n = single
        t = (-n[1], n[0])
    out = {
        "n": f"outward unit normal of the body on Γ_C, n = {format_vector(n)}" if one else
        "the contact normal of each edge of Γ_C (n_x, n_y): the body's outward normal, or the obstacle's (−∇d) "
        f"where the obstacle is given by its geometry; n = {format_vector(n)} on the first edge",
        "t": f"unit tangent t = (−n₂, n₁) = {format_vector(t)}" if one else "unit tangent t = (−n₂, n₁) of each edge",
        "n_x": "the x component of the contact normal n there",
        "n_y": "the y component of the contact normal n there",
        "xi": abscissa_description(problem),
        "lambda_n": "λ_n = −σ_n ≥ 0, the contact pressure",
        "lambda_t": "λ_t = −σ_t, along t: the obstacle's friction traction on the body is −λ_t t",
        "tangential_force": "∫ λ_t: the obstacle pulls the body by −tangential_force along t",
        "contact_force": "(Fx, Fy) = −(normal_force n + tangential_force t): the force the obstacle exerts on "
        "the body, global axes",
        "shift": shift_description(problem, solution),
        "obstacle_motion": f"−approach n + shift t = {format_vector(motion)}, global axes",
        "slip": "u_t − s: tangential displacement of the body relative to the obstacle, along t",
        "current_gap": "g − u_n along n: 0 in contact, negative where the body penetrates",
        "states": "separation λ_n = 0; stick |λ_t| below the bound; slip |λ_t| at the bound",
    }
    if len(problem.pairs) > 1:
        out.update({
            "pair": "the contact pair of the row (its contact edge set); n, t and ξ are the row's own pair's",
            "n": "the contact normal of each row's pair and edge (n_x, n_y): the body's outward normal, or the "
            "obstacle's (−∇d) where it is given by its geometry",
            "t": "unit tangent t = (−n₂, n₁) of each row's pair and edge",
            "xi": "the abscissa along the row's own pair's side (each pair's from its own start)",
        })
    if problem.primary is not None:
        secondary, primary = problem.contact, problem.primary
        # With further pairs the two bodies' texts are the first pair's rows; n, t and ξ stay each row's pair's.
        first = f"the rows of the pair '{secondary}': " if len(problem.pairs) > 1 else ""
        out.update({} if first else {
            "n": f"outward unit normal of the secondary body on its contact side '{secondary}', n = {format_vector(n)}"})
        total = "the sum over the pairs (each pair's in pairs); for the bodies' pair: " if first else ""
        out.update({
            "lambda_t": first + f"λ_t = −σ_t, along t: the friction traction of '{primary}' on the secondary side is "
            "−λ_t t",
            "tangential_force": total + f"∫ λ_t: '{primary}' pulls the secondary body by −tangential_force along t",
            "contact_force": total + f"(Fx, Fy) = −(normal_force n + tangential_force t): the force '{primary}' "
            "exerts on the secondary body (the primary body takes the opposite), global axes",
            "shift": "none: two bodies move through their prescribed displacements",
            "obstacle_motion": "none: two bodies move through their prescribed displacements",
            "slip": first + "the jump [u]_t = (u¹ − u²∘Π)·t of the two sides, along t (in a history: since the "
            "previous step)",
            "current_gap": first + "g₀ − [u]_n: the gap between the two sides, 0 in contact",
        })
    if problem.model == "axisymmetric":
        out["model"] = (
            "axisymmetric: the solid of revolution of the mesh about the y axis (x = r ≥ 0, the axis held at "
            "u_r = 0); tractions are per unit area of the surface; normal_force and tangential_force are ∫ λ over "
            "the surface of revolution (the whole turn); the contact force and the bodies' reactions are resultants "
            "on the whole turn, whose radial components cancel (0); a node's reaction is the force on its ring; "
            "σ_zz of the files is the hoop stress σ_θθ"
        )
    if solution.friction == "tresca":
        out["states"] += (
            "; Tresca's threshold is given, not μ λ_n, so λ_t may sit at ±threshold where there is no "
            "contact (state separation): that is Tresca's model, not slip"
        )
    return out
