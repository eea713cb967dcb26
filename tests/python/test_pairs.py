"""Several contact pairs through Python: a block pressed by a punch onto a foundation, each pair with its own
obstacle; its parts of the solution; what takes one pair today refuses several with a typed error."""

from __future__ import annotations

import json
import tomllib
from pathlib import Path

import numpy as np
import pytest

import tribo
from tribo.run import run_scene
from tribo.scene import load_scene, parse_scene, scene_path

PUNCH = tribo.Obstacle.disc((0.0, 1.5), 0.5)
FOUNDATION = tribo.Obstacle.line((0.0, 0.0), (0.0, 1.0))


def block(n: int = 12, **keywords: object) -> tribo.Problem:
    """The half block [0, ½] × [0, 1] (a roller on its axis), the punch on its top, the foundation under it."""
    mesh = tribo.Mesh.rectangle((0.0, 0.5), (0.0, 1.0), n, 2 * n)
    arguments = dict(young=1.0, poisson=0.3, contact="top", supports=[tribo.Support.roller("left")], obstacle=PUNCH,
                     approach=0.02, pairs=[tribo.Pair("bottom", FOUNDATION)])
    return tribo.Problem(mesh, **{**arguments, **keywords})


def test_a_block_between_a_punch_and_a_foundation_is_the_block_on_a_roller() -> None:
    """With γ0 = 0 the foundation, touching everywhere, acts as a roller: the problem of the punch alone on a block
    whose bottom is a roller has the same displacement and punch pressure; the foundation takes the punch's force."""
    two = block()
    assert two.pairs == ["top", "bottom"]
    one = block(pairs=None, supports=[tribo.Support.roller("left"), tribo.Support.roller("bottom")])
    s2, s1 = two.solve(gamma0=0.0), one.solve(gamma0=0.0)
    assert s2.report.converged and s1.report.converged
    top, bottom = s2.pairs
    assert (top.name, bottom.name) == ("top", "bottom")
    assert isinstance(top, tribo.PairResult) and s2.lambda_n.size == bottom.multipliers.stop
    assert np.all(s2.lambda_n[bottom.multipliers] > 0.0), "the foundation touches everywhere"
    scale = np.abs(s1.lambda_n).max()
    assert np.abs(s2.lambda_n[top.multipliers] - s1.lambda_n).max() <= 1e-6 * scale
    assert np.abs(s2.displacement - s1.displacement).max() <= 1e-6 * np.abs(s1.displacement).max()
    # The block is held vertically by the two contacts alone: their vertical forces cancel.
    assert abs(top.contact_force[1] + bottom.contact_force[1]) <= 1e-6 * top.normal_force
    assert s2.normal_force == pytest.approx(top.normal_force + bottom.normal_force, rel=1e-12)
    # Each pair's fields are its slices; its contact zone its own side's (the foundation's: all of it).
    assert s2.node_abscissae[bottom.nodes].size == 13 and s2.sigma_n[bottom.edges].size == 12
    assert bottom.contact_width == pytest.approx(0.5) and 0.0 < top.contact_width < 0.5
    assert s2.contact_width == top.contact_width


def test_the_checks_name_the_pair() -> None:
    """A further pair whose obstacle never reaches its side is said by name (without the first pair's approach)."""
    wall = tribo.Obstacle.line((0.6, 0.0), (-1.0, 0.0))
    problem = block(n=8, pairs=[("bottom", FOUNDATION), tribo.Pair("right", wall)])
    reasons = tribo.check_solution(problem, problem.solve())
    assert any(r.startswith("pair 'right': nothing touches") and "approach 0.02" not in r for r in reasons), reasons
    assert not any(r.startswith("pair 'bottom': nothing touches") for r in reasons), reasons


def test_what_takes_one_pair_refuses_several() -> None:
    problem = block(n=6)
    with pytest.raises(tribo.ContactGeometryError, match="on_mesh"):
        block(n=6, multiplier_ratio=2.0).on_mesh(problem.mesh, problem.multiplier_mesh)
    with pytest.raises(tribo.MeshError, match="nowhere"):
        block(n=6, pairs=[("nowhere", None, None, None)])
    with pytest.raises(TypeError, match="a contact pair must be a tribo.Pair"):
        block(n=6, pairs=[42])
    with pytest.raises(tribo.ContactGeometryError, match="obstacle must be a tribo.Obstacle"):
        block(n=6, pairs=[tribo.Pair("bottom", "flat")])


def test_a_history_of_two_pairs_moves_the_first_pairs_obstacle(tmp_path: Path) -> None:
    """A history moves the punch (the first pair's obstacle), the foundation stays: frictionless, each step is the
    static solve of its approach; the history gives each pair's series by name, and history.csv each pair's columns
    (read back with pandas)."""
    import pandas as pd

    from tribo.history import write_history

    problem = block(n=8)
    approaches = [0.01, 0.02, 0.015]
    history = problem.solve_history(approach=approaches, shift=0.0, gamma0=0.0)
    assert history.converged and list(history.pairs) == ["top", "bottom"]
    for k, a in enumerate(approaches):
        static = block(n=8, approach=a).solve(gamma0=0.0)
        step = history.solution(k)
        assert np.abs(step.displacement - static.displacement).max() <= 1e-6 * np.abs(static.displacement).max()
        for name, pair in zip(history.pairs, static.pairs, strict=True):
            assert history.pairs[name]["normal_force"][k] == pytest.approx(pair.normal_force, rel=1e-6)
        assert history.normal_force[k] == pytest.approx(static.normal_force, rel=1e-6)
    bottom = history.pairs["bottom"]
    assert bottom["contact_zone"].shape == (3, 2) and np.allclose(bottom["contact_zone"], [0.0, 0.5])
    np.testing.assert_array_equal(history.contact_zone, history.pairs["top"]["contact_zone"])
    write_history(tmp_path, problem, history, plots=True)
    table = pd.read_csv(tmp_path / "history.csv", comment="#")
    assert {"top.normal_force", "bottom.normal_force", "bottom.gross_sliding"} <= set(table.columns)
    np.testing.assert_allclose(table["bottom.normal_force"], bottom["normal_force"], rtol=1e-12)
    np.testing.assert_allclose(table["normal_force"], table["top.normal_force"] + table["bottom.normal_force"], rtol=1e-12)
    assert (tmp_path / "history_loop.png").exists() and (tmp_path / "history_tractions.png").exists()


def test_two_pairs_adapt_on_the_hierarchical_estimate() -> None:
    """The adaptive loop takes several pairs and stops on the hierarchical estimate of both (or the bound, the
    smaller): the punch's pressure ends within the tolerance of the block on a roller adapted further (the same
    physics); a level's problem made again gives its answer. A two-pair solve has error bars."""
    two = block(n=4, approach=0.01).solve_adaptive(tol=0.05)
    assert two.stop == "tolerance" and len(two.levels) > 2
    sharp = [level.estimate["traction_hierarchical_relative"] for level in two.levels]
    assert any(np.isfinite(sharp)) and two.levels[-1].relative <= 0.05
    one = block(n=4, approach=0.01, pairs=None, supports=[tribo.Support.roller("left"), tribo.Support.roller("bottom")])
    reference = one.solve_adaptive(tol=0.005)
    x = np.linspace(0.0, 0.5, 2001)
    first = two.problem.pairs and two.solution.pair(0)
    mine = two.problem.evaluate_multiplier(first.lambda_n, x)
    theirs = reference.problem.evaluate_multiplier(reference.solution.lambda_n, x)
    assert np.linalg.norm(mine - theirs) <= (0.05 + 0.005) * np.linalg.norm(theirs)
    again = two.level_problem(len(two.levels) - 1).solve()
    np.testing.assert_allclose(again.lambda_n, two.solution.lambda_n, atol=1e-6 * np.abs(two.solution.lambda_n).max())
    # Sharp, not bounds: on these uniform meshes, whose punch zone spans one or two cells, the bar of P is 0.69 and
    # 0.92 times |P − P_64| (8 and 16 cells across, approach 0.02; the guide).
    barred = block(n=8).solve(error_bars=True)
    bars = [barred.report.estimate[f"{key}_error"] for key in ("normal_force", "contact_width")]
    assert all(np.isfinite(bars)) and min(bars) > 0.0

def test_each_pair_has_its_own_mu() -> None:
    """The punch dragging the block (μ = 0.5) beside a foundation of its own μ = 0: the foundation carries no
    tangential traction, and the problem is the block on a roller (γ0 = 0) with the punch's law; a pair's own μ
    needs Coulomb friction, said naming the pair; the two spellings of a pair (Pair, tuple) are one problem."""
    own = block(shift=0.0005, approach=0.01, pairs=[tribo.Pair("bottom", FOUNDATION, mu=0.0)])
    roller = block(shift=0.0005, approach=0.01, pairs=None,
                   supports=[tribo.Support.roller("left"), tribo.Support.roller("bottom")])
    s2, s1 = own.solve(mu=0.5, gamma0=0.0), roller.solve(mu=0.5, gamma0=0.0)
    top, bottom = s2.pairs
    assert (top.mu, bottom.mu, s2.mu) == (0.5, 0.0, 0.5) and s1.pairs[0].mu == 0.5
    assert abs(s1.tangential_force) > 0.05 * s1.normal_force, "the punch drags the top"
    scale = np.abs(s1.lambda_n).max()
    assert np.abs(s2.lambda_t[top.multipliers] - s1.lambda_t).max() <= 1e-6 * scale
    assert np.abs(s2.lambda_t[bottom.multipliers]).max() <= 1e-8 * scale
    tupled = block(shift=0.0005, approach=0.01, pairs=[("bottom", FOUNDATION, None, None, 0.0)]).solve(mu=0.5, gamma0=0.0)
    assert np.array_equal(tupled.lambda_t, s2.lambda_t)
    with pytest.raises(tribo.ContactGeometryError, match="'bottom': its own mu needs Coulomb friction"):
        own.solve()
    with pytest.raises(tribo.SettingsError, match="mu"):
        block(pairs=[tribo.Pair("bottom", FOUNDATION, mu=-1.0)])


def test_a_scene_of_two_pairs_runs_and_writes_each_pair(tmp_path: Path) -> None:
    """The shipped scene `punch_on_foundation.toml` through `tribo run`'s code: summary.json gives each pair's forces
    (the foundation's balances the punch's vertical force), the contact CSVs name each row's pair, read back with
    pandas; a two-pair scene with error bars, an [adapt] or a [history] runs."""
    import pandas as pd

    scene = load_scene(scene_path("punch_on_foundation"))
    problem, solution, files = run_scene(scene, tmp_path)
    assert problem.pairs == ["top", "bottom"] and solution.report.converged
    summary = json.loads((tmp_path / "summary.json").read_text())
    top, bottom = summary["pairs"]
    assert (top["name"], bottom["name"], top["mu"], bottom["mu"]) == ("top", "bottom", 0.3, 0.6)
    assert bottom["normal_force"] == pytest.approx(-top["contact_force"][1], rel=1e-6)
    assert summary["normal_force"] == pytest.approx(top["normal_force"] + bottom["normal_force"], rel=1e-12)
    multipliers = pd.read_csv(tmp_path / "contact.csv", comment="#")
    nodes = pd.read_csv(tmp_path / "contact_nodes.csv", comment="#")
    assert list(multipliers["pair"].unique()) == ["top", "bottom"] and len(multipliers) == solution.lambda_n.size
    # Each row's point lies on its own side: y = 1 on the top, y = 0 on the bottom.
    assert np.allclose(nodes.loc[nodes["pair"] == "top", "y"], 1.0)
    assert np.allclose(nodes.loc[nodes["pair"] == "bottom", "y"], 0.0)
    assert np.allclose(nodes.loc[nodes["pair"] == "bottom", "obstacle_y"], 0.0)
    # The VTU files, read back with meshio: each pair's side a chain of lines on its own side, the dofs vertices.
    import meshio

    contact = meshio.read(tmp_path / "result_contact.vtu")
    pair_of_line = contact.cell_data["pair"][0]
    assert sorted(set(pair_of_line.tolist())) == [0, 1] and len(pair_of_line) == solution.sigma_n.size
    bottom_lines = contact.cells_dict["line"][pair_of_line == 1]
    assert np.allclose(contact.points[bottom_lines.ravel(), 1], 0.0)
    dofs = meshio.read(tmp_path / "result_multipliers.vtu")
    assert np.allclose(dofs.point_data["lambda_n"], solution.lambda_n)
    assert np.allclose(dofs.points[dofs.point_data["pair"] == 1, 1], 0.0)
    # The plots read the first pair's side.
    import matplotlib

    matplotlib.use("Agg")
    from tribo import plot

    ax = plot.contact_pressure(problem, solution)
    assert ax.get_lines() and solution.pair(0).lambda_n.size == solution.pairs[0].multipliers.stop
    plot.tangential(problem, solution)
    plot.von_mises(problem, solution, obstacle=True)
    data = tomllib.loads(scene_path("punch_on_foundation").read_text(encoding="utf-8"))
    _, barred, _ = run_scene(parse_scene({**data, "estimate": {"error_bars": True}}), tmp_path / "bars")
    assert np.isfinite(barred.report.estimate["normal_force_error"])
    _, adapted, _ = run_scene(parse_scene({**data, "adapt": {"tol": 0.1}}), tmp_path / "adapt")
    assert adapted.report.converged and (tmp_path / "adapt" / "adapt.csv").exists()
    _, last, _ = run_scene(parse_scene({**data, "history": {"approach": [0.01, 0.02]}}), tmp_path / "history")
    assert last.report.converged and [p.name for p in last.pairs] == ["top", "bottom"]
    steps = pd.read_csv(tmp_path / "history" / "history.csv", comment="#")
    assert steps["bottom.normal_force"].iloc[-1] == pytest.approx(last.pairs[1].normal_force, rel=1e-12)
    pairs = data["contact"]["pairs"]
    turned = {**data, "contact": {**data["contact"], "pairs": [{**pairs[0], "rotation": {"center": [0, 0], "angle": 1}}]}}
    with pytest.raises(tribo.SceneError, match=r"contact.pairs\[0\].rotation': a further pair's obstacle does not turn"):
        parse_scene(turned)
    without_law = {k: v for k, v in data.items() if k != "friction"}
    with pytest.raises(tribo.SceneError, match=r"contact.pairs\[0\].mu': a pair's own mu needs Coulomb friction"):
        parse_scene(without_law).build()
    misspelled = {**data, "contact": {**data["contact"], "pairs": [{**pairs[0], "edge_set": "botom"}]}}
    with pytest.raises(tribo.SceneError, match=r"contact.pairs\[0\].edge_set' = 'botom'"):
        parse_scene(misspelled).build()
    # The plots of Γ_C show the first pair; another pair's part is refused, not drawn on the first side.
    with pytest.raises(ValueError, match="first contact pair"):
        plot.contact_pressure(problem, solution.pair(1))
    second = solution.pair(1)
    assert second.pairs[0].index == 1 and second.lambda_n.size == solution.lambda_n[solution.pairs[1].multipliers].size
    assert (second.mu, solution.pair(0).mu, solution.mu) == (0.6, 0.3, 0.3)


def test_two_bodies_with_a_foundation_pair() -> None:
    """Two stacked blocks, the lower one resting on a rigid foundation (a further pair, its only vertical hold),
    pressed in uniaxial strain: λ_n is the pressure p = δ / Σ h_i/M_i at every dof of both pairs, frictionless and
    Coulomb with the foundation's own μ; a further pair on the primary side is refused."""
    def p_modulus(e: float, nu: float) -> float:
        return e * (1 - nu) / ((1 + nu) * (1 - 2 * nu))

    rollers = [tribo.Support.roller("left"), tribo.Support.roller("right")]
    lower = tribo.Body("lower", tribo.Mesh.rectangle((0.0, 2.0), (-1.0, 0.0), 5, 3), young=100.0, poisson=0.3,
                       supports=rollers)
    upper = tribo.Body("upper", tribo.Mesh.rectangle((0.0, 2.0), (0.0, 0.5), 7, 2), young=300.0, poisson=0.2,
                       supports=[*rollers, tribo.Support.displacement("top", y=-0.01)])
    p = 0.01 / (1.0 / p_modulus(100.0, 0.3) + 0.5 / p_modulus(300.0, 0.2))
    ground = tribo.Obstacle.line((0.0, -1.0), (0.0, 1.0))
    for own_mu, mu in ((None, None), (0.5, 0.3)):
        problem = tribo.Problem.two_bodies(lower, upper, secondary="upper.bottom", primary="lower.top",
                                           multiplier_ratio=1.0, pairs=[tribo.Pair("lower.bottom", ground, mu=own_mu)])
        assert problem.pairs == ["upper.bottom", "lower.bottom"]
        sol = problem.solve(mu=mu)
        assert sol.report.converged
        for r in sol.pairs:
            assert np.abs(sol.lambda_n[r.multipliers] - p).max() <= 1e-9 * p, r.name
        assert [r.mu for r in sol.pairs] == ([None, None] if mu is None else [0.3, 0.5])
    with pytest.raises(tribo.ContactGeometryError, match="primary side 'lower.top'"):
        tribo.Problem.two_bodies(lower, upper, secondary="upper.bottom", primary="lower.top",
                                 pairs=[tribo.Pair("lower.top", ground)])


def test_a_two_body_scene_with_a_foundation_pair_runs(tmp_path: Path) -> None:
    """The two-body Hertz scene with the lower block on a rigid foundation instead of its clamp (rollers on its
    sides): the foundation alone holds it vertically, so it carries the contact force; the summary names both pairs."""
    text = scene_path("hertz_two_bodies").read_text(encoding="utf-8")
    text = text.replace('supports = [{ kind = "clamp", edge_set = "bottom" }]',
                        'supports = [{ kind = "roller", edge_set = "left" }, { kind = "roller", edge_set = "right" }]')
    text = text.replace("h_min = 0.005", "h_min = 0.02")
    text += '\n[[contact.pairs]]\nedge_set = "lower.bottom"\nshape = "line"\npoint = [0.0, -2.0]\nnormal = [0.0, 1.0]\n'
    scene = tmp_path / "stack.toml"
    scene.write_text(text, encoding="utf-8")
    problem, solution, _ = run_scene(load_scene(scene), tmp_path / "out")
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["status"] == "converged" and [r["name"] for r in summary["pairs"]] == ["lower.top", "lower.bottom"]
    top, bottom = summary["pairs"]
    assert bottom["normal_force"] == pytest.approx(top["normal_force"], rel=1e-6)
    misspelled = text.replace('edge_set = "lower.bottom"', 'edge_set = "bottom"')
    with pytest.raises(tribo.SceneError, match=r"contact.pairs\[0\].edge_set' = 'bottom': no body has"):
        parse_scene(tomllib.loads(misspelled)).build()
    # The upper block's support and the foundation hold the stack: their forces balance (no body force).
    assert summary["bodies"][1]["reaction"][1] == pytest.approx(-bottom["normal_force"], rel=1e-6)
