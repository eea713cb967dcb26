"""Shared scenes of the Python tests: the Hertz scene of `tribo/scenes/hertz.toml` (the file the Rust tests,
the benches and the studies read too), small enough to solve in milliseconds."""

from __future__ import annotations

import pytest

import tribo
from tribo.scene import load_scene, scene_path

HERTZ = load_scene(scene_path("hertz"))
_body, _disc = HERTZ.sections["body"], HERTZ.sections["discretization"]
BLOCK = dict(x=_body["x"], y=_body["y"])
GRADING = dict(
    side=HERTZ.get("contact", "edge_set"), segment=_disc["grading"], h_min=_disc["h_min"], h_max=_disc["h"],
    growth=_disc["growth"],
)


def hertz_problem(mesh: tribo.Mesh | None = None, **kw: object) -> tribo.Problem:
    """The Hertz problem of the scene file (on its mesh unless `mesh` is given), with keywords of
    `tribo.Problem` overriding the scene's."""
    args: dict[str, object] = dict(
        young=HERTZ.get("material", "young"),
        poisson=HERTZ.get("material", "poisson"),
        clamped=HERTZ.get("supports", "clamped"),
        contact=HERTZ.get("contact", "edge_set"),
        obstacle=HERTZ.obstacle(),
        approach=HERTZ.get("obstacle", "approach"),
    )
    args.update(kw)
    return tribo.Problem(mesh if mesh is not None else HERTZ.mesh(), **args)  # type: ignore[arg-type]


@pytest.fixture(scope="session")
def hertz() -> tribo.Problem:
    return hertz_problem(shift=0.004)
