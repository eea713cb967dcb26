"""What a reader gets back: conventions stated, global force components, warnings on doubtful scenes,
the condensation's progress, and the Tresca states explained."""

from __future__ import annotations

import json
import warnings
from pathlib import Path

import numpy as np
import pytest

import tribo
from conftest import hertz_problem
from tribo.checks import (
    MAX_APPROACH_FRACTION,
    MAX_POISSON,
    MAX_SHIFT_FRACTION,
    MIN_CONTACT_DOFS,
    check_solution,
    conventions,
    warn_solution,
)
from tribo.cli import main
from tribo.scene import demo_scene_path, load_scene, scene_path


def square(n: int = 8, **kw: object) -> tribo.Problem:
    """A unit square clamped at the bottom, pressed on top by a flat obstacle (keywords override)."""
    args: dict[str, object] = dict(
        young=1.0, poisson=0.3, clamped="bottom", contact="top", obstacle=tribo.Obstacle.flat(), approach=0.01
    )
    args.update(kw)
    return tribo.Problem(tribo.Mesh.rectangle((0.0, 1.0), (0.0, 1.0), n, n), **args)  # type: ignore[arg-type]


def test_contact_force_is_global(hertz: tribo.Problem) -> None:
    s = hertz.solve(mu=0.3)
    n, t = np.array(hertz.contact_normal), np.array(hertz.contact_tangent)
    np.testing.assert_allclose(s.contact_force, -(s.normal_force * n + s.tangential_force * t), rtol=1e-15)
    # The obstacle pushes down (−y) and, shifted toward −x (t = (−1, 0), s > 0), drags the body toward −x.
    assert s.contact_force[1] < 0 and s.contact_force[0] < 0
    assert s.obstacle_motion == pytest.approx((-hertz.shift, -hertz.approach))
    np.testing.assert_allclose(s.stress_zz, hertz.poisson * (s.stress[:, 0] + s.stress[:, 1]))
    np.testing.assert_array_equal(s.current_gap, s.gap - s.u_n)


def test_good_scene_has_no_warnings(hertz: tribo.Problem) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        problem, solution = load_scene(demo_scene_path()).solve()
    assert check_solution(problem, solution) == []
    # The shipped Hertz scene (h_min = 0.04) shifted has 4 dofs in contact, where λ_n is about a quarter off the
    # Hertz pressure (the Python guide measures it): the warning is right there.
    assert "only 4 multiplier dofs" in check_solution(hertz, hertz.solve(mu=0.3))[0]


def test_warning_nothing_touches() -> None:
    problem = square(approach=-0.01)
    s = problem.solve()
    assert s.normal_force == 0
    with pytest.warns(tribo.SceneWarning, match=r"nothing touches.*smallest gap after the approach 0.01"):
        reasons = warn_solution(problem, s)
    assert len(reasons) == 1


def test_warning_few_contact_dofs() -> None:
    # A parabola of radius 1 pushed 0.002 in: half-width ≈ √(2Rδ) ≈ 0.06, a cell or two of a 16 × 16 mesh.
    problem = square(16, obstacle=tribo.Obstacle.parabola(1.0, 0.5), approach=0.002)
    s = problem.solve()
    k = int(np.count_nonzero(s.states != 0))
    assert 0 < k < MIN_CONTACT_DOFS
    with pytest.warns(tribo.SceneWarning, match=f"only {k} multiplier dofs? \\(fewer than {MIN_CONTACT_DOFS}\\)"):
        warn_solution(problem, s)
    # Pushed further on a finer mesh, the contact zone holds enough dofs.
    fine = square(64, obstacle=tribo.Obstacle.parabola(1.0, 0.5), approach=0.02)
    assert check_solution(fine, fine.solve()) == []


def test_warning_large_approach() -> None:
    approach = 2 * MAX_APPROACH_FRACTION  # the body is 1 high along n
    problem = square(16, approach=approach)
    with pytest.warns(tribo.SceneWarning, match=r"approach 0.1 is 10 % of the body's extent along n \(1\)"):
        warn_solution(problem, problem.solve())
    small = square(16, approach=0.5 * MAX_APPROACH_FRACTION)
    assert check_solution(small, small.solve()) == []


def test_warning_contact_side_held_by_a_support(tmp_path: Path) -> None:
    """The primary side of two bodies clamped: it cannot move, and the contact force is what the supports
    allow (the core refuses a support on the secondary side, Γ_C). Supports meeting the contact sides at
    their ends (the two-body scene as shipped) are no reason."""
    text = scene_path("hertz_two_bodies").read_text(encoding="utf-8")
    held = text.replace('{ kind = "displacement", edge_set = "left", x = 0.0 },',
                        '{ kind = "displacement", edge_set = "left", x = 0.0 }, { kind = "clamp", edge_set = "bottom" },')
    assert held != text
    path = tmp_path / "held.toml"
    path.write_text(held, encoding="utf-8")
    problem = load_scene(path).build()
    reasons = check_solution(problem, problem.solve())
    assert [r for r in reasons if "contact side 'upper.bottom' is also held by a support at" in r], reasons
    shipped = load_scene(scene_path("hertz_two_bodies")).build()
    assert not [r for r in check_solution(shipped, shipped.solve()) if "held by a support" in r]


def test_warning_contact_zone_cut_by_the_end_of_the_contact_side() -> None:
    """A flat obstacle pressed on the middle half of a top face: the zone fills the contact side and would
    spread past its ends, where the face goes on. The whole top face pressed ends at the body's corners:
    no reason. A cylinder whose zone stops short of the ends: none either."""
    mesh = tribo.Mesh.rectangle((0.0, 2.0), (0.0, 1.0), 16, 8)
    x = mesh.points[:, 0]
    top = np.asarray(mesh.edge_sets["top"])
    middle = top[(x[top] >= 0.5 - 1e-12).all(axis=1) & (x[top] <= 1.5 + 1e-12).all(axis=1)]
    cut = tribo.Mesh(mesh.points, mesh.triangles, {**mesh.edge_sets, "middle": middle})
    args: dict[str, object] = dict(young=1.0, poisson=0.3, clamped="bottom", obstacle=tribo.Obstacle.flat(), approach=0.01)
    problem = tribo.Problem(cut, contact="middle", **args)  # type: ignore[arg-type]
    reasons = check_solution(problem, problem.solve())
    ends = [r for r in reasons if "reaches the end of the contact side 'middle'" in r]
    assert len(ends) == 2 and "ξ = 0.5" in ends[0] + ends[1] and "ξ = 1.5" in ends[0] + ends[1], reasons
    whole = tribo.Problem(cut, contact="top", **args)  # type: ignore[arg-type]
    assert check_solution(whole, whole.solve()) == []
    args["obstacle"] = tribo.Obstacle.parabola(1.0, 1.0)
    curved = tribo.Problem(cut, contact="middle", **args)  # type: ignore[arg-type]
    solution = curved.solve()
    assert solution.states[0] == 0 and solution.states[-1] == 0
    assert not [r for r in check_solution(curved, solution) if "reaches the end" in r]


def test_warning_nearly_incompressible() -> None:
    problem = square(16, poisson=0.4999, formulation="displacement")
    with pytest.warns(tribo.SceneWarning, match=r"ν = 0.4999 is close to ½: P1 triangles lock \(λ/μ = 5e\+03\)"):
        warn_solution(problem, problem.solve())
    below = square(16, poisson=MAX_POISSON - 0.01)
    assert not [r for r in check_solution(below, below.solve()) if "close to ½" in r]
    # The default formulation ('auto') is mixed from ν = 0.49 in plane strain: nothing locks, nothing is said.
    chosen = square(16, poisson=0.4999)
    assert chosen.formulation == "mixed" and not [r for r in check_solution(chosen, chosen.solve()) if "lock" in r]


def test_warning_classic_method_with_a_multiplier_mesh_finer_than_the_fe_edges() -> None:
    """γ0 = 0 with T_H twice as fine as the FE edges (study 1a's checkerboard scene): more multiplier dofs across the
    contact zone than FE nodes under them, so H is singular there; stabilized, or with H = h, no warning."""
    mesh = tribo.Mesh.rectangle((-2.0, 2.0), (-2.0, 0.0), 80, 40)
    def reasons(ratio: float, **solve: float) -> list[str]:
        problem = tribo.Problem(mesh, young=200.0, poisson=0.3, clamped="bottom", contact="top",
                                obstacle=tribo.Obstacle.circle(1.0), approach=0.05, multiplier_ratio=ratio)
        return [r for r in check_solution(problem, problem.solve(**solve)) if "classic method" in r]
    said = reasons(0.5, gamma0=0.0)
    assert len(said) == 1 and "11 multiplier dofs across the contact zone over 7 FE nodes" in said[0], said
    assert reasons(0.5) == [] and reasons(1.0, gamma0=0.0) == []


def test_warning_shift_large_for_small_sliding(hertz: tribo.Problem) -> None:
    """A cylinder shifted by a third of its contact width: the answer's zone stays where it was. The demo's
    shift (3 % of the width) is no reason, nor any shift of a flat obstacle."""
    width = hertz.solve(mu=0.3).contact_width
    moved = hertz_problem(shift=3 * MAX_SHIFT_FRACTION * width)
    with pytest.warns(tribo.SceneWarning, match=r"the shift s = \S+ is \S+ % of the contact width .* small sliding"):
        warn_solution(moved, moved.solve(mu=0.3))
    flat = square(16, shift=0.5)
    assert not [r for r in check_solution(flat, flat.solve(mu=0.3)) if "shift" in r]


def test_scene_solve_and_cli_warn(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    text = demo_scene_path().read_text(encoding="utf-8").replace("approach = 0.01", "approach = -0.01")
    path = tmp_path / "apart.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.warns(tribo.SceneWarning, match="nothing touches"):
        load_scene(path).solve()
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the CLI reports them as lines, not as Python warnings
        assert main(["-q", "run", str(path), "--out", str(tmp_path / "o"), "--no-plots"]) == 0
    err = capsys.readouterr().err
    assert [line for line in err.splitlines() if line.startswith("tribo: warning: nothing touches")], err
    summary = json.loads((tmp_path / "o" / "summary.json").read_text(encoding="utf-8"))
    assert len(summary["warnings"]) == 1 and summary["warnings"][0].startswith("nothing touches")


def test_summary_states_the_conventions(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["-q", "demo", "--out", str(tmp_path), "--no-plots"]) == 0
    out = capsys.readouterr().out
    assert "the obstacle moved toward −x" in out and "(Fx, Fy) = (" in out
    s = json.loads((tmp_path / "summary.json").read_text(encoding="utf-8"))
    assert s["normal"] == [0.0, 1.0] and s["tangent"] == [-1.0, 0.0]
    assert s["obstacle_motion"] == pytest.approx([-0.004, -0.01])
    fx, fy = s["contact_force"]
    assert fy == pytest.approx(-s["normal_force"]) and fx == pytest.approx(s["tangential_force"])
    c = s["conventions"]
    assert c["xi"] == "abscissa ξ along Γ_C, increasing with x (along −t)"
    assert c["shift"] == "s = 0.004 along t = (-1, 0): the obstacle moved toward −x"
    for key in ("n", "t", "lambda_n", "lambda_t", "tangential_force", "contact_force", "slip", "current_gap"):
        assert c[key]


def test_a_history_step_states_its_own_shift() -> None:
    """A drag in a history moves the obstacle by each step's shift: the conventions (summary.json, the CSV
    headers) and the tangential plot state that shift, not the problem's (which said "no shift" while the
    obstacle had moved by (-0.03, -0.01))."""
    problem = hertz_problem()
    assert problem.shift == 0.0
    history = problem.solve_history(0.01, [0.0, 0.003], mu=0.3)
    last = history.solutions[-1]
    assert last.obstacle_motion == pytest.approx((-0.003, -0.01))
    said = conventions(problem, last)["shift"]
    assert said == "s = 0.003 along t = (-1, 0): the obstacle moved toward −x", said
    assert conventions(problem, history.solutions[0])["shift"] == "no shift"


def test_on_phase_reports_the_condensation(hertz: tribo.Problem) -> None:
    events: list[tuple[str, object]] = []
    s = hertz.solve(
        mu=0.3,
        on_phase=lambda phase, seconds: events.append((phase, seconds)),
        progress=lambda *a: events.append(("qp", a[0])),
    )
    assert s.report.status == "converged"
    assert events[0][0] == "condensation" and isinstance(events[0][1], float) and events[0][1] >= 0
    assert [e[0] for e in events[1:]] == ["qp"] * (s.report.iterations + 1)
    stopped = hertz.solve(mu=0.3, on_phase=lambda phase, seconds: False, progress=lambda *a: pytest.fail("a QP ran"))
    assert stopped.report.status == "interrupted" and stopped.report.interrupted_iteration == 0
    assert not stopped.lambda_n.any()

    def boom(phase: str, seconds: float) -> None:
        raise ZeroDivisionError(phase)

    with pytest.raises(ZeroDivisionError, match="condensation"):
        hertz.solve(on_phase=boom)
    with pytest.raises(tribo.SettingsError, match="on_phase must be a callable"):
        hertz.solve(on_phase=3)  # type: ignore[arg-type]


def test_tresca_states_are_explained() -> None:
    """With a given threshold λ_t sits at ±threshold where nothing touches: those dofs are 'separation',
    and the plot's legend and the conventions say why λ_t is at its bound there."""
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from tribo import plot
    from tribo.checks import conventions

    problem = hertz_problem(shift=0.004)
    s = problem.solve(threshold=1e-3)
    apart = s.states == 0
    at_bound = np.isclose(np.abs(s.lambda_t), s.friction_threshold, rtol=1e-6)
    assert (apart & at_bound).any(), "Tresca: λ_t at ±threshold without contact"
    ax = plot.tangential(problem, s)
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert any(label.startswith("separation (Tresca") for label in labels), labels
    assert "toward −x" in ax.get_title()
    assert "not slip" in conventions(problem, s)["states"]
    plt.close("all")


def test_reprs_format_numbers_for_people(hertz: tribo.Problem) -> None:
    s = hertz.solve(mu=0.3, gamma0=0.0)
    assert "gamma0=0," in repr(s.report) and "e0" not in repr(s.report)
    assert "gamma0_bound=9.29e-4)" in repr(hertz)
    assert f"normal_force={s.normal_force:.6g}," in repr(s)
    # More digits than a double holds print 17; a precision beyond what Rust's formatter takes is no panic.
    from tribo._tribo import format_number

    assert format_number(1.0 / 3.0, 70000) == format_number(1.0 / 3.0, 17) == "0.33333333333333331"


def test_recovered_stress_is_written_and_plotted(hertz: tribo.Problem, tmp_path: Path) -> None:
    """The recovered nodal stress is a mean of the cell stresses around each node (so within their
    range), its von Mises is written as VTU point data (read back with meshio), and the von Mises plot
    shows it by default (the cell stress with recovered=False)."""
    import matplotlib

    matplotlib.use("Agg")
    import meshio

    from tribo.io import write_vtu
    from tribo.plot import von_mises

    s = hertz.solve(mu=0.3)
    n = hertz.mesh.n_nodes
    assert s.nodal_stress.shape == (n, 3) and s.nodal_von_mises.shape == (n,)
    assert np.all(s.nodal_stress.min(axis=0) >= s.stress.min(axis=0) - 1e-12)
    assert np.all(s.nodal_stress.max(axis=0) <= s.stress.max(axis=0) + 1e-12)
    write_vtu(tmp_path / "r.vtu", hertz, s)
    body = meshio.read(tmp_path / "r.vtu")
    np.testing.assert_allclose(body.point_data["von_mises_recovered"], s.nodal_von_mises)
    np.testing.assert_allclose(body.point_data["stress_recovered"], s.nodal_stress)
    assert "recovered" in von_mises(hertz, s).figure.axes[-1].get_ylabel()
    assert "per cell" in von_mises(hertz, s, recovered=False).figure.axes[-1].get_ylabel()
