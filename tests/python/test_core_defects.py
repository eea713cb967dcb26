"""Regression tests of the defects an outside fuzzing campaign found (numbered D1–D20 in its report), in
the Python API where they were found, each with the campaign's reproduction: a panic, an abort or a wrong
'converged' answer before, a typed error or an honest status now. Reproductions use
``m = Mesh.rectangle((-2,2),(-2,0),8,4)`` and the ``KW`` below, as the report does.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from conftest import hertz_problem
from fuzzing import assert_honest, outcome

import tribo

KW: dict[str, Any] = dict(young=200.0, poisson=0.3, clamped="bottom", contact="top")


def block() -> tribo.Mesh:
    return tribo.Mesh.rectangle((-2.0, 2.0), (-2.0, 0.0), 8, 4)


def promise(**kw: Any) -> None:
    """Problem(block(), **kw).solve(): a TriboError, or a solution whose status is honest; no panic."""
    problem = outcome(lambda: tribo.Problem(block(), **kw))
    if problem is not None:
        solution = outcome(problem.solve)
        if solution is not None:
            assert_honest(solution)


# ----- panics and aborts -----


@pytest.mark.parametrize("young", [1e308, 5e-324])
def test_d1_extreme_young_is_not_a_panic(young: float) -> None:
    promise(**{**KW, "young": young})


@pytest.mark.parametrize("multiplier", [{"multiplier_ratio": 1e-20}, {"multiplier_size": 1e-300}])
def test_d2_multiplier_mesh_too_fine_is_a_typed_error(multiplier: dict[str, Any]) -> None:
    with pytest.raises(tribo.TriboError, match=r"\d"):  # the message gives the size
        tribo.Problem(block(), **KW, **multiplier)


def test_d3_multiplier_size_too_small_is_a_typed_error() -> None:
    with pytest.raises(tribo.TriboError, match=r"\d"):
        tribo.Problem(block(), **KW, multiplier_size=1e-12)  # 32 TB


def test_d3_dense_contact_matrix_too_large_is_a_typed_error() -> None:
    problem = tribo.Problem(block(), **KW, approach=0.01, multiplier_points=np.linspace(-2.0, 2.0, 100_000))
    with pytest.raises(tribo.SolverError, match=r"memory budget") as info:
        problem.solve()  # a dense H of about 320 GB
    assert info.value.kind == "MemoryBudget" and info.value.details["needed"] > info.value.details["budget"]


def test_d3_rectangle_too_large_is_a_typed_error() -> None:
    with pytest.raises(tribo.MeshError, match=r"\d"):
        tribo.Mesh.rectangle((0.0, 1.0), (0.0, 1.0), 4000, 4000)  # 5.5 GB at once


# ----- 'converged' answers that are wrong -----


def test_d4_overflowing_load_is_not_converged() -> None:
    promise(**KW, approach=0.01, body_force=(1e308, 0.0))


def test_d5_von_mises_without_overflow() -> None:
    s = tribo.Problem(block(), **{**KW, "young": 1e300}, approach=0.01).solve()
    scale = np.abs(s.stress).max()
    sxx, syy, sxy = (s.stress / scale).T
    # Plane strain: σ_zz = ν (σ_xx + σ_yy).
    szz = KW["poisson"] * (sxx + syy)
    expected = scale * np.sqrt(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2) + 3.0 * sxy**2)
    np.testing.assert_allclose(s.von_mises, expected, rtol=1e-12)


def test_d6_nan_gap_at_contact_nodes_is_refused() -> None:
    nodes = tribo.Problem(block(), **KW, approach=0.01).solve().node_abscissae

    def gap(xi: float) -> float:
        return float("nan") if np.abs(nodes - xi).min() == 0.0 else 0.0

    with pytest.raises(tribo.TriboError):
        tribo.Problem(block(), **KW, obstacle=gap, approach=0.01).solve()


@pytest.mark.parametrize("friction", [{"threshold": 1e5}, {"threshold": 1e6}, {"mu": 1e8}])
def test_d9_large_friction_bounds_give_the_same_stick_solution(friction: dict[str, Any]) -> None:
    """All of Γ_C sticks (max |λ_t| ≈ 2) for every bound ≥ 3, so λ is one answer. The all-stick λ for
    thresholds from 3 to 100 agree to 5e-6 today: 1e-4 leaves room for the QP tolerance, not for a
    scaling defect (2.9 % at 1e5, 25 % at 1e6, F_n ten times too large at μ = 1e8)."""
    hertz = hertz_problem(shift=0.004)
    reference = hertz.solve(threshold=100.0) if "threshold" in friction else hertz.solve(mu=100.0)
    assert reference.report.status == "converged" and "slip" not in reference.state_names
    s = hertz.solve(**friction)
    assert s.report.status == "converged", s.report.status
    error = np.abs(s.lambda_n - reference.lambda_n).max() / np.abs(reference.lambda_n).max()
    assert error < 1e-4, f"λ_n off by {error:.2e} with status 'converged'"


def two_squares_joined_at_a_node() -> tribo.Mesh:
    points = [[0, 0], [1, 0], [1, 1], [0, 1], [2, 1], [2, 2], [1, 2]]
    triangles = [[0, 1, 2], [0, 2, 3], [2, 4, 5], [2, 5, 6]]
    return tribo.Mesh(points, triangles, {"bottom": [[0, 1]], "top": [[5, 6]]})


def test_d10_mechanism_is_an_error() -> None:
    """The piece joined at a single node has no support: refused at the door, naming the piece."""
    with pytest.raises(tribo.SettingsError, match="node") as info:
        tribo.Problem(two_squares_joined_at_a_node(), young=1.0, poisson=0.3, clamped="bottom", contact="top", approach=0.01)
    assert info.value.kind == "FloatingPiece" and info.value.details["pieces"] == 2


# Equilibrium residual a 'converged' solve may report: a direct solve that lost more than half of the
# digits (√ε) is not converged.
EQUILIBRIUM_TOL = float(np.sqrt(np.finfo(np.float64).eps))


@pytest.mark.parametrize(
    "poisson",
    [
        0.49999999999999994,  # the report's value
        0.499999999999999,  # 'converged' with an equilibrium residual of 0.26 before the fix
    ],
)
def test_d11_nearly_incompressible_is_an_error_or_accurate(poisson: float) -> None:
    problem = outcome(lambda: hertz_problem(young=1.0, poisson=poisson))
    solution = outcome(problem.solve) if problem is not None else None
    if solution is not None and solution.report.status == "converged":
        assert solution.kkt["equilibrium"] < EQUILIBRIUM_TOL


def test_d12_clamped_contact_nodes_are_refused_or_reported() -> None:
    square = tribo.Mesh.rectangle((0.0, 1.0), (0.0, 1.0), 1, 1)
    problem = outcome(
        lambda: tribo.Problem(square, young=1.0, poisson=0.3, clamped=["left", "right"], contact="top", approach=0.01)
    )
    solution = outcome(lambda: problem.solve(gamma0=0.0)) if problem is not None else None
    assert solution is None or solution.report.status != "converged", "the approach was not met and no one said"


def test_d13_duplicate_edge_in_a_set_is_refused() -> None:
    square = tribo.Mesh.rectangle((0.0, 1.0), (0.0, 1.0), 1, 1)
    sets = {**square.edge_sets, "right": np.vstack([square.edge_sets["right"]] * 2)}
    with pytest.raises(tribo.MeshError, match="'right'"):
        tribo.Mesh(square.points, square.triangles, sets)


def test_d20_folded_mesh_is_refused() -> None:
    with pytest.raises(tribo.MeshError):
        tribo.Mesh([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.5]], [[0, 1, 2], [0, 2, 3], [0, 1, 4]])


# ----- minor -----


def test_d18_huge_index_is_reported_as_it_is() -> None:
    with pytest.raises(tribo.MeshError, match="18446744073709551615"):
        tribo.Mesh([[0, 0], [1, 0], [1, 1]], np.array([[0, 1, 2**64 - 1]], dtype=np.uint64))


def test_d19_denormal_young_is_refused_at_the_door() -> None:
    try:
        problem = tribo.Problem(block(), **{**KW, "young": 1e-310})
    except tribo.TriboError as e:
        assert "inf" not in str(e)
        return
    assert np.isfinite(problem.gamma0_bound)
    promise(**{**KW, "young": 1e-310})


@pytest.mark.parametrize(
    ("setup", "friction"),
    [
        ({}, {}),  # nothing happens: NaN
        ({"shift": 2.65e-39}, {"threshold": 1.0}),  # Tresca and a tiny shift: inf
        # Touching without force (found by a long fuzz run): the circle's gap away from its centre is its
        # radius, the approach equals it, so the gap is 0 at both nodes of Γ_C and λ = 0: NaN.
        ({"obstacle": tribo.Obstacle.circle(0.03125), "approach": 0.03125, "space": "P0", "multiplier_ratio": 1.0}, {}),
    ],
)
def test_kkt_residuals_stay_finite_without_contact(setup: dict[str, Any], friction: dict[str, Any]) -> None:
    """λ = 0 and a gap of 0 (or none): the residuals' scale λ·gap, both floored at the smallest normal
    float, underflows to 0 and 0/0 is reported."""
    mesh = tribo.Mesh.rectangle((-2.0, 2.0), (-1.0, 0.0), 1, 1) if "obstacle" in setup else block()
    solution = tribo.Problem(mesh, **KW, **setup).solve(**friction)
    assert_honest(solution)
    assert solution.kkt_max < 1.0


# ----- found by the fuzzing, not in the report -----


def test_inverted_triangle_with_huge_coordinates_is_refused() -> None:
    """The first triangle is clockwise; with coordinates near 1e300 its area is inf − inf = NaN, which
    passed the checks before: now coordinates whose area or diameter overflow are refused as such."""
    points = 1e300 * np.array([[0.166, -0.949], [-0.299, -0.103], [-1.471, 0.176], [-0.404, 2.037]])
    with pytest.raises(tribo.MeshError, match="too large"):
        tribo.Mesh(points, [[0, 1, 3], [0, 3, 2]])


@pytest.mark.parametrize(
    "call",
    [
        "rectangle",
        "qp_max_iter",
        "fp_max_iter",
    ],
)
def test_integers_out_of_range_are_typed_errors(call: str) -> None:
    with pytest.raises(tribo.TriboError):
        if call == "rectangle":
            tribo.Mesh.rectangle((0.0, 1.0), (0.0, 1.0), -1, 2)
        else:
            settings: dict[str, Any] = {call: -1}
            tribo.Problem(block(), **KW, approach=0.01).solve(**settings, mu=0.3)
