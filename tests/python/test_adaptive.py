"""Adaptive refinement from Python: the loop finds a contact zone no grading hint knows, stops where it
must, and refuses bad settings with a SettingsError naming the setting."""

from __future__ import annotations

import pickle
from pathlib import Path

import numpy as np
import pytest

import tribo


def off_centre() -> tribo.Problem:
    """The Hertz block on an 8 x 4 uniform mesh with the cylinder between two nodes of Γ_C: no node
    touches at first."""
    mesh = tribo.Mesh.rectangle((-2.0, 2.0), (-2.0, 0.0), 8, 4)
    return tribo.Problem(mesh, young=200.0, poisson=0.3, clamped="bottom", contact="top",
                         obstacle=tribo.Obstacle.circle(1.0, center=0.3), approach=0.01)


def test_the_loop_finds_the_contact_zone_and_hands_back_its_problem() -> None:
    problem = off_centre()
    assert problem.solve().normal_force == 0.0
    heard: list[tuple[int, float, float]] = []
    out = problem.solve_adaptive(tol=0.05, progress=lambda u, r, s: heard.append((u, r, s)))
    assert out.stop == "tolerance" and out.solution.report.converged
    assert len(heard) == len(out.levels) and [h[0] for h in heard] == [lv.unknowns for lv in out.levels]
    assert out.levels[-1].relative <= 0.05 and out.levels[0].relative == np.inf
    assert all(b.unknowns > a.unknowns for a, b in zip(out.levels, out.levels[1:]))
    assert out.problem.n_free == out.levels[-1].unknowns
    assert out.solution.estimator.shape == (out.problem.mesh.n_triangles,)
    # The problem handed back is the last level's: solving it again gives its solution.
    again = out.problem.solve()
    scale = np.max(out.solution.lambda_n)
    assert np.max(np.abs(again.lambda_n - out.solution.lambda_n)) <= 1e-6 * scale
    assert pickle.loads(pickle.dumps(out.levels)) == out.levels
    # Every level's mesh and T_H come back; level k's problem is the one the loop solved there.
    assert len(out.meshes) == len(out.levels)
    for k in (0, len(out.levels) // 2, len(out.levels) - 1):
        level = out.level_problem(k)
        assert level.n_free == out.levels[k].unknowns and level.n_multipliers == out.levels[k].multipliers
    assert out.level_problem(0).mesh.n_triangles == problem.mesh.n_triangles


def test_the_loop_stops_before_max_unknowns_and_when_told() -> None:
    out = off_centre().solve_adaptive(tol=1e-6, max_unknowns=1500)
    assert out.stop == "max_unknowns" and all(lv.unknowns <= 1500 for lv in out.levels)
    out = off_centre().solve_adaptive(tol=1e-6, progress=lambda u, r, s: len(str(u)) < 3)
    assert out.stop == "interrupted" and out.levels[-1].unknowns >= 100


def test_a_level_beyond_the_memory_budget_hands_back_the_level_before() -> None:
    """6 MiB holds clarabel's dense QP over about 200 multiplier unknowns: the loop stops there, converged."""
    out = off_centre().solve_adaptive(tol=1e-6, stop_on="bound", max_unknowns=400_000, mu=0.3, memory_budget=6 << 20)
    assert out.stop == "memory_budget" and len(out.levels) > 3
    assert out.solution.report.status == "converged" and out.levels[-1].unknowns == out.problem.n_free


@pytest.mark.parametrize(
    ("keywords", "name"),
    [
        ({"tol": 0.0}, "adapt_tol"),
        ({"tol": float("nan")}, "adapt_tol"),
        ({"theta": 0.0}, "adapt_theta"),
        ({"theta": 1.5}, "adapt_theta"),
        ({"max_levels": 0}, "adapt_max_levels"),
        ({"max_unknowns": 10}, "adapt_max_unknowns"),
        ({"algebraic": 1.0}, "adapt_algebraic"),
    ],
)
def test_bad_adaptive_settings_name_the_setting(keywords: dict[str, float], name: str) -> None:
    with pytest.raises(tribo.SettingsError, match=name):
        off_centre().solve_adaptive(**keywords)  # type: ignore[arg-type]


def test_an_unknown_marking_or_bisection_is_refused() -> None:
    with pytest.raises(tribo.SettingsError, match="dorfler"):
        off_centre().solve_adaptive(marking="greedy")  # type: ignore[arg-type]
    with pytest.raises(tribo.SettingsError, match="all_edges") as e:
        off_centre().solve_adaptive(bisection="red")  # type: ignore[arg-type]
    assert e.value.kind == "UnknownChoice"  # type: ignore[attr-defined]


def test_stopping_on_the_hierarchical_estimate_reports_it() -> None:
    """``stop_on='hierarchical'`` (issue 36), the default: the loop stops on the smaller of the bound and the
    hierarchical estimate where it computed it, or the calibrated bound on the level after (the bound times the ratio
    of the two there); the answer and the last level carry what it read (NaN on the levels where the loop did not
    compute the one or form the other, and always with ``stop_on='bound'``), and end on fewer unknowns than the bound
    at the same tol; an unknown name is refused."""
    out = off_centre().solve_adaptive(tol=0.05)
    assert out.stop == "tolerance"
    levels = out.levels
    for before, level in zip(levels, levels[1:]):
        est = level.estimate
        sharp, calibrated = est["traction_hierarchical_relative"], est["traction_calibrated_relative"]
        # The level after one estimated below its bound carries the calibrated bound, and no other does.
        calibrating = np.isfinite(before.estimate["traction_hierarchical_relative"]) and \
            before.relative < before.estimate["traction_relative"]
        assert np.isfinite(calibrated) == calibrating
        if np.isfinite(sharp):
            assert level.relative == min(sharp, est["traction_relative"]) and est["traction_hierarchical"] > 0
        elif np.isfinite(calibrated):
            ratio = before.relative / before.estimate["traction_relative"]
            assert np.isfinite(before.estimate["traction_hierarchical_relative"]) and ratio < 1
            assert calibrated == pytest.approx(ratio * est["traction_relative"], rel=1e-12)
            assert level.relative == min(calibrated, est["traction_relative"])
    last = out.solution.report.estimate
    read = last["traction_hierarchical_relative"]
    read = read if np.isfinite(read) else last["traction_calibrated_relative"]
    assert 0 < levels[-1].relative == min(read, last["traction_relative"]) <= 0.05
    assert any(np.isfinite(lv.estimate["traction_calibrated_relative"]) for lv in levels)
    bound = off_centre().solve_adaptive(tol=0.05, stop_on="bound")
    assert np.isnan(bound.solution.report.estimate["traction_hierarchical_relative"])
    assert bound.problem.n_free > 2 * out.problem.n_free
    with pytest.raises(tribo.SettingsError, match="hierarchical"):
        off_centre().solve_adaptive(stop_on="sharpest")  # type: ignore[arg-type]


def test_a_history_stops_on_the_hierarchical_estimate() -> None:
    """A loading history stops on the hierarchical estimate as a static solve does: the levels where the loop
    computed it read the smaller of it and the bound, every step of the history handed back carries its own or,
    on the level after an estimated one, the calibrated bound, and the run ends on fewer unknowns than the same run
    stopping on the bound."""
    shift = [0.0, 0.001, 0.002]
    sharp = off_centre().solve_history_adaptive(0.01, shift, mu=0.3, tol=0.05, stop_on="hierarchical")
    bound = off_centre().solve_history_adaptive(0.01, shift, mu=0.3, tol=0.05, stop_on="bound")
    assert sharp.stop == bound.stop == "tolerance" and len(sharp.history) == 3
    estimated = [lv for lv in sharp.levels if np.isfinite(lv.estimate["traction_hierarchical_relative"])]
    assert estimated and sharp.levels[-1].relative <= 0.05
    for lv in estimated:
        est = lv.estimate
        assert lv.relative == min(est["traction_hierarchical_relative"], est["traction_relative"])
    for solution in sharp.history.solutions:
        # Estimated, or calibrated on the level after an estimated one.
        est = solution.report.estimate
        assert np.isfinite(est["traction_hierarchical_relative"]) or np.isfinite(est["traction_calibrated_relative"])
    # The per-step series carry the same (history.csv writes them).
    series = sharp.history.traction_error_hierarchical, sharp.history.traction_error_calibrated
    assert np.isfinite(series[0]).all() or np.isfinite(series[1]).all()
    for k, solution in enumerate(sharp.history.solutions):
        assert series[1][k] == pytest.approx(solution.report.estimate["traction_calibrated_relative"], nan_ok=True)
    assert sharp.problem.n_free < bound.problem.n_free
    with pytest.raises(tribo.SettingsError, match="stop_on"):
        off_centre().solve_history_adaptive(0.01, shift, mu=0.3, stop_on="sharpest")  # type: ignore[arg-type]


def test_the_enriched_answer_is_handed_back_from_python() -> None:
    """``stop_on='enriched'``: a static loop and a history hand back the answer enriched for the last
    estimated level where its own estimate meets ``tol`` and the level's does not: the last level is ``enriched``, has
    no time of its own, more unknowns than the one before, and its estimate is the answer's; the history's every step
    carries it."""
    out = off_centre().solve_adaptive(tol=0.05, stop_on="enriched")
    last, before = out.levels[-1], out.levels[-2]
    assert out.stop == "tolerance" and last.enriched and last.seconds == 0.0 and not before.enriched
    assert last.unknowns == out.problem.n_free > before.unknowns
    sharp = out.solution.report.estimate["traction_hierarchical_relative"]
    assert 0 < sharp <= 0.05 and last.relative == min(sharp, out.solution.report.estimate["traction_relative"])
    # The default stop, "hierarchical", refines on the same levels until it stops, and goes on past the level the
    # enriched answer came from (issue 36: that answer is often more accurate than asked).
    default = off_centre().solve_adaptive(tol=0.05)
    assert [lv.unknowns for lv in default.levels[:len(out.levels) - 1]] == [lv.unknowns for lv in out.levels[:-1]]
    assert len(default.levels) >= len(out.levels)
    history = off_centre().solve_history_adaptive(0.01, [0.0, 0.001], mu=0.3, tol=0.05, stop_on="enriched")
    assert history.stop == "tolerance" and history.levels[-1].enriched and history.levels[-1].seconds == 0.0
    assert history.levels[-1].unknowns == history.problem.n_free
    for solution in history.history.solutions:
        assert np.isfinite(solution.report.estimate["traction_hierarchical_relative"])


def test_all_edge_bisection_takes_fewer_levels_to_the_same_tolerance() -> None:
    """Both bisections reach the tolerance; all three edges of a marked triangle (the default) grows each level
    more, so the loop needs fewer levels (the shapes of the children are checked in the core's tests)."""
    default, one_edge = (off_centre().solve_adaptive(tol=0.1, bisection=b) for b in (None, "refinement_edge"))
    assert default.stop == one_edge.stop == "tolerance"
    assert len(default.levels) < len(one_edge.levels)


def test_a_history_adapts_and_hands_back_the_history_on_its_last_mesh() -> None:
    """Pressed, then dragged with Coulomb friction: every level solves the whole history; the history
    handed back is the one on the last mesh, and solving it again there gives the same answer."""
    problem = off_centre()
    shift = np.linspace(0.0, 0.004, 6)
    heard: list[int] = []
    out = problem.solve_history_adaptive(0.01, shift, mu=0.3, tol=0.2, progress=lambda u, r, s: heard.append(u))
    assert isinstance(out, tribo.AdaptiveHistory) and out.stop == "tolerance" and out.history.converged
    assert heard == [lv.unknowns for lv in out.levels] and out.problem.n_free == out.levels[-1].unknowns
    # Each step reads the smaller of its bound and the hierarchical estimate where the loop computed it, or the
    # calibrated bound on the level after.
    def reads(e: dict[str, float]) -> float:
        sharp = e["traction_hierarchical_relative"]
        return float(np.fmin(sharp if np.isfinite(sharp) else e["traction_calibrated_relative"], e["traction_relative"]))

    read = [reads(s.report.estimate) for s in out.history.solutions]
    assert out.levels[-1].relative == pytest.approx(max(read)) and max(read) <= 0.2
    again = out.problem.solve_history(0.01, shift, mu=0.3)
    assert np.allclose(again.tangential_force, out.history.tangential_force, rtol=1e-6, atol=1e-12)
    with pytest.raises(tribo.SettingsError, match="adapt_steps"):
        problem.solve_history_adaptive(0.01, shift, mu=0.3, on=[6])


def test_contact_edges_join_consecutive_contact_nodes() -> None:
    problem = off_centre()
    edges, nodes = problem.contact_edges, problem.contact_nodes
    assert edges.shape == (len(nodes) - 1, 2) and np.array_equal(edges[:, 0], nodes[:-1])
    points = problem.mesh.points
    assert np.all(np.diff(problem.node_abscissae) > 0) and np.all(points[edges[:, 1], 0] > points[edges[:, 0], 0])


def test_a_body_read_from_a_gmsh_file_refines(tmp_path: Path) -> None:
    """A mesh read with meshio (a Gmsh file: four triangles of the unit square, physical lines 'top'
    and 'bottom') adapts like a generated one: the edge sets are inherited by the halves, and the loop
    finds a contact zone that falls between the file's nodes."""
    from test_io import MSH22

    from tribo.io import read_mesh

    path = tmp_path / "square.msh"
    path.write_text(MSH22)
    mesh = read_mesh(path)
    problem = tribo.Problem(mesh, young=200.0, poisson=0.3, clamped="bottom", contact="top",
                            obstacle=tribo.Obstacle.circle(1.0, center=0.45), approach=0.002)
    assert problem.solve().normal_force == 0.0, "no node of the file's top edge touches"
    out = problem.solve_adaptive(tol=0.2)
    assert out.stop == "tolerance" and out.solution.normal_force > 0.0
    last = out.problem.mesh
    top = last.points[np.unique(last.edge_sets["top"])]
    assert np.allclose(top[:, 1], 1.0) and len(top) > 10, "the top edge set was refined along with the mesh"
    assert np.allclose(last.points[np.unique(last.edge_sets["bottom"])][:, 1], 0.0)


def test_a_tresca_threshold_per_dof_is_carried_to_every_level() -> None:
    """A threshold given per multiplier dof of the first T_H is the W_H function it defines on every level."""
    problem = tribo.Problem(tribo.Mesh.rectangle((-2.0, 2.0), (-2.0, 0.0), 8, 4), young=200.0, poisson=0.3,
                            clamped="bottom", contact="top", obstacle=tribo.Obstacle.circle(1.0), approach=0.01,
                            shift=0.004)
    assert problem.n_multipliers == 9
    hat = np.where(np.arange(9) == 4, 2.0, 0.0)
    out = problem.solve_adaptive(threshold=hat, tol=1e-6, max_unknowns=5000, stop_on="bound")
    assert out.stop == "max_unknowns" and out.solution.report.converged and len(out.levels) > 3
    s = out.solution
    middle = 0.5 * (s.multiplier_abscissae[0] + s.multiplier_abscissae[-1])
    expected = 2.0 * np.maximum(0.0, 1.0 - np.abs(s.multiplier_abscissae - middle) / 0.5)
    np.testing.assert_allclose(s.friction_threshold, expected, atol=1e-12)
