"""Results are plain data: built without a solve, pickled, compared; the arrays of a solve are read-only."""

from __future__ import annotations

import dataclasses
import pickle
from typing import Any

import numpy as np
import pytest
from conftest import hertz_problem

import tribo
from tribo.problem import history_steps


def report(**kw: Any) -> tribo.Report:
    fields: dict[str, Any] = dict(
        status="converged", interrupted_iteration=None, failed_iteration=None, failure_reason=None, iterations=2,
        residual_history=np.array([0.1, 1e-9]), coulomb_method="fixed_point", coulomb_fallback=False,
        qp_iterations=np.array([9, 3, 1]), qp_factorizations=np.array([1, 0, 0]),
        qp_methods=["active_set"] * 3, qp_fallbacks=0, condensation="columns", qp_inaccurate=0, gamma0=0.0,
        gamma0_bound=9.29e-4, reused_factorization=False, timings={"qp": 0.002},
    )
    return tribo.Report(**{**fields, **kw})


def solution(**kw: Any) -> tribo.Solution:
    """Two triangles, three multiplier dofs (one separated, one sticking, one slipping), three Γ_C nodes."""
    q, nodes = np.array([0.0, 0.5, 1.0]), np.array([0.0, 0.5, 1.0])
    fields: dict[str, Any] = dict(
        friction="coulomb", mu=0.3, displacement=np.zeros((4, 2)), stress=np.zeros((2, 3)), stress_zz=np.zeros(2),
        von_mises=np.zeros(2), reactions=np.zeros((4, 2)), multiplier_abscissae=q, lambda_n=np.array([0.0, 2.0, 1.0]),
        lambda_t=np.array([0.0, 0.1, 0.3]), friction_threshold=np.array([0.0, 0.6, 0.3]),
        states=np.array([0, 1, 2], dtype=np.int8), edge_abscissae=np.array([0.25, 0.75]), sigma_n=np.zeros(2),
        sigma_t=np.zeros(2), node_abscissae=nodes, u_n=np.array([0.0, 0.01, 0.0]), slip=np.zeros(3),
        gap=np.array([0.02, 0.01, 0.02]), contact_force=(0.0, -1.5), obstacle_motion=(0.0, -0.01), normal_force=1.5,
        tangential_force=0.2, max_penetration=0.0,
        kkt={"equilibrium": 1e-12, "normal_sign": 0.0, "stick": float("nan")}, report=report(),
    )
    return tribo.Solution(**{**fields, **kw})


def history(**kw: Any) -> tribo.History:
    s = solution()
    fields: dict[str, Any] = dict(
        status="converged", ended_at=None, solutions=[s, s], kept=np.arange(2), failed=None, approach=np.full(2, 0.01),
        shift=np.array([0.0, 0.001]), load_factor=np.ones(2), rotation=np.full(2, np.nan), normal_force=np.full(2, 1.5),
        tangential_force=np.full(2, 0.2), error_estimate=np.full(2, 0.1), traction_error=np.full(2, 0.05),
        traction_error_hierarchical=np.full(2, np.nan), traction_error_calibrated=np.full(2, np.nan),
        stick_count=np.ones(2, dtype=np.int64), slip_count=np.ones(2, dtype=np.int64),
        separation_count=np.ones(2, dtype=np.int64), contact_zone=np.array([[0.5, 1.0], [np.nan, np.nan]]),
        stick_zone=np.array([[0.5, 0.5], [np.nan, np.nan]]), stick_slip_boundaries=np.array([0.75]),
        stick_slip_steps=np.zeros(1, dtype=np.int64),
        gross_sliding=np.zeros(2, dtype=bool), step_seconds=np.full(2, 0.01), factorizations=1, setup_seconds=0.02,
    )
    return tribo.History(**{**fields, **kw})


def test_results_are_built_without_a_solve() -> None:
    r = report(status="interrupted", interrupted_iteration=1)
    assert not r.converged and r.interrupted_iteration == 1 and r.failure_reason is None
    assert report(status="qp_failed", failed_iteration=0, failure_reason="MaxIterations").failure_reason == "MaxIterations"
    s = solution()
    assert s.state_names == ["separation", "stick", "slip"]
    np.testing.assert_array_equal(s.current_gap, [0.02, 0.0, 0.02])
    assert np.isnan(s.kkt_max), "a NaN residual is the largest"
    assert solution(kkt={"equilibrium": 1e-12, "stick": 3e-9}).kkt_max == 3e-9
    assert repr(s) == "Solution(friction='coulomb', status='converged', normal_force=1.5, tangential_force=0.2)"
    assert repr(s.report) == "Report(status='converged', iterations=2, gamma0=0, gamma0_bound=9.29e-4)"
    h = history()
    assert h.converged and len(h) == 2 and h.failed is None and repr(h) == (
        "History(status='converged', steps=2/2, kept=2, factorizations=1)")
    with pytest.raises(dataclasses.FrozenInstanceError):
        s.mu = 0.5  # type: ignore[misc]


def test_results_pickle_and_compare_as_data() -> None:
    for result in (report(), solution(), history(), history(failed=solution(), status="max_iterations", ended_at=2)):
        again = pickle.loads(pickle.dumps(result))
        assert type(again) is type(result) and again == result
    # Equal data, NaN included; any difference in a value, a dtype or a nested result is a difference.
    assert solution() == solution() and history() == history()
    assert solution(lambda_n=np.array([0.0, 2.0, 1.5])) != solution()
    assert solution(states=np.array([0, 1, 2], dtype=np.int64)) != solution()
    assert solution(report=report(iterations=3)) != solution()
    assert history(stick_slip_boundaries=np.array([0.5])) != history()
    assert solution() != "a solution"
    with pytest.raises(TypeError):
        hash(solution())


def test_solved_results_pickle_and_are_read_only() -> None:
    problem = hertz_problem(shift=0.004)
    s = problem.solve(mu=0.3)
    assert isinstance(s, tribo.Solution) and isinstance(s.report, tribo.Report)
    assert pickle.loads(pickle.dumps(s)) == s
    with pytest.raises(ValueError, match="read-only"):
        s.lambda_n[0] = 1.0
    assert s.lambda_n is s.lambda_n, "built once, not on every read"
    h = problem.solve_history(0.01, [0.0, 0.002], mu=0.3)
    assert isinstance(h, tribo.History) and all(isinstance(x, tribo.Solution) for x in h.solutions)
    assert pickle.loads(pickle.dumps(h)) == h
    with pytest.raises(ValueError, match="read-only"):
        problem.contact_nodes[0] = 3
    with pytest.raises(ValueError, match="read-only"):
        problem.mesh.points[0, 0] = 3.0


def test_history_steps_broadcast_scalars() -> None:
    nan = np.nan  # the obstacle's angle: the problem's own
    np.testing.assert_array_equal(history_steps(0.01, [0.0, 0.002]), [[0.01, 0.0, 1.0, nan], [0.01, 0.002, 1.0, nan]])
    np.testing.assert_array_equal(history_steps([0.01], 0.0, [0.5, 1.0]), [[0.01, 0.0, 0.5, nan], [0.01, 0.0, 1.0, nan]])
    np.testing.assert_array_equal(history_steps(0.0, 0.0, rotation=[0.1, 0.2]), [[0.0, 0.0, 1.0, 0.1], [0.0, 0.0, 1.0, 0.2]])
    for args, match in [
        ((0.01, [0.0, 0.1], [1.0, 1.0, 1.0]), "shift has 2 values, but the history has 3 steps"),
        ((0.01, []), r"at least one step \(shift has no value\)"),
        (([[0.01]], 0.0), "approach must be a number or a sequence of numbers, got shape"),
        ((0.01, "far"), "shift must be a number"),
    ]:
        with pytest.raises(tribo.SettingsError, match=match) as info:
            history_steps(*args)
        assert info.value.kind == "BadInput" and info.value.details == {}
