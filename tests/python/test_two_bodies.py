"""Two elastic bodies from Python: ``tribo.Body`` and ``Problem.two_bodies`` (the core's ``tribo::pair``).

The Rust tests (``crates/tribo/tests/integration/two_bodies.rs``) hold the method's checks (patch test,
action and reaction, the rigid limit, two-body Hertz); these check what Python hands over and back.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import tribo


def stacked(lower_secondary: bool = True, space: str = "P1") -> tuple[tribo.Problem, float]:
    """Two blocks of different materials on non-matching meshes, pressed 0.01 in uniaxial strain (rollers
    on the sides): the pressure is 0.01 / (h1/M1 + h2/M2), M the plane-strain P-wave modulus."""
    rollers = [tribo.Support.roller("left"), tribo.Support.roller("right")]
    lower = tribo.Body("lower", tribo.Mesh.rectangle((0.0, 2.0), (-1.0, 0.0), 5, 3, diagonal="alternating"),
                       young=100.0, poisson=0.3, supports=[*rollers, tribo.Support.roller("bottom")])
    upper = tribo.Body("upper", tribo.Mesh.rectangle((0.0, 2.0), (0.0, 0.5), 7, 2), young=300.0, poisson=0.2,
                       supports=[*rollers, tribo.Support.displacement("top", y=-0.01)])
    sides = ("lower.top", "upper.bottom") if lower_secondary else ("upper.bottom", "lower.top")
    problem = tribo.Problem.two_bodies(lower, upper, secondary=sides[0], primary=sides[1], space=space)  # type: ignore[arg-type]

    def modulus(e: float, nu: float) -> float:
        return e * (1 - nu) / ((1 + nu) * (1 - 2 * nu))

    return problem, 0.01 / (1.0 / modulus(100.0, 0.3) + 0.5 / modulus(300.0, 0.2))


@pytest.mark.parametrize("lower_secondary", [True, False])
@pytest.mark.parametrize("space", ["P0", "P1"])
def test_stacked_blocks_pass_the_patch_test(lower_secondary: bool, space: str) -> None:
    problem, p = stacked(lower_secondary, space)
    assert problem.primary == ("upper.bottom" if lower_secondary else "lower.top")
    assert [name for name, _, _ in problem.bodies] == ["lower", "upper"]
    (_, lo, _), (_, up, _) = problem.bodies
    assert lo[0] == 0 and lo[1] == up[0] and up[1] == problem.mesh.n_nodes
    assert lo[2] == 0 and lo[3] == up[2] and up[3] == problem.mesh.n_triangles
    assert {"lower.top", "upper.bottom", "lower.left", "upper.top"} <= set(problem.mesh.edge_sets)
    for friction in ({}, {"mu": 0.3}):
        sol = problem.solve(**friction)  # type: ignore[arg-type]
        assert sol.report.status == "converged"
        np.testing.assert_allclose(sol.lambda_n, p, rtol=1e-10)
        np.testing.assert_allclose(sol.stress[:, 1], -p, rtol=1e-10)
        assert np.abs(sol.u_n).max() < 1e-12 and sol.normal_force == pytest.approx(2.0 * p, rel=1e-10)
    # Action and reaction: the supports of the two bodies carry equal and opposite forces.
    sol = problem.solve(mu=0.3)
    ry = sol.reactions[:, 1]
    assert ry[lo[0]:lo[1]].sum() == pytest.approx(-ry[up[0]:up[1]].sum(), rel=1e-12)


def test_a_two_body_solution_is_written_and_read_back(tmp_path: Path) -> None:
    import meshio

    problem, _ = stacked()
    sol = problem.solve(mu=0.3)
    files = tribo.write_vtu(tmp_path / "two.vtu", problem, sol)
    back = meshio.read(files[0])
    assert len(back.points) == problem.mesh.n_nodes and len(back.cells_dict["triangle"]) == problem.mesh.n_triangles
    np.testing.assert_allclose(back.point_data["displacement"][:, :2], sol.displacement, atol=1e-15)
    # Cell data 'body' tells the bodies apart (ParaView's Threshold on it shows one body).
    body = back.cell_data["body"][0]
    (_, lo, _), (_, up, _) = problem.bodies
    assert (body[lo[2]:lo[3]] == 0).all() and (body[up[2]:up[3]] == 1).all()


def test_bad_pairs_are_errors() -> None:
    problem, _ = stacked()
    mesh = tribo.Mesh.rectangle((0.0, 2.0), (0.0, 1.0), 4, 2)
    a = tribo.Body("a", tribo.Mesh.rectangle((0.0, 2.0), (-1.0, 0.0), 4, 2), young=1.0, poisson=0.3, clamped="bottom")
    b = tribo.Body("b", mesh, young=1.0, poisson=0.3, clamped="top")
    with pytest.raises(tribo.ContactGeometryError, match="no body named 'c'") as info:
        tribo.Problem.two_bodies(a, b, secondary="c.top", primary="b.bottom")
    assert info.value.kind == "ContactPair"
    with pytest.raises(tribo.ContactGeometryError, match="does not cover"):
        short = tribo.Body("b", tribo.Mesh.rectangle((0.5, 2.0), (0.0, 1.0), 4, 2), young=1.0, poisson=0.3, clamped="top")
        tribo.Problem.two_bodies(a, short, secondary="a.top", primary="b.bottom")
    with pytest.raises(tribo.MeshError, match="side"):
        tribo.Problem.two_bodies(a, b, secondary="a.top", primary="b.side")
    with pytest.raises(tribo.SettingsError, match="traction on 'top'"):
        tribo.Body("b", mesh, young=1.0, poisson=0.3, clamped="top", tractions={"top": (1.0, 2.0, 3.0)})._compiled()
    with pytest.raises(tribo.SettingsError, match="per body") as info:
        tribo.Problem([a._compiled(), b._compiled()], contact="a.top", primary="b.bottom", young=1.0)
    assert info.value.kind == "BadSettingValue"
    with pytest.raises(TypeError, match="two tribo.Body"):
        tribo.Problem.two_bodies(a, mesh, secondary="a.top", primary="b.bottom")  # type: ignore[arg-type]
    # A punch held in y only by the contact, with nothing pressing it down: its position is undetermined.
    punch = tribo.Body("punch", mesh, young=1.0, poisson=0.3, supports=tribo.Support.roller("left"))
    free = tribo.Problem.two_bodies(a, punch, secondary="a.top", primary="punch.bottom")
    with pytest.raises(tribo.ContactGeometryError, match="body 'punch' is held only by the contact.*translation") as info:
        free.solve()
    assert info.value.kind == "HeldOnlyByContact" and "undetermined" in info.value.details["what"]
    with pytest.raises(tribo.ContactGeometryError, match="spans of the two bodies"):
        problem.on_mesh(problem.mesh, problem.multiplier_mesh, [[0, 1, 0, 1]])


def test_a_punch_pushed_by_a_load_is_held_by_the_contact() -> None:
    """The upper block has no support in y: a uniform pressure on its top pushes it onto the lower block,
    and the contact holds it (uniaxial strain with rollers on the sides: the pressure is the load)."""
    rollers = [tribo.Support.roller("left"), tribo.Support.roller("right")]
    lower = tribo.Body("lower", tribo.Mesh.rectangle((0.0, 2.0), (-1.0, 0.0), 5, 3), young=100.0, poisson=0.3,
                       supports=[*rollers, tribo.Support.roller("bottom")])
    upper = tribo.Body("upper", tribo.Mesh.rectangle((0.0, 2.0), (0.0, 0.5), 7, 2), young=300.0, poisson=0.2,
                       supports=rollers, tractions={"top": (0.0, -0.5)})
    problem = tribo.Problem.two_bodies(lower, upper, secondary="lower.top", primary="upper.bottom")
    for friction in ({}, {"mu": 0.3}):
        sol = problem.solve(**friction)  # type: ignore[arg-type]
        assert sol.report.converged and sol.report.qp_methods[-1] == "clarabel"
        np.testing.assert_allclose(sol.lambda_n, 0.5, rtol=1e-9)
        assert sol.normal_force == pytest.approx(1.0, rel=1e-9)


def coarse_pair() -> tribo.Problem:
    """Two-body Hertz (steel under aluminium, a parabolic gap of radius 1) on coarse uniform meshes of
    both blocks: no node of either side lies under the contact zone."""
    lower = tribo.Body("lower", tribo.Mesh.rectangle((-2.0, 2.0), (-2.0, 0.0), 8, 4), young=200.0, poisson=0.3,
                       clamped="bottom")
    upper = tribo.Body("upper", tribo.Mesh.rectangle((-2.0, 2.0), (0.0, 1.0), 8, 2, diagonal="left"), young=70.0,
                       poisson=0.33, supports=tribo.Support.displacement("top", x=0.0, y=-0.01))
    return tribo.Problem.two_bodies(lower, upper, secondary="lower.top", primary="upper.bottom",
                                    gap=tribo.Obstacle.parabola(1.0))


def test_two_bodies_adapt_and_hand_back_each_level() -> None:
    """The loop refines both bodies (the Rust test checks the accuracy against two-body Hertz); every level's
    problem, rebuilt in Python from its joined mesh and the bodies' spans, is the one the loop solved."""
    out = coarse_pair().solve_adaptive(tol=0.15)
    assert out.stop == "tolerance" and out.solution.report.converged
    assert [name for name, _, _ in out.problem.bodies] == ["lower", "upper"]
    for k in (0, len(out.levels) // 2, len(out.levels) - 1):
        level = out.level_problem(k)
        assert (level.n_free, level.n_multipliers) == (out.levels[k].unknowns, out.levels[k].multipliers)
        assert [list(s) for _, s, _ in level.bodies] == [list(s) for s in out.meshes[k][2]]
    again = out.level_problem(len(out.levels) - 1).solve()
    scale = np.max(out.solution.lambda_n)
    assert np.max(np.abs(again.lambda_n - out.solution.lambda_n)) <= 1e-9 * scale
    # Each body keeps its reaction balance: the two supports carry equal and opposite vertical forces.
    (_, lo, _), (_, up, _) = out.problem.bodies
    ry = again.reactions[:, 1]
    assert ry[lo[0]:lo[1]].sum() == pytest.approx(-ry[up[0]:up[1]].sum(), rel=1e-9)


def test_a_two_body_history_adapts() -> None:
    """Pressed, then sheared through the upper block's top with Coulomb friction: every level solves the
    whole history on both refined bodies. Stopping on the bound, whose last mesh is fine enough that the
    shear of the pressing step (from the meshes' asymmetry) is below 1e-3 of the sliding limit."""
    out = coarse_pair().solve_history_adaptive(displacements={"upper.top.x": [0.0, 0.0005, 0.001]}, mu=0.3,
                                               tol=0.3, stop_on="bound")
    assert out.stop == "tolerance" and out.history.status == "converged" and len(out.history.solutions) == 3
    assert out.levels[-1].unknowns > 10 * out.levels[0].unknowns
    # Pressing alone shears only through the dissimilar materials and the meshes' asymmetry; then the
    # friction force grows with the shear, below sliding.
    q = [s.tangential_force for s in out.history.solutions]
    limit = 0.3 * out.history.solutions[-1].normal_force
    assert abs(q[0]) < 1e-3 * limit and q[0] < q[1] < q[2] < limit


def shear_pair(h_min: float = 0.01) -> tribo.Problem:
    """The two-body Hertz blocks of study 9: the upper block held by its top only, through a prescribed
    displacement that a history moves."""
    def mesh(y: tuple[float, float], side: str) -> tribo.Mesh:
        return tribo.Mesh.graded_rectangle((-2.0, 2.0), y, side=side, segment=(-0.15, 0.15), h_max=0.5, h_min=h_min)

    lower = tribo.Body("lower", mesh((-2.0, 0.0), "top"), young=200.0, poisson=0.3, clamped="bottom")
    upper = tribo.Body("upper", mesh((0.0, 1.0), "bottom"), young=200.0, poisson=0.3,
                       supports=tribo.Support.displacement("top", x=0.0, y=0.0))
    return tribo.Problem.two_bodies(lower, upper, secondary="lower.top", primary="upper.bottom",
                                    gap=tribo.Obstacle.parabola(1.0))


def test_a_history_moves_the_bodies_through_their_supports() -> None:
    problem = shear_pair()
    assert problem.prescribed == [("upper.top.x", 0.0), ("upper.top.y", 0.0)]
    (_, lo, n_lo), (_, up, n_up) = problem.bodies
    assert n_lo + n_up == problem.n_free and n_lo > n_up > 0
    x = np.r_[0.0, 0.0, np.linspace(0.001, 0.004, 4)]
    h = problem.solve_history(displacements={"upper.top.x": x, "upper.top.y": np.r_[-0.005, -0.01, [-0.01] * 4]},
                              mu=0.3)
    assert h.converged and len(h) == 6
    assert list(h.displacements) == ["upper.top.x", "upper.top.y"]
    np.testing.assert_array_equal(h.displacements["upper.top.x"], x)
    with pytest.raises(ValueError):
        h.displacements["upper.top.x"][0] = 1.0  # read-only, as every array of a result
    # The top of the upper block is where the step put it; the stick zone shrinks as the shear grows.
    top = np.flatnonzero(problem.mesh.points[:, 1] == 1.0)
    for k, sol in enumerate(h.solutions):
        np.testing.assert_allclose(sol.displacement[top], [[x[k], h.displacements["upper.top.y"][k]]] * len(top))
    stick = h.stick_zone[2:, 1] - h.stick_zone[2:, 0]
    assert np.all(np.diff(stick) < 0) and 0 < h.tangential_force[-1] < 0.3 * h.normal_force[-1]
    # A component left out keeps its value: pressing only, the tangential force stays 0.
    pressed = problem.solve_history(displacements={"upper.top.y": [-0.005, -0.01]}, mu=0.3)
    assert np.allclose(pressed.tangential_force, 0.0, atol=1e-12) and pressed.normal_force[-1] > 0


def test_bad_moves_are_errors() -> None:
    problem = shear_pair(0.04)
    with pytest.raises(tribo.SettingsError, match="no prescribed component 'upper.top.z'.*upper.top.x, upper.top.y"):
        problem.solve_history(displacements={"upper.top.z": 0.1})
    with pytest.raises(tribo.SettingsError, match="upper.top.y has 2 values, but the history has 3 steps"):
        problem.solve_history(displacements={"upper.top.x": [0, 1, 2], "upper.top.y": [0, 1]})
    # Two bodies move only through their supports: an obstacle motion is refused by the core, naming the step.
    with pytest.raises(tribo.TriboError, match="step 1.*prescribed displacements") as info:
        problem.solve_history(approach=[0.0, 0.01])
    assert info.value.kind == "BadLoadStep"
    # A value that contradicts another support where they meet.
    one = tribo.Problem(tribo.Mesh.rectangle((0.0, 2.0), (0.0, 1.0), 8, 4), young=1.0, poisson=0.3, contact="top",
                        clamped="left", supports=tribo.Support.displacement("bottom", x=0.0, y=0.0))
    with pytest.raises(tribo.TriboError, match="step 0") as info:
        one.solve_history(displacements={"bottom.y": 0.01})
    assert info.value.kind == "BadLoadStep"
    no = tribo.Problem(tribo.Mesh.rectangle((0.0, 2.0), (0.0, 1.0), 8, 4), young=1.0, poisson=0.3, contact="top",
                       clamped="bottom")
    with pytest.raises(tribo.SettingsError, match="none: the problem has no prescribed displacement"):
        no.solve_history(0.0, 0.0, displacements={"bottom.y": 0.01})


def test_the_pressure_plot_compares_two_bodies_with_their_combined_modulus() -> None:
    """Between two bodies the Hertz reference of the pressure plot is that of 1/E* = Σ (1 − ν_i²)/E_i."""
    import math

    import tribo.plot

    out = coarse_pair().solve_adaptive(tol=0.3)  # the coarse meshes alone see no contact (a weak gap)
    problem, sol = out.problem, out.solution
    ref = tribo.plot.hertz_pressure(problem, sol)
    assert ref is not None
    e_star = 1.0 / ((1.0 - 0.3**2) / 200.0 + (1.0 - 0.33**2) / 70.0)
    a = math.sqrt(4.0 * sol.normal_force * 1.0 / (math.pi * e_star))
    assert ref[0][-1] - ref[0][0] == pytest.approx(2.0 * a, rel=1e-12)
