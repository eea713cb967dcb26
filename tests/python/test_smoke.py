"""The compiled module loads and solves the smallest frictionless scene."""

import numpy as np

import tribo


def test_frictionless_block_pressed_flat() -> None:
    mesh = tribo.Mesh.rectangle((0.0, 1.0), (0.0, 1.0), 4, 4)
    problem = tribo.Problem(
        mesh, young=1.0, poisson=0.3, clamped="bottom", contact="top", obstacle=tribo.Obstacle.flat(), approach=0.01
    )
    solution = problem.solve()
    assert solution.report.status == "converged"
    assert solution.displacement.shape == (mesh.n_nodes, 2)
    assert solution.normal_force > 0.0
    assert np.all(solution.lambda_n >= -1e-12)
