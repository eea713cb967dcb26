"""Shared scenes of the Python tests: small enough to solve in milliseconds."""

from __future__ import annotations

import numpy as np
import pytest

import tribo

# The Hertz-like scene of the demo on a coarser graded mesh.
BLOCK = dict(x=(-2.0, 2.0), y=(-2.0, 0.0))
GRADING = dict(side="top", segment=(-0.3, 0.3), h_min=0.04, h_max=0.5, growth=0.3)


def hertz_problem(mesh: tribo.Mesh | None = None, **kw: object) -> tribo.Problem:
    mesh = mesh if mesh is not None else tribo.Mesh.graded_rectangle(BLOCK["x"], BLOCK["y"], **GRADING)
    args: dict[str, object] = dict(
        young=200.0, poisson=0.3, clamped="bottom", contact="top", obstacle=tribo.Obstacle.circle(1.0), approach=0.01
    )
    args.update(kw)
    return tribo.Problem(mesh, **args)  # type: ignore[arg-type]


@pytest.fixture(scope="session")
def hertz() -> tribo.Problem:
    return hertz_problem(shift=0.004)


def arrays_of(mesh: tribo.Mesh) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
    return mesh.points, mesh.triangles, mesh.edge_sets
