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

``conventions(problem, solution)`` gives the directions and signs every output is read in (written into
``summary.json``, the CSV files and the plots).
"""

from __future__ import annotations

import warnings

import numpy as np

from tribo.problem import Problem
from tribo.results import Solution

__all__ = [
    "MAX_APPROACH_FRACTION",
    "MIN_CONTACT_DOFS",
    "SceneWarning",
    "check_solution",
    "conventions",
    "format_vector",
    "shift_description",
    "warn_solution",
]

MIN_CONTACT_DOFS = 10
MAX_APPROACH_FRACTION = 0.05


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
    in_contact = int(np.count_nonzero(solution.states != 0))
    if in_contact == 0:
        closest = float(solution.gap.min()) if len(solution.gap) else float("nan")
        reasons.append(
            "nothing touches: no multiplier dof is in contact and the contact force is zero "
            f"(smallest gap after the approach {_g(closest)}; approach {_g(problem.approach)})"
        )
    elif in_contact < MIN_CONTACT_DOFS:
        reasons.append(
            f"the contact zone holds only {in_contact} multiplier dof{'s' if in_contact > 1 else ''} "
            f"(fewer than {MIN_CONTACT_DOFS}): its extent and pressure are barely resolved; refine near the "
            "contact (h_min) or use more multiplier points (multiplier_ratio)"
        )
    extent = body_extent_along_normal(problem)
    if extent > 0 and abs(problem.approach) > MAX_APPROACH_FRACTION * extent:
        reasons.append(
            f"the approach {_g(problem.approach)} is {_g(abs(problem.approach) / extent * 100)} % of the body's "
            f"extent along n ({_g(extent)}), more than {_g(MAX_APPROACH_FRACTION * 100)} %: beyond small "
            "strain (check the units)"
        )
    return reasons


def warn_solution(problem: Problem, solution: Solution, stacklevel: int = 2) -> list[str]:
    """Emits each reason of ``check_solution`` as a ``SceneWarning``; returns them."""
    reasons = check_solution(problem, solution)
    for r in reasons:
        warnings.warn(r, SceneWarning, stacklevel=stacklevel + 1)
    return reasons


def format_vector(v: tuple[float, float] | np.ndarray) -> str:
    """A 2-vector for people: ``(-0.004, -0.01)``."""
    return f"({_g(float(v[0]))}, {_g(float(v[1]))})"


def shift_description(problem: Problem) -> str:
    """Which way the obstacle was shifted, in words: ``s = 0.004 along t = (-1, 0): toward −x``."""
    s, t = problem.shift, problem.contact_tangent
    if s == 0:
        return "no shift"
    d = (s * t[0], s * t[1])
    where = f"by {format_vector(d)}"
    for comp, other, axis in ((d[0], d[1], "x"), (d[1], d[0], "y")):
        if abs(other) <= 1e-12 * abs(comp):
            where = f"toward {'+' if comp > 0 else '−'}{axis}"
    return f"s = {_g(s)} along t = {format_vector(t)}: the obstacle moved {where}"


def conventions(problem: Problem, solution: Solution) -> dict[str, str]:
    """The directions and signs of every output, as sentences keyed by the quantity."""
    n, t = problem.contact_normal, problem.contact_tangent
    axis = "x" if abs(t[0]) >= abs(t[1]) else "y"
    xi_along = "+t" if problem.tangent_sign > 0 else "−t"
    motion = solution.obstacle_motion
    out = {
        "n": f"outward unit normal of the body on Γ_C, n = {format_vector(n)}",
        "t": f"unit tangent t = (−n₂, n₁) = {format_vector(t)}",
        "xi": f"abscissa ξ along Γ_C, increasing with {axis} (along {xi_along})",
        "lambda_n": "λ_n = −σ_n ≥ 0, the contact pressure",
        "lambda_t": "λ_t = −σ_t, along t: the obstacle's friction traction on the body is −λ_t t",
        "tangential_force": "∫ λ_t: the obstacle pulls the body by −tangential_force along t",
        "contact_force": "(Fx, Fy) = −(normal_force n + tangential_force t): the force the obstacle exerts on "
        "the body, global axes",
        "shift": shift_description(problem),
        "obstacle_motion": f"−approach n + shift t = {format_vector(motion)}, global axes",
        "slip": "u_t − s: tangential displacement of the body relative to the obstacle, along t",
        "current_gap": "g − u_n along n: 0 in contact, negative where the body penetrates",
        "states": "separation λ_n = 0; stick |λ_t| below the bound; slip |λ_t| at the bound",
    }
    if problem.primary is not None:
        secondary, primary = problem.contact, problem.primary
        out.update({
            "n": f"outward unit normal of the secondary body on its contact side '{secondary}', n = {format_vector(n)}",
            "lambda_t": f"λ_t = −σ_t, along t: the friction traction of '{primary}' on the secondary side is −λ_t t",
            "tangential_force": f"∫ λ_t: '{primary}' pulls the secondary body by −tangential_force along t",
            "contact_force": f"(Fx, Fy) = −(normal_force n + tangential_force t): the force '{primary}' exerts on the "
            "secondary body (the primary body takes the opposite), global axes",
            "shift": "none: two bodies move through their prescribed displacements",
            "obstacle_motion": "none: two bodies move through their prescribed displacements",
            "slip": "the jump [u]_t = (u¹ − u²∘Π)·t of the two sides, along t (in a history: since the previous step)",
            "current_gap": "g₀ − [u]_n: the gap between the two sides, 0 in contact",
        })
    if solution.friction == "tresca":
        out["states"] += (
            "; Tresca's threshold is given, not μ λ_n, so λ_t may sit at ±threshold where there is no "
            "contact (state separation): that is Tresca's model, not slip"
        )
    return out
