"""``Problem``: the compiled problem, whose solves return the typed results of ``tribo.results``.

The compiled ``tribo._tribo.Problem`` validates and assembles the problem and solves it with the GIL
released; its solves hand back plain dicts. This subclass turns them into ``Solution`` and ``History``
and spreads a scalar approach, shift or load factor over the steps of a history (numpy broadcasting).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from typing import Any, Generic, Literal, NoReturn, TypeVar, cast, overload

import numpy as np
import numpy.typing as npt

from tribo import _tribo
from tribo._tribo import format_number
from tribo.inputs import Body, Pair, _compiled_arguments, _contact_error, _settings_error, history_steps
from tribo.results import Adaptive, AdaptiveHistory, History, Level, Solution

__all__ = ["Body", "Pair", "Problem", "history_steps"]

_Law = Literal["frictionless", "tresca", "coulomb"]
ProgressCallback = Callable[[int, float, int, float], object]
PhaseCallback = Callable[[Literal["condensation"], float], object]
StepCallback = Callable[[int, int, str, float], object]


def _adapt_args(tol: float | None, max_unknowns: int | None, theta: float | None, marking: str | None,
                bisection: str | None, stop_on: str | None, max_levels: int | None,
                algebraic: float | None) -> tuple[Any, ...]:
    """The adaptive keywords as the compiled module takes them."""
    return (tol, max_unknowns, theta, (marking, bisection, stop_on), max_levels, algebraic)


def check_adapt(
    *,
    tol: float | None = None,
    max_unknowns: int | None = None,
    theta: float | None = None,
    marking: str | None = None,
    bisection: str | None = None,
    max_levels: int | None = None,
    algebraic: float | None = None,
    stop_on: str | None = None,
) -> None:
    """Checks the keywords of ``Problem.solve_adaptive`` as the core does when its loop starts, without a
    problem (a scene's ``[adapt]`` is checked so when it is read): ``SettingsError`` naming the first bad one.
    ``max_unknowns`` is checked against the first mesh when the loop starts."""
    _tribo.check_adapt(_adapt_args(tol, max_unknowns, theta, marking, bisection, stop_on, max_levels, algebraic))


_T = TypeVar("_T")


class _Attribute(Generic[_T]):
    """A read-only attribute of a problem, built once with it by the core (``_tribo.Problem._data``); a list or a
    dict is read as a copy, so that no reader changes it for the others (the arrays are read-only)."""

    def __init__(self, doc: str) -> None:
        self.__doc__ = doc

    def __set_name__(self, owner: type, name: str) -> None:
        self.name = name

    @overload
    def __get__(self, problem: None, owner: type) -> _Attribute[_T]: ...
    @overload
    def __get__(self, problem: _tribo.Problem, owner: type) -> _T: ...
    def __get__(self, problem: _tribo.Problem | None, owner: type) -> _Attribute[_T] | _T:
        if problem is None:
            return self
        value = problem._data[self.name]
        return cast(_T, type(value)(value) if isinstance(value, (list, dict)) else value)

    def __set__(self, problem: _tribo.Problem, value: NoReturn) -> None:
        raise AttributeError(f"Problem.{self.name} is read-only: build another problem")


def _body_mesh(mesh: _tribo.Mesh, name: str, spans: Sequence[int]) -> _tribo.Mesh:
    """Body ``name`` of a joined two-body mesh alone: nodes ``spans[0]:spans[1]``, triangles
    ``spans[2]:spans[3]``, its edge sets ('name.set') under their own names; the inverse of the join that
    ``Problem.two_bodies`` makes (the vertex order, and with it the refinement state, is kept)."""
    n0, n1, t0, t1 = (int(v) for v in spans)
    prefix = f"{name}."
    sets = {k[len(prefix):]: np.asarray(v) - n0 for k, v in mesh.edge_sets.items() if k.startswith(prefix)}
    return _tribo.Mesh(mesh.points[n0:n1], np.asarray(mesh.triangles)[t0:t1] - n0, sets)


class Problem(_tribo.Problem):
    """A contact problem, validated and assembled once (independent of γ0 and friction). It keeps the
    factorization of its last solve, reused by the next solve with the same γ0.

    ``Problem(mesh, *, young, poisson, contact, clamped=None, supports=None, obstacle=None, approach=None,
    shift=None, rotation=None, tractions=None, pressures=None, body_force=None, multiplier_ratio=None,
    multiplier_size=None, multiplier_points=None, space=None, model=None, formulation=None, materials=None,
    regions=None, pairs=None)``: the body (a Mesh, Young's modulus and Poisson's ratio, or for a body of several materials, a coating on a substrate say, ``materials``
    [(E, ν), …] and ``regions``, the index of each triangle's material, from ``tribo.io.read_triangle_groups``
    or the triangles' centroids; model 'plane_strain', the default, 'plane_stress': a thin plate, forces per unit
    thickness, or 'axisymmetric': the solid of revolution of the mesh about the y axis, x = r ≥ 0, the axis held at
    u_r = 0, tractions per unit area and forces on the whole turn; formulation 'displacement': P1 displacements,
    which lock as ν → ½, 'mixed': P1 displacements and pressures, free of locking, for rubber and other nearly
    incompressible bodies, every model, or 'auto', the default: mixed from ν = 0.49 in plane strain and
    axisymmetry, ``problem.formulation`` saying which), its
    supports (edge sets clamped, or a list of Support), its loads (tractions: a dict edge set -> (tx, ty);
    pressures: a dict edge set -> p, the traction −p n along each edge's outward normal, so a bore or a curved side
    can be pressed; body_force (fx, fy)), Γ_C (the edge set `contact`) and the obstacle with its motion (an
    Obstacle or a callable gap(xi), the approach δ and the tangential shift s, and for an obstacle given by its
    geometry ``rotation=((cx, cy), angle)``: turned by angle radians counterclockwise about (cx, cy), its surface
    sliding with the turn; a history may turn it step by step), and the multiplier mesh T_H (at most one of
    multiplier_ratio H/h, multiplier_size H and multiplier_points; space 'P0' or 'P1'). ``pairs``: further contact pairs, each another edge set of the body against its own rigid obstacle, with its own approach, shift and Coulomb μ (``tribo.Pair``, or a tuple of its fields), T_H as ``contact``'s (of its ratio or size); ``problem.pairs`` names them all, ``Solution.pairs`` gives each its part.
    """

    _arguments: dict[str, Any]
    _source: Any

    mesh = _Attribute[_tribo.Mesh]("The mesh (for two bodies: both, joined; ``bodies`` says where each is).")
    obstacle = _Attribute[_tribo.Obstacle]("The obstacle's shape (flat where none was given).")
    approach = _Attribute[float]("The normal approach δ of the obstacle.")
    shift = _Attribute[float]("The tangential shift s of the obstacle.")
    young = _Attribute[float]("Young's modulus E (under Γ_C's first edge for several materials; the secondary "
                              "body's for two).")
    poisson = _Attribute[float]("Poisson's ratio ν (as ``young``).")
    materials = _Attribute[list[tuple[float, float]]]("Every material (E, ν), by region.")
    regions = _Attribute[npt.NDArray[np.int64]]("The region of each triangle, (n_triangles,) int64.")
    contact = _Attribute[str]("The contact edge set Γ_C (the secondary side for two bodies).")
    clamped = _Attribute[list[str]]("The clamped edge sets.")
    supports = _Attribute[list[_tribo.Support]]("The supports given besides ``clamped``.")
    space = _Attribute[Literal["P0", "P1"]]("The multiplier space, 'P0' or 'P1'.")
    n_free = _Attribute[int]("The number of unknowns: the free displacement dofs, and in the mixed formulation one "
                             "pressure per node.")
    n_multipliers = _Attribute[int]("The number of multiplier dofs q (per component), of every pair.")
    gamma0_bound = _Attribute[float]("The admissible bound on γ0 (K − G stays positive definite, or quasi-definite "
                                     "when mixed, below it).")
    gamma0_bound_element = _Attribute[int]("The triangle that sets ``gamma0_bound``.")
    contact_normal = _Attribute[tuple[float, float]]("The outward unit normal n on Γ_C (its first edge's on a bent "
                                                     "side).")
    contact_tangent = _Attribute[tuple[float, float]]("The tangent t = (−n₂, n₁): tangential quantities are "
                                                      "components along t.")
    tangent_sign = _Attribute[float]("d · t = ±1: +1 where the abscissa ξ increases along t.")
    contact_nodes = _Attribute[npt.NDArray[np.int64]]("The FE nodes of Γ_C by increasing abscissa, (n_c,) int64 (the "
                                                      "first pair's, as the fields below).")
    node_abscissae = _Attribute[npt.NDArray[np.float64]]("The abscissae of ``contact_nodes``.")
    multiplier_mesh = _Attribute[npt.NDArray[np.float64]]("The points x_0 < … < x_N of the multiplier mesh T_H "
                                                          "(abscissae).")
    multiplier_abscissae = _Attribute[npt.NDArray[np.float64]]("The abscissae of the multiplier dofs (midpoints for "
                                                               "P0, points for P1).")
    setup_timings = _Attribute[dict[str, float]]("The set-up wall times in seconds: {'assembly', "
                                                 "'contact_matrices'}.")
    primary = _Attribute[str | None]("The primary contact set of two bodies ('body.set'), or None against a rigid "
                                     "obstacle.")
    bodies = _Attribute[list[tuple[str, tuple[int, int, int, int], int]]](
        "The bodies: (name, (first node, end, first triangle, end) in ``mesh``, unknowns); one, 'body', for one body.")
    prescribed = _Attribute[list[tuple[str, float]]]("The prescribed displacement components a history may move, "
                                                     "('set.x' or 'set.y', value), in order.")
    pairs = _Attribute[list[str]]("The contact pairs by their edge sets, ``contact`` first (the order of "
                                  "``Solution.pairs``).")

    def __new__(cls, mesh: _tribo.Mesh | Sequence[tuple[Any, ...]], **arguments: Any) -> Problem:
        problem = super().__new__(cls, mesh, **_compiled_arguments(arguments))
        # The arguments (and the bodies, for two), so that an adaptive solve can build a level's problem.
        problem._arguments = arguments
        problem._source = mesh
        return problem

    @property
    def model(self) -> str:
        """``'plane_strain'``, ``'plane_stress'`` or ``'axisymmetric'``."""
        return str(self._arguments.get("model") or _tribo.solver_defaults()["model"]).lower()

    @property
    def formulation(self) -> str:
        """The formulation solved, ``'displacement'`` or ``'mixed'`` (one pressure per node besides the displacements,
        ``tribo::fem::mixed``), as asked or as ``'auto'`` chose: mixed when pressures are among the unknowns."""
        return "mixed" if self.n_free > sum(int(b[2]) for b in self.bodies) else "displacement"

    @classmethod
    def two_bodies(
        cls,
        first: Body,
        second: Body,
        *,
        secondary: str,
        primary: str,
        gap: _tribo.Obstacle | Callable[[float], float] | None = None,
        body_force: Any = None,
        multiplier_ratio: float | None = None,
        multiplier_size: float | None = None,
        multiplier_points: npt.ArrayLike | None = None,
        space: Literal["P0", "P1", "p0", "p1"] | None = None,
        model: Literal["plane_strain", "plane_stress", "axisymmetric"] | None = None,
        formulation: Literal["auto", "displacement", "mixed"] | None = None,
        pairs: Sequence[Pair | tuple[Any, ...]] | None = None,
    ) -> Problem:
        """Two elastic bodies in contact along one line, straight or bent: ``secondary`` ('body.edge_set') carries
        the multipliers T_H and the stabilization, ``primary`` meets it with the opposite normal; ``gap``
        is the initial gap between them as an obstacle shape (flat: touching; a parabola for two curved
        profiles). Either side may be bent (a shrink fit's arcs): the two then face each other, and the gap is
        their geometry's (their curves', where both edge sets carry one) plus ``gap``. Each body has its own material (or materials: a coated body), supports and tractions (``Body``);
        ``model`` is both bodies' ('plane_strain', the default, 'plane_stress': two thin plates, or 'axisymmetric': two
        solids of revolution about the y axis); ``formulation`` both bodies' (as ``Problem``'s: 'auto' is mixed when
        either body reaches ν = 0.49 in plane strain or axisymmetry); a motion its supports
        leave free is held by the contact alone (a punch pushed by a load); ``body_force`` acts on both. The problem solves, solves histories and plots
        as a one-body problem; ``bodies`` says where each body lies in ``mesh`` (the two joined, edge sets
        renamed 'body.set'); adaptive refinement bisects both bodies. ``pairs``: further contact pairs, each an edge
        set of either body ('body.set') against its own rigid obstacle (``tribo.Pair``): a block pressed by a second
        body onto a foundation."""
        if not (isinstance(first, Body) and isinstance(second, Body)):
            raise TypeError(f"two_bodies takes two tribo.Body, got {type(first).__name__} and {type(second).__name__}")
        return cls(
            [first._compiled(), second._compiled()],
            contact=secondary, primary=primary, obstacle=gap, body_force=body_force,
            multiplier_ratio=multiplier_ratio, multiplier_size=multiplier_size, multiplier_points=multiplier_points,
            space=space, model=model, formulation=formulation, pairs=pairs,
        )

    def __repr__(self) -> str:
        return (
            f"Problem(n_free={self.n_free}, n_multipliers={self.n_multipliers}, space='{self.space}', "
            f"contact='{self.contact}', gamma0_bound={format_number(self.gamma0_bound)})"
        )

    def solve(
        self,
        *,
        friction: _Law | None = None,
        mu: float | None = None,
        threshold: float | npt.ArrayLike | None = None,
        gamma0: float | None = None,
        gamma0_fraction: float | None = None,
        check_gamma0: bool = True,
        error_bars: bool = False,
        progress: ProgressCallback | None = None,
        on_phase: PhaseCallback | None = None,
        **settings: Any,
    ) -> Solution:
        """Solves the problem; returns a Solution whose ``report.status`` says how the solve ended.

        The friction law is ``friction`` ('frictionless', 'tresca' or 'coulomb'), or, when None,
        inferred: ``mu`` given → Coulomb (mu = 0 is frictionless), ``threshold`` given → Tresca, neither →
        frictionless. γ0 is ``gamma0``, or ``gamma0_fraction`` × the admissible bound, or the core's
        default; ``check_gamma0=False`` takes an explicit ``gamma0`` even at or above the admissible bound
        (for studies of what happens there; the factorization may then fail with SolverError). Every
        other keyword is a solver setting by its name in ``solver_defaults()`` (qp_tol, qp_max_iter,
        qp_kkt_solver, qp_working_set, qp_method, fp_tol, fp_max_iter, fp_relaxation, coulomb, coulomb_check,
        memory_budget, condensation, keep_every); unset ones take the core's defaults. ``coulomb`` chooses the
        Coulomb method: 'fixed_point' (the default and the reference), 'newton' (the semismooth Newton method on
        Γ_C: the friction bound follows λ_n inside each step) or 'auto' (the fixed point where H is not formed,
        else Newton, and the fixed point where Newton does not converge); ``report.coulomb_method`` says which
        answered. ``coulomb_check=True`` solves a converged Coulomb problem again by the other method and
        compares: ``report.coulomb_check`` says 'differ' where the discrete problem has two solutions.

        ``error_bars=True`` also solves the problem enriched (every triangle bisected and those within half a
        contact width of the contact zone again, T_H halved with them: 8-9 times the unknowns, twice where the contact
        reaches an end of Γ_C) and adds to ``report.estimate`` the hierarchical traction
        estimate and the error bars of the normal and tangential forces and of the widths of the contact and
        stick zones (``normal_force_error``, ``tangential_force_error``, ``contact_width_error``,
        ``stick_width_error``: estimated absolute errors, 1.5 times the change under the enrichment; sharp, but
        not guaranteed bounds; the crate documentation of ``tribo::adapt::enriched`` derives them and
        ``docs/error_bars.md`` measures them). They stay NaN without ``error_bars`` and when the solve or the
        enriched solve did not converge.

        ``progress``, if given, is called as progress(iteration, change, qp_iterations, qp_seconds) after
        every QP (and, with ``coulomb='newton'``, after every Newton step: its number, the relative merit
        before it, the size of its linear system and its seconds); returning False (any false value but None: 0, ``numpy.False_``) stops the solve (status
        'interrupted', with the last iterate), raising
        stops it and propagates. ``on_phase``, if given, is called as on_phase(phase, seconds) when a
        phase before the QPs ends: 'condensation' (A = K − G factorized or reused, c and possibly all of H
        formed; ``seconds`` is its wall time so far); False or an exception stops the solve the same way,
        before any QP. Ctrl-C is honoured after the condensation and between QPs.
        """
        return Solution.from_dict(self._solve({
            "friction": friction, "mu": mu, "threshold": threshold, "gamma0": gamma0,
            "gamma0_fraction": gamma0_fraction, "check_gamma0": check_gamma0, "error_bars": error_bars,
            "progress": progress, "on_phase": on_phase, **settings,
        }))

    def solve_history(
        self,
        approach: float | npt.ArrayLike | None = None,
        shift: float | npt.ArrayLike | None = None,
        load_factor: float | npt.ArrayLike | None = None,
        *,
        displacements: Mapping[str, Any] | None = None,
        rotation: float | npt.ArrayLike | None = None,
        friction: _Law | None = None,
        mu: float | None = None,
        threshold: float | npt.ArrayLike | None = None,
        gamma0: float | None = None,
        gamma0_fraction: float | None = None,
        check_gamma0: bool = True,
        progress: StepCallback | None = None,
        **settings: Any,
    ) -> History:
        """Solves a quasi-static loading history from rest on one factorization; returns a History.

        Step k moves the obstacle to approach ``approach[k]`` and tangential position ``shift[k]``
        (totals, not increments; a scalar is the same at every step; default the problem's) under
        ``load_factor[k]`` × the body force and tractions (default 1), and the prescribed displacements to
        ``displacements`` (a dict from the components of ``prescribed``, 'set.x' or 'set.y', to a value or
        one per step; a component left out keeps its value): two bodies move only this way. ``rotation`` turns an
        obstacle that has a ``rotation`` to that angle (radians, the total about its centre; default its own) at each
        step (the contact frame stays the problem's: small rotations). Coulomb's law acts on the slip increment relative to the
        obstacle, so the answer depends on the path; a history of one step is the static ``solve``. The
        friction, γ0 and settings keywords are those of ``solve``. ``progress``, if given, is called as
        progress(step, steps, status, seconds) after every step; returning False ends the history there
        (status 'interrupted', the steps done kept), raising ends it and propagates with the steps done as
        the exception's ``history`` (a History, status 'interrupted'). Ctrl-C is honoured between steps (the
        KeyboardInterrupt carries ``history`` too). A step that does not converge ends the history with its status; ``History.failed``
        holds its last iterate. ``keep_every=k`` keeps the whole solution of steps 0, k, 2k, … and of the last
        converged step only (the per-step arrays cover every step): a long history then fits the memory
        budget, which the solutions kept must fit before any step runs.
        """
        steps = self._steps(approach, shift, load_factor, displacements, rotation)
        try:
            return self._history(steps, self._solve_history(steps, {
                "friction": friction, "mu": mu, "threshold": threshold, "gamma0": gamma0,
                "gamma0_fraction": gamma0_fraction, "check_gamma0": check_gamma0, "progress": progress, **settings,
            }))
        except BaseException as e:
            # An exception from the callback (or Ctrl-C) keeps the steps done, as ``e.history``.
            partial = getattr(e, "_partial_history", None)
            if partial is not None:
                e.history = self._history(steps, partial)  # type: ignore[attr-defined]
            raise

    def solve_adaptive(
        self,
        *,
        tol: float | None = None,
        max_unknowns: int | None = None,
        theta: float | None = None,
        marking: Literal["dorfler", "maximum"] | None = None,
        bisection: Literal["all_edges", "refinement_edge"] | None = None,
        max_levels: int | None = None,
        algebraic: float | None = None,
        stop_on: Literal["bound", "hierarchical", "enriched"] | None = None,
        friction: _Law | None = None,
        mu: float | None = None,
        threshold: float | npt.ArrayLike | None = None,
        gamma0: float | None = None,
        gamma0_fraction: float | None = None,
        check_gamma0: bool = True,
        progress: Callable[[int, float, float], object] | None = None,
        **settings: Any,
    ) -> Adaptive:
        """Solves adaptively from this problem's mesh: solve, estimate, mark, refine by newest-vertex
        bisection, until the relative estimated error is at most ``tol`` (default 0.01) or the next level
        would exceed ``max_unknowns`` (default 200 000) unknowns (the pressures of the mixed formulation counted);
        returns an Adaptive with the
        last ``solution``, the ``problem`` on the last mesh, every level and the reason it stopped.

        The relative estimate is that of the contact tractions (λ in L²(Γ_C)) when something touches, of
        the energy while nothing does. By default (``stop_on='hierarchical'``) it is the smaller of the residual
        bound and the hierarchical estimate 1.5‖λ_H − λ_f‖ / ‖λ_f‖ (λ_f the answer with the whole mesh bisected
        and the strip along the contact zone again, ``report.estimate["traction_hierarchical_relative"]``; where
        the contact zone reaches an end of Γ_C, its reduction there is measured by two more enrichments): 1.38–1.58
        times the true error on every level of nine cases of docs/tol_table.md, 1.82–1.88 on the block, whose
        traction is singular at its corners (its bound 1.82–1.91), not a guaranteed bound, computed on the levels
        near ``tol`` with at least 10 multiplier dofs in contact at the cost of a solve of 8–9 times their
        unknowns. The level right after an estimated one reads the calibrated bound instead, the bound times the
        ratio of the two measured there (``report.estimate["traction_calibrated_relative"]``), and may stop on it
        without an enriched solve of its own. The answer's true error then ends in [tol/3, tol] at about the time of
        the cheapest adequate level (docs/tol_table.md counts the runs). With ``'enriched'`` the loop also hands back
        the answer of a level's enriched problem where its own estimate (a third of the level's away from the ends
        of Γ_C in contact) meets ``tol`` and the level's own does not (P1 multipliers, a mesh without curves; a
        history's enriched history alike; ``progress``'s return value is not read for that last level): a more
        accurate answer of 8–9 times the level's unknowns, often more than asked, sooner. With
        ``stop_on='bound'`` it is the residual bound alone, above
        the true error but pessimistically (on Hertz by 3 on coarse meshes and up to 24 on fine ones,
        docs/STUDIES.md, study 6): the answer is usually many times more accurate than ``tol``, at many times
        the unknowns. Marking is Dörfler's with ``theta`` (default 0.5), or the maximum
        strategy (``marking='maximum'``); a marked triangle is bisected on all three edges into four
        (``bisection='all_edges'``, the default: fewer levels) or on its refinement edge only
        (``'refinement_edge'``); ``max_levels`` (default 40) bounds the levels. A level's Coulomb
        fixed point stops once its change is ``algebraic`` (default 0.1) times the previous level's relative
        estimate (never below ``fp_tol``); the last level is solved again to ``fp_tol`` (an enriched answer handed
        back was solved to it). T_H is refined
        where the FE edges under it are, keeping the ratio H/h of this problem, except where the body is
        surely apart from the obstacle and no Tresca threshold acts (a threshold per dof is carried to each
        level as the W_H function it defines). The friction, γ0 and settings keywords are those of ``solve``;
        ``progress``, if given, is called as progress(unknowns, relative, seconds) after every level, and
        returning False stops the loop there (stop 'interrupted'). Defaults come from the core.
        """
        options: dict[str, Any] = {"friction": friction, "mu": mu, "threshold": threshold, "gamma0": gamma0,
                                   "gamma0_fraction": gamma0_fraction, "check_gamma0": check_gamma0, "progress": progress, **settings}
        adapt = _adapt_args(tol, max_unknowns, theta, marking, bisection, stop_on, max_levels, algebraic)
        solution, problem, levels, stop, meshes = self._adapt(options, adapt)
        return Adaptive(solution=Solution.from_dict(solution), problem=problem, levels=levels, stop=stop, meshes=meshes)  # type: ignore[arg-type]

    def solve_history_adaptive(
        self,
        approach: float | npt.ArrayLike | None = None,
        shift: float | npt.ArrayLike | None = None,
        load_factor: float | npt.ArrayLike | None = None,
        *,
        displacements: Mapping[str, Any] | None = None,
        rotation: float | npt.ArrayLike | None = None,
        on: Sequence[int] | None = None,
        tol: float | None = None,
        max_unknowns: int | None = None,
        theta: float | None = None,
        marking: Literal["dorfler", "maximum"] | None = None,
        bisection: Literal["all_edges", "refinement_edge"] | None = None,
        max_levels: int | None = None,
        algebraic: float | None = None,
        stop_on: Literal["bound", "hierarchical", "enriched"] | None = None,
        friction: _Law | None = None,
        mu: float | None = None,
        threshold: float | npt.ArrayLike | None = None,
        gamma0: float | None = None,
        gamma0_fraction: float | None = None,
        check_gamma0: bool = True,
        progress: Callable[[int, float, float], object] | None = None,
        **settings: Any,
    ) -> AdaptiveHistory:
        """Solves a loading history adaptively: every level solves the whole history (as
        ``solve_history``, same steps and keywords) and is refined where the largest η_K and ζ_K over the
        steps ``on`` (0-based indices; default all) are; the loop stops when the largest relative estimate
        over those steps is at most ``tol``. Returns an AdaptiveHistory with the ``history`` on the last
        mesh, its ``problem``, every level (each with the estimate of its worst step) and the stop reason.
        The adaptive keywords are those of ``solve_adaptive``; unless ``stop_on='bound'`` the whole history
        is solved again on the enriched mesh where the loop computes the estimate, and every step carries its
        own (``Problem::estimate_history_hierarchical`` in the crate), or on the level after, its calibrated bound. Levels start their steps from rest, as a
        history does, not from the previous level.
        """
        steps = self._steps(approach, shift, load_factor, displacements, rotation)
        options: dict[str, Any] = {"friction": friction, "mu": mu, "threshold": threshold, "gamma0": gamma0,
                                   "gamma0_fraction": gamma0_fraction, "check_gamma0": check_gamma0, "progress": progress, **settings}
        adapt = _adapt_args(tol, max_unknowns, theta, marking, bisection, stop_on, max_levels, algebraic)
        history, problem, levels, stop, meshes = self._adapt(options, adapt, steps, list(on or []))
        return AdaptiveHistory(
            history=self._history(steps, history), problem=problem, levels=levels, stop=stop, meshes=meshes  # type: ignore[arg-type]
        )

    def _steps(self, approach: Any, shift: Any, load_factor: Any, displacements: Mapping[str, Any] | None,
               rotation: Any = None) -> npt.NDArray[np.float64]:
        """The rows of a history: the problem's approach and shift where none is given."""
        approach = self.approach if approach is None else approach
        shift = self.shift if shift is None else shift
        return history_steps(approach, shift, load_factor, displacements, self.prescribed, rotation)

    def _history(self, steps: npt.NDArray[np.float64], data: dict[str, Any]) -> History:
        """The History of the compiled dict, with the prescribed displacements its rows moved."""
        names = [name for name, _ in self.prescribed] if steps.shape[1] > 4 else []
        columns = {n: np.array(steps[:, 4 + i]) for i, n in enumerate(names)}
        for c in columns.values():
            c.flags.writeable = False  # read-only, as every array of a result
        return History.from_dict({**data, "displacements": columns})

    def _adapt(
        self, options: dict[str, Any], adapt: tuple[Any, ...], *history: Any
    ) -> tuple[Any, Problem, list[Level], str, list[tuple[_tribo.Mesh, npt.NDArray[np.float64], Any, Any]]]:
        """The compiled adaptive loop: its answer, the Problem of the last mesh, the levels as Level
        records, the stop, and each level's mesh with its T_H points and its bodies' spans."""
        answer, levels, stop = self._solve_adaptive(options, adapt, *history)
        records = [
            Level(unknowns=u, multipliers=q, triangles=t, estimate=dict(e), relative=r, seconds=s, status=st,  # type: ignore[arg-type]
                  enriched=f)
            for ((u, q, t, e, r, s), st, _, f) in levels
        ]
        meshes = [(mesh, xi, spans, regions) for (_, _, (spans, mesh, xi, regions), _) in levels]
        return answer, self.on_mesh(*meshes[-1]), records, stop, meshes

    def on_mesh(
        self, mesh: _tribo.Mesh, multiplier_points: npt.ArrayLike, bodies: Sequence[Sequence[int]] | None = None,
        regions: npt.ArrayLike | None = None,
    ) -> Problem:
        """This problem (materials, supports, loads, obstacle or contact pair, multiplier space) on another
        mesh with the multiplier mesh T_H through ``multiplier_points`` (abscissae on Γ_C): how an adaptive
        solve hands back the problem of a level. For two bodies ``mesh`` is the two joined, as in
        ``problem.mesh``, and ``bodies`` gives each body's first node, end, first triangle, end in it (as
        ``problem.bodies``; default this problem's). A body of several materials needs the ``regions`` of
        the new mesh's triangles, indices into ``problem.materials`` (for two bodies the first body's materials,
        then the second's; an adaptive level's are its own)."""
        ratio, size = self._arguments.get("multiplier_ratio"), self._arguments.get("multiplier_size")
        if self.pairs[1:] and (size is not None or ratio not in (None, 1.0)):
            # A further pair's T_H takes the first pair's ratio or size, which given points would replace.
            raise _contact_error("on_mesh (a level's problem) takes several contact pairs with the default multiplier "
                                 "mesh only (multiplier_ratio 1, no multiplier_size): build the level's problem in Rust "
                                 "(Problem::on_level)")
        arguments = {**self._arguments, "multiplier_ratio": None, "multiplier_size": None}
        arguments["multiplier_points"] = multiplier_points
        if self._arguments.get("materials") is not None:
            if regions is None:
                raise _settings_error("a body of several materials needs the regions of the new mesh's triangles")
            arguments["regions"] = regions
        if self.primary is None:
            return Problem(mesh, **arguments)
        spans = [s for _, s, _ in self.bodies] if bodies is None else bodies
        if len(spans) != 2:
            raise _contact_error(f"bodies must give the spans of the two bodies, got {len(spans)}")
        if regions is None and any(b[3] is not None for b in self._source):
            raise _settings_error("a body of several materials needs the regions of the new mesh's triangles")
        compiled, offset = [], 0
        for b, s in zip(self._source, spans, strict=True):
            # Each body's regions from the joined mesh's (which index both bodies' materials, the first's first).
            own = None if regions is None else np.asarray(regions)[s[2]:s[3]] - offset
            if own is not None and ((own < 0) | (own >= len(b[2]))).any():
                raise _settings_error(f"regions of body {b[0]!r} must index its materials in problem.materials "
                                      f"({offset} to {offset + len(b[2]) - 1})")
            own = None if own is None else own.tolist()
            compiled.append((b[0], _body_mesh(mesh, b[0], s), b[2], own if own is not None else b[3], *b[4:]))
            offset += len(b[2])
        return Problem(compiled, **arguments)

    @property
    def contact_edges(self) -> npt.NDArray[np.int64]:
        """FE edges of Γ_C by increasing abscissa, (n_c − 1, 2) int64 (left, right node): consecutive
        ``contact_nodes``."""
        nodes = np.asarray(self.contact_nodes)
        return np.column_stack([nodes[:-1], nodes[1:]])
