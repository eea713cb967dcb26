"""The results of a solve as plain data: ``Report``, ``Solution`` and ``History``.

The compiled module hands every result over once, as a dict of numpy arrays (read-only), numbers, names
and lists; these frozen dataclasses give it its types and its documentation. They hold no reference to
the problem or to the core, so they pickle, compare (arrays element by element, NaN equal to NaN) and can
be built without a solve:

>>> import numpy as np
>>> report = Report(status="converged", interrupted_iteration=None, failed_iteration=None,
...                 failure_reason=None, iterations=0, residual_history=np.zeros(0),
...                 coulomb_method=None, coulomb_fallback=False, qp_iterations=np.array([7]), qp_factorizations=np.array([1]), qp_methods=["active_set"],
...                 qp_fallbacks=0, condensation="columns", qp_inaccurate=0, gamma0=0.0, gamma0_bound=1.0,
...                 reused_factorization=False, timings={"qp": 0.001})
>>> report.converged
True

Contact fields live at three kinds of places along Γ_C: multiplier dofs (``multiplier_abscissae``:
``lambda_n``, ``lambda_t``, ``friction_threshold``, ``states``), FE edge midpoints (``edge_abscissae``:
``sigma_n``, ``sigma_t``) and FE nodes (``node_abscissae``: ``u_n``, ``slip``, ``gap``).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
import numpy.typing as npt

from tribo._tribo import STATE_NAMES, format_number

__all__ = ["Report", "Solution", "History", "Level", "Adaptive"]

_Floats = npt.NDArray[np.float64]
_Ints = npt.NDArray[np.int64]
Status = Literal["converged", "max_iterations", "stagnated", "interrupted", "qp_failed", "non_finite", "inaccurate"]


def at_points(values: npt.ArrayLike, n_points: int) -> npt.NDArray[Any]:
    """P1 multiplier dof values at the ``n_points`` points of T_H: as they are, but on a closed Γ_C (a loop: one dof
    fewer than points), whose first dof is also at its last point."""
    v = np.asarray(values)
    return np.append(v, v[:1]) if len(v) == n_points - 1 else v


def dof_span(abscissae: npt.ArrayLike, mask: npt.ArrayLike, period: float | None = None) -> tuple[float, float] | None:
    """The first and last abscissae of the dofs ``mask`` picks, None when it picks none. On a closed Γ_C
    (``period`` its length) the shortest arc that holds them: the loop less its largest gap between picked
    dofs, beginning a period early (before Γ_C's start) where it crosses the cut, as the core reads zones."""
    x = np.asarray(abscissae, dtype=float)[np.asarray(mask, dtype=bool)]
    if len(x) == 0:
        return None
    if period is None:
        return float(x.min()), float(x.max())
    x = np.sort(x)
    # The gap across the cut first, so that on a tie the arc does not cross it (as the core reads it).
    gaps = np.append(x[0] + period - x[-1], np.diff(x))
    k = int(np.argmax(gaps))  # the arc begins after the largest gap: at x[k]
    if k == 0:
        return float(x[0]), float(x[-1])
    return float(x[k] - period), float(x[k - 1])


def _same(a: object, b: object) -> bool:
    """Equal data: arrays of one dtype and shape with equal elements (NaN equal to NaN), containers item by
    item, numbers by value (NaN equal to NaN)."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        x, y = np.asarray(a), np.asarray(b)
        nan = x.dtype.kind in "fc"
        return x.dtype == y.dtype and x.shape == y.shape and bool(np.array_equal(x, y, equal_nan=nan))
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return type(a) is type(b) and len(a) == len(b) and all(map(_same, a, b))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return type(a) is type(b) and bool(a == b)


class _Record:
    """Equality of frozen records by their fields (see ``_same``); they are not hashable."""

    def __eq__(self, other: object) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        return all(_same(getattr(self, f.name), getattr(other, f.name)) for f in dataclasses.fields(self))  # type: ignore[arg-type]

    __hash__ = None  # type: ignore[assignment]


@dataclass(frozen=True, eq=False, repr=False, kw_only=True)
class Report(_Record):
    """How a solve went: status, iterations, γ0 and timings.

    Attributes:
        status: 'converged', 'max_iterations', 'stagnated', 'interrupted' (the progress callback returned
            False), 'qp_failed', 'non_finite' (a field overflowed) or 'inaccurate' (KKT residuals above
            what the tolerances justify). Only 'converged' promises finite fields and small residuals.
        interrupted_iteration: for 'interrupted', the fixed-point iteration after which the solve
            stopped, else None.
        failed_iteration: for 'qp_failed', the fixed-point iteration at which a QP failed (0 = the
            initial QP; for Newton, the QP of a restart after that many steps less one), else None.
        failure_reason: for 'qp_failed', the QP solver's status, else None.
        iterations: iterations of the Coulomb method that answered: fixed-point iterations (a QP each) or
            Newton steps (a dense LU solve each); 0 for frictionless and Tresca.
        residual_history: after each fixed-point iteration, the relative change of λ_n; for Newton, the relative
            merit ‖C‖ / ‖λ_n‖ of each point it evaluated: before each step, at each restart from one fixed-point
            iteration (its QP booked in ``qp_methods`` after the first) and the point it ended on.
        coulomb_method: the Coulomb method that answered, 'fixed_point' or 'newton' (the ``coulomb`` setting
            chooses; 'auto' is the fixed point where H is not formed (``condensation == 'saddle'``), else Newton,
            and the fixed point where Newton did not converge); None for frictionless and Tresca.
        coulomb_fallback: True when ``coulomb='auto'`` tried Newton, which did not converge, and the fixed
            point answered.
        coulomb_check: with ``coulomb_check=True``, what solving a converged Coulomb problem again by the other
            method found: 'agree' (one answer), 'differ' (two answers, each meeting Coulomb's law, further apart
            than their residuals allow: λ is not unique there, or not determined to better than their distance)
            or 'undecided' (the other method did not converge or was refused, or the two lie further apart than
            their residuals where the fixed point's last changes show no contraction); None unchecked.
        check_status: how the other method ended ('converged', …), None unchecked or refused.
        check_distance, check_allowed: the distance of the two answers' λ_n and the bound within which they are
            one, both relative to the larger ‖λ_n‖ (NaN when the other method did not converge; the bound inf
            where the fixed point shows no contraction); None unchecked.
        qp_iterations: iterations of each QP: interior-point iterations (clarabel) or steps (active set).
        qp_factorizations: factorizations among each QP's active-set steps (dense Cholesky of the free
            block, or sparse LDLᵀ of the saddle-point system): the other steps updated or bordered a
            factorization. 0 for clarabel.
        qp_methods: the method that answered each QP: 'clarabel' or 'active_set'.
        qp_fallbacks: how many QPs the first method tried did not answer, so that the other one did.
        condensation: how H was formed: 'columns' (one solve per column the QPs need), 'schur' (all of it
            from a partial factorization with the Γ_C dofs last) or 'saddle' (not at all: the QPs' steps
            solve the sparse saddle-point system).
        qp_inaccurate: how many QPs met only the fallback tolerance (1e-10), not ``qp_tol``.
        gamma0: γ0 used.
        gamma0_bound: the admissible bound on γ0.
        reused_factorization: True when this solve reused the factorization of an earlier solve with the
            same γ0 (the 'factorization' and 'condensation' timings are then those of that earlier solve).
        timings: wall times per phase in seconds: assembly, contact_matrices, factorization,
            condensation, qp, recovery, fields (stresses, reactions, contact fields, KKT residuals and
            the error estimate formed from u and λ).
        estimate: the a posteriori error estimate (see ``Solution.estimator``): ``total`` η and its parts
            ``bulk``, ``gamma_c``, ``contact``, ``friction`` (each the root of a sum of squares over the
            triangles, in stress × length), ``energy_relative`` ((Σ η_K² / E*_K)^½ / a(u_h, u_h)^½, η / (E* a(u_h, u_h))^½ for one material), ``traction``
            (ζ, the estimate of ‖λ − λ_H‖ in L²(Γ_C), a bound) and ``traction_relative`` (ζ / ‖λ_H‖, NaN
            when nothing touches); ``traction_hierarchical`` and ``traction_hierarchical_relative``, the
            hierarchical estimate (1.5‖λ_H − λ_f‖, λ_f with the whole mesh bisected and the strip along the
            contact zone again; the reduction measured where the zone reaches an end of Γ_C) and its ratio
            to ‖λ_f‖ (sharp but not a bound; inf where a measured reduction is 1 or more: no estimate; NaN
            unless an adaptive solve (``stop_on`` ``'hierarchical'``, the default, or ``'enriched'``) or
            ``solve(error_bars=True)`` computed it; on an enriched answer handed back, ½‖λ_H − λ_f‖, its own error); ``traction_calibrated_relative``, on the adaptive level after one so
            estimated, its bound times their ratio there (NaN elsewhere); from the same enriched solve, the error bars
            ``normal_force_error``, ``tangential_force_error``, ``contact_width_error``, ``stick_width_error``
            (estimated absolute errors, NaN unless computed). Empty without an estimate.
    """

    status: Status
    interrupted_iteration: int | None
    failed_iteration: int | None
    failure_reason: str | None
    iterations: int
    residual_history: _Floats
    coulomb_method: Literal["fixed_point", "newton"] | None
    coulomb_fallback: bool
    qp_iterations: _Ints
    qp_factorizations: _Ints
    qp_methods: list[Literal["clarabel", "active_set"]]
    qp_fallbacks: int
    condensation: Literal["columns", "schur", "saddle"]
    qp_inaccurate: int
    gamma0: float
    gamma0_bound: float
    reused_factorization: bool
    timings: dict[str, float]
    estimate: dict[str, float] = dataclasses.field(default_factory=dict)
    coulomb_check: Literal["agree", "differ", "undecided"] | None = None
    check_status: Status | None = None
    check_distance: float | None = None
    check_allowed: float | None = None

    @property
    def converged(self) -> bool:
        """True when the status is 'converged'."""
        return self.status == "converged"

    def __repr__(self) -> str:
        return (
            f"Report(status='{self.status}', iterations={self.iterations}, gamma0={format_number(self.gamma0)}, "
            f"gamma0_bound={format_number(self.gamma0_bound)})"
        )


@dataclass(frozen=True, eq=False, repr=False)
class PairResult(_Record):
    """One contact pair's part of a solution (``Solution.pairs``): the fields on Γ_C hold the pairs one after the
    other, in the order of ``Problem.pairs`` (``index`` its place there); ``multipliers``, ``nodes`` and ``edges`` are the slices of the fields
    per multiplier dof, per FE node and per FE edge of Γ_C that are this pair's; its forces (``contact_force`` the
    force its obstacle exerts on the body, global axes), the widths of its contact and stick zones, and its
    Coulomb coefficient ``mu`` as solved (None for the other laws)."""

    name: str
    index: int
    multipliers: slice
    nodes: slice
    edges: slice
    normal_force: float
    tangential_force: float
    contact_force: tuple[float, float]
    contact_width: float
    stick_width: float
    closed: bool
    mu: float | None = None

    @classmethod
    def from_tuple(cls, index: int, data: tuple[Any, ...]) -> PairResult:
        """Pair ``index`` from the tuple the compiled module gives: (name, three spans, six numbers, closed, μ)."""
        name, ((m0, m1), (n0, n1), (e0, e1)), (n, t, fx, fy, contact, stick), closed, mu = data
        return cls(name, index, slice(m0, m1), slice(n0, n1), slice(e0, e1), n, t, (fx, fy), contact, stick, closed, mu)


@dataclass(frozen=True, eq=False, repr=False, kw_only=True)
class Solution(_Record):
    """The solution of a contact problem: fields as numpy arrays, totals, KKT residuals and the report.

    Contact fields live at multiplier dofs (q of them), FE edge midpoints of Γ_C and FE nodes of Γ_C
    (n_c of them), each with its abscissae.

    Attributes:
        friction: friction law solved: 'frictionless', 'tresca' or 'coulomb'.
        mu: Coulomb coefficient μ, or None: the law's, the first pair's (each pair's in ``pairs``).
        displacement: nodal displacements, (N, 2).
        stress: constant stress (σ_xx, σ_yy, σ_xy) per triangle, (T, 3).
        stress_zz: out-of-plane stress per triangle, (T,): ν (σ_xx + σ_yy) in plane strain (−p̄ in the mixed
            formulation), 0 in plane stress, the
            hoop stress σ_θθ in axisymmetry (where x is r, y the axis and ``stress`` is (σ_rr, σ_zz, σ_rz)).
        von_mises: von Mises stress per triangle (with that σ_zz), (T,).
        reactions: the supports' forces per node, (N, 2) (zero off the supported nodes): (K − G) u − f + Eᵀ λ,
            the equation of (3.1) at the supported dofs (the contact's and the stabilization's shares left out).
        multiplier_abscissae: abscissae of the multiplier dofs, (q,).
        lambda_n: λ_n at the multiplier dofs (a contact pressure: ≥ 0), (q,).
        lambda_t: λ_t at the multiplier dofs (along t), (q,).
        friction_threshold: bound on ``|λ_t|`` per multiplier dof: μ λ_n (Coulomb), the Tresca threshold,
            or 0, (q,).
        states: contact state per multiplier dof as int8: 0 separation, 1 stick, 2 slip (see
            STATE_NAMES), (q,).
        edge_abscissae: abscissae of the midpoints of the FE edges of Γ_C, (n_c − 1,) (n_c less the number of pairs).
        sigma_n: σ_n(u_h) on each FE edge of Γ_C.
        sigma_t: σ_t(u_h) on each FE edge of Γ_C.
        node_abscissae: abscissae of the FE nodes of Γ_C, (n_c,).
        closed: whether Γ_C (the first pair's) is a closed loop: its abscissae wrap with its length (the last node
            abscissa less the first), and a contact or stick zone may cross its cut (its first node, also its last).
        u_n: u_n at the FE nodes of Γ_C.
        slip: u_t − s (slip relative to the obstacle) at the FE nodes of Γ_C; in a history, the slip
            increment of the step.
        gap: gap g = g0 − δ at the FE nodes of Γ_C.
        contact_force: total force (Fx, Fy) the obstacle exerts on the body in global axes:
            −(normal_force n + tangential_force t); with several pairs the sum of theirs (``pairs``).
        obstacle_motion: how the (first pair's) obstacle moved, in global axes: −approach n + shift t (a turned obstacle's
            rotation is not in it: ``summary.json`` gives it as ``obstacle_rotation``).
        normal_force: total normal contact force ∫ λ_n.
        tangential_force: total tangential contact force ∫ λ_t (the obstacle pulls the body by
            −tangential_force along t).
        max_penetration: largest pointwise penetration max(u_n − g)₊ over the FE nodes of Γ_C.
        contact_width: the width of the contact zone: from the first to the last multiplier dof in contact,
            each end placed midway to the neighbouring dof in separation (or at the end of Γ_C); 0 when
            nothing touches. ``report.estimate["contact_width_error"]`` is its error bar when computed.
        stick_width: the same for the dofs that stick (0 when none does).
        kkt: dimensionless KKT residuals of (3.1), each dof against its own terms (``KktResiduals``): equilibrium,
            normal_sign, non_penetration, normal_complementarity, friction_bound, stick, slip_direction.
        report: the report of the solve.
        estimator: the a posteriori error indicator η_K per triangle, (T,): the residuals of equilibrium,
            of the Barbosa–Hughes term λ_H + σ_h n, of contact and of friction (their totals are
            ``report.estimate``; the crate documentation of ``tribo::results`` derives them).
        traction_estimator: the traction indicator ζ_K per triangle, (T,): its part of the estimate of
            the error of the contact tractions on Γ_C (``report.estimate["traction"]`` is the root of the
            sum of squares); it weighs η_K by the distance to Γ_C and adds the contact and friction
            conditions in units of traction.
        nodal_stress: the recovered stress (σ_xx, σ_yy, σ_xy) per node, (N, 3): the area-weighted mean of
            the cell stresses around each node (the simplest Zienkiewicz–Zhu-type recovery). Exact for a
            linear stress at the interior nodes of a uniform mesh; it smooths the P1 cell stress's jumps,
            for plots and files. ``stress`` (per triangle) is the stress of the solve.
        nodal_von_mises: the von Mises stress of ``nodal_stress`` per node, (N,).
        pressure: the pressure p per node of the mixed formulation, (N,): σ = 2μ ε(u) − p̄ I on each triangle
            (p̄ the mean of its three nodes'), p = −λ div u; empty for the displacement formulation.
        pairs: each contact pair's part (``PairResult``), ``Problem.pairs`` in order. With several pairs the fields on
            Γ_C hold the pairs one after the other (each with its own side's abscissae), the forces are their sums,
            and ``contact_width``, ``stick_width`` and ``closed`` are the first pair's.
    """

    friction: Literal["frictionless", "tresca", "coulomb"]
    mu: float | None
    displacement: _Floats
    stress: _Floats
    stress_zz: _Floats
    von_mises: _Floats
    reactions: _Floats
    multiplier_abscissae: _Floats
    lambda_n: _Floats
    lambda_t: _Floats
    friction_threshold: _Floats
    states: npt.NDArray[np.int8]
    edge_abscissae: _Floats
    sigma_n: _Floats
    sigma_t: _Floats
    node_abscissae: _Floats
    u_n: _Floats
    slip: _Floats
    gap: _Floats
    contact_force: tuple[float, float]
    obstacle_motion: tuple[float, float]
    normal_force: float
    tangential_force: float
    max_penetration: float
    kkt: dict[str, float]
    report: Report
    estimator: _Floats = dataclasses.field(default_factory=lambda: np.zeros(0))
    traction_estimator: _Floats = dataclasses.field(default_factory=lambda: np.zeros(0))
    nodal_stress: _Floats = dataclasses.field(default_factory=lambda: np.zeros((0, 3)))
    nodal_von_mises: _Floats = dataclasses.field(default_factory=lambda: np.zeros(0))
    pressure: _Floats = dataclasses.field(default_factory=lambda: np.zeros(0))
    contact_width: float = math.nan
    stick_width: float = math.nan
    closed: bool = False
    pairs: list[PairResult] = dataclasses.field(default_factory=list)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Solution:
        """A solution from the dict of fields the compiled module gives (the report as a dict too)."""
        pairs = [PairResult.from_tuple(k, p) for k, p in enumerate(data.get("pairs", []))]
        return cls(**{**data, "report": Report(**data["report"]), "pairs": pairs})

    def pair(self, k: int) -> Solution:
        """This solution with its fields on Γ_C those of pair ``k`` alone (``pairs[k]``, which keeps its ``index``), its
        forces, zone widths, ``closed`` and ``mu`` the pair's: what a plot of one contact side reads (the plots take the
        first pair's). The displacement, stresses, ``obstacle_motion`` (the first pair's), ``max_penetration``, ``kkt``
        and the report stay the whole solution's."""
        if len(self.pairs) <= 1 and k == 0:
            return self
        r = self.pairs[k]
        spans = [(r.multipliers, ("multiplier_abscissae", "lambda_n", "lambda_t", "friction_threshold", "states")),
                 (r.nodes, ("node_abscissae", "u_n", "slip", "gap")), (r.edges, ("edge_abscissae", "sigma_n", "sigma_t"))]
        fields = {name: getattr(self, name)[span] for span, names in spans for name in names}

        def shifted(s: slice) -> slice:
            return slice(0, s.stop - s.start)

        alone = [dataclasses.replace(r, multipliers=shifted(r.multipliers), nodes=shifted(r.nodes),
                                     edges=shifted(r.edges))]
        return dataclasses.replace(self, **fields, normal_force=r.normal_force, tangential_force=r.tangential_force,
                                   contact_force=r.contact_force, contact_width=r.contact_width,
                                   stick_width=r.stick_width, closed=r.closed, mu=r.mu, pairs=alone)

    @property
    def state_names(self) -> list[str]:
        """Contact state per multiplier dof as strings."""
        return [STATE_NAMES[s] for s in self.states]

    @property
    def current_gap(self) -> _Floats:
        """Current gap g − u_n at the FE nodes of Γ_C: 0 where the body touches the obstacle, < 0 where it
        penetrates."""
        return self.gap - self.u_n

    def extent(self, mask: npt.ArrayLike) -> float:
        """The length of Γ_C from the first to the last multiplier dof ``mask`` picks (0 for none); on a closed
        Γ_C the shortest arc that holds them, which may cross the cut (``dof_span``). The first pair's dofs."""
        first = self.pairs[0].multipliers if len(self.pairs) > 1 else slice(None)  # the first pair's dofs
        x = self.pair(0).node_abscissae
        at = self.multiplier_abscissae[first]
        span = dof_span(at, np.asarray(mask)[first], float(x[-1] - x[0]) if self.closed else None)
        return span[1] - span[0] if span else 0.0

    @property
    def kkt_max(self) -> float:
        """The largest KKT residual (NaN if any is NaN)."""
        return float(np.max([0.0, *self.kkt.values()]))

    def __repr__(self) -> str:
        return (
            f"Solution(friction='{self.friction}', status='{self.report.status}', "
            f"normal_force={format_number(self.normal_force, 6)}, "
            f"tangential_force={format_number(self.tangential_force, 6)})"
        )


@dataclass(frozen=True, eq=False, repr=False, kw_only=True)
class History(_Record):
    """A quasi-static loading history: per-step arrays for every step that converged, and the solutions kept.

    The arrays have one entry per converged step (``len(history)``); ``approach``, ``shift``, ``load_factor`` and
    ``rotation`` give the steps asked for (all of them). ``solutions`` holds every step's solution by default; with
    ``keep_every=k`` only every k-th step's (``step % k == 0``) and the last converged one's, ``kept`` naming their
    steps (the arrays still cover every step); ``history.solution(step)`` finds a kept step's solution.

    Attributes:
        status: 'converged' when every step converged; otherwise the status of the step that ended the
            history ('interrupted' when the progress callback returned False).
        ended_at: the step (0-based) that ended the history early, or None.
        solutions: the solutions kept (every converged step's by default), in order.
        kept: the step (0-based) of each solution in ``solutions``.
        failed: the last iterate of a step that did not converge (not in ``solutions``), or None.
        approach: approach δ_k of every step asked for.
        shift: tangential position s_k of every step asked for.
        load_factor: load factor α_k of every step asked for.
        rotation: the obstacle's angle θ_k (radians, about its rotation's centre) of every step asked for; NaN
            where a step kept the problem's own.
        displacements: the prescribed displacement components the steps moved ('set.x'/'set.y' of the
            problem's ``prescribed``), each with its value at every step asked for; empty when the history
            kept them as the problem has them.
        normal_force: total normal force ∫λ_n per converged step.
        tangential_force: total tangential force ∫λ_t per converged step.
        error_estimate, traction_error: the error estimate η (energy norm) and the relative traction error estimate
            (the bound; NaN where nothing touches) per converged step.
        traction_error_hierarchical: the hierarchical estimate of the relative traction error per converged step
            (NaN where not computed: ``solve_history_adaptive`` does, unless ``stop_on='bound'``, near ``tol``; on an
            enriched history handed back, each step's ½‖λ_H − λ_f‖, its own error); ``traction_error_calibrated``, on
            the adaptive level after one so estimated, each step's bound times that level's ratio of the two (or NaN).
        stick_count, slip_count, separation_count: multiplier dofs that stick, slip, or are separated from the
            obstacle, per converged step (over every pair).
        contact_zone: (first, last) abscissa of the first pair's multiplier dofs in contact, per converged step, (K, 2);
            NaN when nothing touches. On a closed Γ_C the shortest arc that holds them: first < the side's
            start where it crosses the cut (first + its length is where it begins).
        stick_zone: (first, last) abscissa of the first pair's multiplier dofs that stick, per converged step, (K, 2);
            NaN when none sticks.
        stick_slip_boundaries: the abscissae of the (first pair's) stick–slip boundaries (midpoints between a dof that
            sticks and a neighbour that slips) of every converged step, in step order: one array however
            long the history (``stick_slip_boundaries[stick_slip_steps == k]`` are those of step k).
        stick_slip_steps: the step (0-based) of each of ``stick_slip_boundaries``.
        gross_sliding: per converged step, True when the (first pair's) contact slides as a whole (something touches
            and every dof in contact slips: ``|Q| = μP`` for Coulomb friction).
        pairs: each contact pair's series by its name (``Problem.pairs``, the first pair's too): 'normal_force',
            'tangential_force', 'contact_zone', 'stick_zone' and 'gross_sliding' as above (zones on its own side).
        step_seconds: wall time of each step solved (the converged ones, then the failed one), in seconds.
        factorizations: factorizations of K − G done for the history: 1, or 0 when an earlier solve's was
            reused.
        setup_seconds: wall time of the factorization set-up, in seconds (0 when reused).
    """

    status: Status
    ended_at: int | None
    solutions: list[Solution]
    kept: _Ints
    failed: Solution | None
    approach: _Floats
    shift: _Floats
    load_factor: _Floats
    rotation: _Floats
    displacements: dict[str, _Floats] = dataclasses.field(default_factory=dict)
    normal_force: _Floats
    tangential_force: _Floats
    error_estimate: _Floats
    traction_error: _Floats
    traction_error_hierarchical: _Floats
    traction_error_calibrated: _Floats
    stick_count: _Ints
    slip_count: _Ints
    separation_count: _Ints
    contact_zone: _Floats
    stick_zone: _Floats
    stick_slip_boundaries: _Floats
    stick_slip_steps: _Ints
    gross_sliding: npt.NDArray[np.bool_]
    pairs: dict[str, dict[str, npt.NDArray[Any]]] = dataclasses.field(default_factory=dict)
    step_seconds: _Floats
    factorizations: int
    setup_seconds: float

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> History:
        """A history from the dict the compiled module gives (its solutions as dicts too)."""
        failed, pairs = data["failed"], dict(data["pairs"])
        first = next(iter(pairs.values()))
        first.setdefault("normal_force", data["normal_force"])  # one pair: the totals are its own
        first.setdefault("tangential_force", data["tangential_force"])
        return cls(**{
            **data,
            "pairs": pairs,
            **{key: first[key] for key in ("contact_zone", "stick_zone", "gross_sliding")},
            "solutions": [Solution.from_dict(s) for s in data["solutions"]],
            "failed": None if failed is None else Solution.from_dict(failed),
        })

    @property
    def converged(self) -> bool:
        """True when every step converged."""
        return self.status == "converged"

    def __len__(self) -> int:
        return len(self.normal_force)

    def solution(self, step: int) -> Solution:
        """The kept solution of ``step`` (0-based; negative counts from the last converged step).

        Raises:
            KeyError: the step did not converge or was not kept (see ``keep_every``).
        """
        k = step + len(self) if step < 0 else step
        where = np.flatnonzero(self.kept == k)
        if where.size == 0:
            raise KeyError(f"step {step} is not kept (kept: {self.kept.tolist()}; converged steps: {len(self)})")
        return self.solutions[int(where[0])]

    def __repr__(self) -> str:
        return (
            f"History(status='{self.status}', steps={len(self)}/{len(self.approach)}, "
            f"kept={len(self.solutions)}, factorizations={self.factorizations})"
        )


@dataclass(frozen=True, eq=False, kw_only=True)
class Level(_Record):
    """One level of an adaptive solve.

    Attributes:
        unknowns: unknowns (displacements after the supports, and the pressures of the mixed formulation).
        multipliers: multiplier dofs q (per component).
        triangles: triangles of the level's mesh.
        estimate: the level's a posteriori estimate (the keys of ``Report.estimate``).
        relative: the relative estimate the stopping test reads: of the contact tractions, or of the
            energy while nothing touches (inf when the body has not moved yet).
        seconds: wall time of the level (building the problem, solving, estimating, marking, refining); 0 if
            ``enriched`` (solved as the estimate of the level before it, whose seconds count it).
        status: how the level's solve ended.
        enriched: whether the level is the answer enriched for the estimate of the level before it, handed back
            as the last (``stop_on='enriched'``); its hierarchical estimate is then half its change from it.
    """

    unknowns: int
    multipliers: int
    triangles: int
    estimate: dict[str, float]
    relative: float
    seconds: float
    status: Status
    enriched: bool = False


AdaptStop = Literal["tolerance", "max_unknowns", "max_levels", "memory_budget", "not_converged", "exact", "interrupted"]


@dataclass(frozen=True, eq=False, repr=False, kw_only=True)
class _Levels(_Record):
    """What every adaptive result holds besides its answer: the problem on the last mesh, the levels and
    why the loop stopped."""

    problem: Any
    levels: list[Level]
    stop: AdaptStop
    meshes: list[tuple[Any, _Floats, list[list[int]], Any]] = dataclasses.field(default_factory=list)

    def level_problem(self, level: int) -> Any:
        """The Problem of level ``level`` (its mesh and T_H, the rest as ``problem``), to look at it or solve
        it again."""
        return self.problem.on_mesh(*self.meshes[level])

    def _summary(self) -> str:
        last = self.levels[-1]
        return f"stop='{self.stop}', levels={len(self.levels)}, unknowns={last.unknowns}, relative={format_number(last.relative)}"


@dataclass(frozen=True, eq=False, repr=False, kw_only=True)
class Adaptive(_Levels):
    """The result of ``Problem.solve_adaptive``.

    Attributes:
        solution: the last level's Solution.
        problem: the Problem on the last mesh (``problem.mesh`` the refined mesh, T_H its multiplier mesh).
        levels: every level, the first (the given mesh) included.
        stop: why the loop stopped: 'tolerance' (the relative estimate reached ``tol``), 'max_unknowns'
            (the next refinement would have exceeded it), 'max_levels', 'memory_budget' (the next level's solve
            would have exceeded it: the level before is handed back), 'not_converged' (a level's solve did not
            converge), 'exact' (the estimate is zero) or 'interrupted' (the progress callback returned False).
        meshes: each level's Mesh, T_H points, bodies' spans in the mesh (as ``problem.bodies``:
            first node, end, first triangle, end per body) and triangles' regions (as ``problem.regions``);
            ``level_problem(k)`` builds level k's Problem.
    """

    solution: Solution

    def __repr__(self) -> str:
        return f"Adaptive({self._summary()})"


@dataclass(frozen=True, eq=False, repr=False, kw_only=True)
class AdaptiveHistory(_Levels):
    """The result of ``Problem.solve_history_adaptive``.

    Attributes:
        history: the History solved on the last mesh.
        problem: the Problem on the last mesh.
        levels: every level, the first (the given mesh) included; a level's estimate is that of its step
            (among those adapted on) with the largest relative estimate.
        stop: why the loop stopped, as ``Adaptive.stop``.
        meshes: each level's Mesh, T_H points, bodies' spans and triangles' regions, as ``Adaptive.meshes``.
    """

    history: History

    def __repr__(self) -> str:
        return f"AdaptiveHistory({self._summary()}, steps={len(self.history.solutions)})"
