"""The mixed displacement–pressure formulation from Python and scene files (issue 41, item 1): the keyword and
its resolved value, the pressure output, the VTU point data and summary.json, and the refusals."""

from __future__ import annotations

import json
import tomllib
from pathlib import Path

import meshio
import numpy as np
import pytest

import tribo
from tribo.run import run_scene
from tribo.scene import parse_scene, scene_path



def block(poisson: float, **kw: object) -> tribo.Problem:
    mesh = tribo.Mesh.rectangle((0.0, 1.0), (0.0, 1.0), 8, 8)
    return tribo.Problem(mesh, young=1.0, poisson=poisson, clamped="top", contact="bottom", approach=0.01, **kw)


def test_auto_and_the_pressure_output() -> None:
    """'auto' (the default) is mixed from ν = 0.49 in plane strain, displacement below and in plane stress;
    the mixed problem has one pressure per node among its unknowns and in its solution."""
    mixed, plain = block(0.4999), block(0.3)
    assert (mixed.formulation, plain.formulation) == ("mixed", "displacement")
    assert block(0.4999, model="plane_stress").formulation == "displacement"
    assert block(0.4999, formulation="displacement").formulation == "displacement"
    assert block(0.3, formulation="mixed").formulation == "mixed"
    nodes = mixed.mesh.n_nodes
    assert mixed.n_free == plain.n_free + nodes
    solution = mixed.solve()
    assert solution.report.status == "converged"
    assert solution.pressure.shape == (nodes,) and np.all(np.isfinite(solution.pressure))
    # Pressed by the obstacle, the block is in compression under it: p = −λ div u > 0 there.
    assert solution.pressure.max() > 0
    assert plain.solve().pressure.shape == (0,)


def test_axisymmetric_rubber() -> None:
    """In axisymmetry 'auto' is mixed from ν = 0.49 too: a cylinder on the axis pressed by δ at ν = 0.4999 has the
    uniform state (λ_n = E δ, u_r = ν δ r, the pressure p = −λ div u = E ν δ / (1 + ν), the hoop strain in div u)
    and the force π R² E δ on the whole turn; the P1 displacements on the same mesh give the same uniform state
    (it is in their space) but have no pressure."""
    mesh = tribo.Mesh.rectangle((0.0, 1.0), (0.0, 1.0), 6, 6)
    young, nu, delta = 200.0, 0.4999, 1e-3
    kw: dict[str, object] = dict(young=young, poisson=nu, contact="bottom", model="axisymmetric",
                                 supports=[tribo.Support.displacement("top", y=-delta)])
    problem = tribo.Problem(mesh, **kw)  # type: ignore[arg-type]
    assert problem.formulation == "mixed"
    solution = problem.solve()
    assert solution.report.status == "converged"
    np.testing.assert_allclose(solution.lambda_n, young * delta, rtol=1e-7)
    np.testing.assert_allclose(solution.pressure, young * nu * delta / (1 + nu), rtol=1e-6)
    np.testing.assert_allclose(solution.displacement[:, 0], nu * delta * mesh.points[:, 0], atol=1e-9)
    np.testing.assert_allclose(solution.normal_force, np.pi * young * delta, rtol=1e-7)
    plain = tribo.Problem(mesh, formulation="displacement", **kw)  # type: ignore[arg-type]
    assert plain.formulation == "displacement" and plain.solve().pressure.shape == (0,)


def test_refusals() -> None:
    """Mixed with ν ≤ 0, a misspelled formulation and the partial factorization are typed
    errors naming what to do."""
    with pytest.raises(tribo.SettingsError, match="above 0"):
        block(0.0, formulation="mixed")
    with pytest.raises(tribo.SettingsError, match="displacement, mixed"):
        block(0.3, formulation="mini")
    with pytest.raises(tribo.SettingsError, match="schur"):
        block(0.4999).solve(condensation="schur")


def test_a_scene_file_takes_the_formulation(tmp_path: Path) -> None:
    """[material] formulation reaches the problem; tribo run writes the pressure to the VTU body file (read back
    with meshio) and the formulation to summary.json; 'auto' says what it chose."""
    def scene(formulation: str) -> dict[str, object]:
        data = tomllib.loads(scene_path("hertz").read_text())  # the shipped Hertz scene, made of rubber
        data["material"].update(poisson=0.4999, formulation=formulation)
        return data

    for formulation, said in (("auto", "mixed"), ("displacement", "displacement"), ("mixed", "mixed")):
        data = scene(formulation)
        out = tmp_path / formulation
        problem, solution, _ = run_scene(parse_scene(data), out, plots=False)
        assert problem.formulation == said and solution.report.status == "converged"
        summary = json.loads((out / "summary.json").read_text())
        assert summary["formulation"] == said
        body = meshio.read(out / "result.vtu")
        if said == "mixed":
            assert np.allclose(body.point_data["pressure"], solution.pressure)
        else:
            assert "pressure" not in body.point_data
    with pytest.raises(tribo.SceneError, match="formulation"):
        parse_scene(scene("p1p1"))


def test_two_bodies_take_the_formulation(tmp_path: Path) -> None:
    """Problem.two_bodies(formulation=) and a two-body scene's [[bodies]] material.formulation: both bodies' pressures
    are unknowns; 'auto' is mixed when either body is rubber; the two bodies of a scene must agree."""
    def pair(poisson: float, **kw: object) -> tribo.Problem:
        lower = tribo.Body("lower", tribo.Mesh.rectangle((0.0, 2.0), (-1.0, 0.0), 6, 3), young=100.0, poisson=poisson,
                           clamped="bottom")
        upper = tribo.Body("upper", tribo.Mesh.rectangle((0.0, 2.0), (0.0, 0.5), 6, 2), young=300.0, poisson=0.3,
                           supports=[tribo.Support.displacement("top", x=0.0, y=-0.01)])
        return tribo.Problem.two_bodies(lower, upper, secondary="lower.top", primary="upper.bottom",
                                        **kw)  # type: ignore[arg-type]

    rubber, plain = pair(0.4999), pair(0.3)
    assert (rubber.formulation, plain.formulation) == ("mixed", "displacement")
    nodes = rubber.mesh.n_nodes
    assert rubber.n_free == plain.n_free + nodes
    assert pair(0.4999, formulation="displacement").formulation == "displacement"
    solution = rubber.solve()
    assert solution.report.status == "converged" and solution.pressure.shape == (nodes,)
    data = tomllib.loads(scene_path("hertz_two_bodies").read_text())
    data["bodies"][0]["material"]["formulation"] = "mixed"
    with pytest.raises(tribo.SceneError, match="both bodies take one formulation"):
        parse_scene(data)
    data["bodies"][1]["material"]["formulation"] = "mixed"
    problem, solution, _ = run_scene(parse_scene(data), tmp_path, plots=False)
    assert problem.formulation == "mixed" and solution.report.status == "converged"
