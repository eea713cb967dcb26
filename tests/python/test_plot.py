"""tribo.plot: optional, not imported by tribo, every function takes ax=None and returns its Axes."""

from __future__ import annotations

import sys

import pytest

import tribo

pytest.importorskip("matplotlib")


def test_plot_is_not_imported_by_the_package() -> None:
    import subprocess

    code = "import sys, tribo; assert 'tribo.plot' not in sys.modules and 'matplotlib' not in sys.modules"
    subprocess.run([sys.executable, "-c", code], check=True)


def test_plots_return_axes(hertz: tribo.Problem) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from tribo import plot

    s = hertz.solve(mu=0.3)
    for draw in (plot.contact_pressure, plot.tangential, plot.von_mises):
        ax = draw(hertz, s)
        assert ax.has_data()
        _, given = plt.subplots()
        assert draw(hertz, s, given) is given
    ax = plot.von_mises(hertz, s, scale=1.0, window=(-0.2, 0.2, -0.2, 0.05), obstacle=True)
    assert ax.get_xlim() == (-0.2, 0.2)
    plt.close("all")


def test_normal_plot_shows_the_hertz_pressure_of_the_same_force(hertz: tribo.Problem) -> None:
    """The demo's normal-contact plot carries the Hertz pressure of the computed force: it integrates to
    that force and its half-width is the plane-strain Hertz one; a flat obstacle has none."""
    import numpy as np

    from tribo import plot

    solution = hertz.solve()
    xi, p = plot.hertz_pressure(hertz, solution)  # type: ignore[misc]
    assert abs(np.trapezoid(p, xi) - solution.normal_force) < 1e-3 * solution.normal_force
    ax = plot.contact_pressure(hertz, solution)
    assert any("Hertz" in line.get_label() for line in ax.get_lines())
    flat = tribo.Problem(tribo.Mesh.rectangle((0.0, 1.0), (0.0, 1.0), 4, 4), young=1.0, poisson=0.3,
                         clamped="bottom", contact="top", obstacle=tribo.Obstacle.flat(), approach=0.01)
    assert plot.hertz_pressure(flat, flat.solve()) is None
    # In plane stress the contact modulus is E: the half-width a = √(4PR/(πE)).
    from conftest import hertz_problem

    stress = hertz_problem(model="plane_stress")
    solved = stress.solve()
    xi, p = plot.hertz_pressure(stress, solved)  # type: ignore[misc]
    radius = stress.obstacle.radius
    assert radius is not None
    a = np.sqrt(4 * solved.normal_force * radius / (np.pi * stress.young))
    assert (xi[-1] - xi[0]) / 2 == pytest.approx(a, rel=1e-12)


def test_plot_titles_name_who_exerts_the_force() -> None:
    """Between two bodies the titles name the primary side and the secondary body (they said "the obstacle"),
    against a rigid obstacle the obstacle and the body, with the force components of the run."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from tribo import plot
    from tribo.checks import format_vector
    from tribo.scene import load_scene, scene_path

    problem = load_scene(scene_path("fretting_two_bodies")).build()
    solution = problem.solve(mu=0.3)
    normal = plot.contact_pressure(problem, solution).get_title()
    tangential = plot.tangential(problem, solution).get_title()
    assert "obstacle" not in normal + tangential, normal + tangential
    assert f"force of '{problem.primary}' on the secondary body (Fx, Fy) = {format_vector(solution.contact_force)}" in normal
    assert f"'{problem.primary}' pulls the secondary body by" in tangential
    hertz = load_scene(scene_path("hertz")).build()
    s = hertz.solve(mu=0.3)
    assert "force of the obstacle on the body" in plot.contact_pressure(hertz, s).get_title()
    assert "the obstacle pulls the body by" in plot.tangential(hertz, s).get_title()
    plt.close("all")


def test_history_tractions_say_what_moves_and_which_way_positions_run() -> None:
    """Each step's legend gives what the history moves and its Q (the Cattaneo–Mindlin gallery said "s = 0"
    at every step of a history that moves prescribed displacements); the abscissa says which way it runs
    (it said "along t" while positions increase along −t)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    from tribo import plot
    from tribo.scene import load_scene, scene_path

    hertz = load_scene(scene_path("hertz")).build()
    shifted = hertz.solve_history(0.01, np.linspace(0.0, 0.004, 3), mu=0.3)
    ax = plot.history_tractions(shifted, [1, 2], problem=hertz)
    labels = [line.get_label() for line in ax.get_lines() if line.get_label().startswith("λ_t")]
    assert labels == [f"λ_t, step {k} (s = {shifted.shift[k]:.3g}, Q = {shifted.tangential_force[k]:.3g})" for k in (1, 2)]
    assert ax.get_xlabel() == "abscissa ξ along Γ_C, increasing with x (along −t)"
    two = load_scene(scene_path("fretting_two_bodies")).build()
    moved = two.solve_history(displacements={"upper.top.x": np.array([0.0, 0.001])}, mu=0.3)
    labels = [line.get_label() for line in plot.history_tractions(moved, [1]).get_lines()]
    assert f"λ_t, step 1 (Q = {moved.tangential_force[1]:.3g})" in labels, labels
    plt.close("all")


def test_sweep_maps_share_one_scale_two_to_a_row() -> None:
    """Issue 38: the sweep maps were unreadable at page width (three to a row, a colour bar each, each on
    its own scale). Over three axes: two maps to a row, one colour scale and one colour bar, short titles;
    a case that did not converge is crossed."""
    import itertools

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import pandas as pd

    from tribo.plot import sweep_figure

    rows = [{"friction.mu": mu, "material.poisson": nu, "solver.qp_tol": tol, "iterations": i,
             "status": "converged" if i < 17 else "max_iterations"}
            for i, (mu, nu, tol) in enumerate(itertools.product([0.1, 0.3], [0.2, 0.3, 0.45], [1e-12, 1e-10, 1e-8]))]
    fig = sweep_figure(pd.DataFrame(rows), ["friction.mu", "material.poisson", "solver.qp_tol"], "iterations")
    maps = [ax for ax in fig.axes if ax.images]
    assert len(maps) == 3 and len({ax.get_position().x0 for ax in maps}) == 2, "two to a row"
    assert {ax.images[0].get_clim() for ax in maps} == {(0.0, 17.0)}, "one scale: the values of all maps"
    assert len(fig.axes) == 4 + 1, "three maps, the hidden fourth and one colour bar"
    assert [ax.get_title() for ax in maps] == [f"qp_tol = {t}" for t in (1e-12, 1e-10, 1e-08)]
    crossed = [line for ax in maps for line in ax.lines if line.get_marker() == "x"]
    assert len(crossed) == 1
    plt.close(fig)
