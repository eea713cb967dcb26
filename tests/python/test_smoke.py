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


def test_import_sets_the_allocator_purge_delay_unless_the_user_did() -> None:
    """`import tribo` keeps freed pages 250 ms (docs/python_memory.md); a user's MIMALLOC_PURGE_DELAY wins."""
    import os
    import subprocess
    import sys

    code = "import os, tribo; print(os.environ['MIMALLOC_PURGE_DELAY'])"
    env = {k: v for k, v in os.environ.items() if k != "MIMALLOC_PURGE_DELAY"}
    for user, expected in ((None, "250"), ("-1", "-1"), ("0", "0")):
        run_env = env if user is None else {**env, "MIMALLOC_PURGE_DELAY": user}
        out = subprocess.run([sys.executable, "-c", code], env=run_env, capture_output=True, text=True, check=True)
        assert out.stdout.strip() == expected
