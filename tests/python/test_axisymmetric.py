"""Axisymmetry from Python and scene files (issue 41, item 2): the shipped sphere-on-flat scene against 3D Hertz
through ``tribo run``, its files read back, the uniaxial cylinder exact, and the refusals as typed errors."""

from __future__ import annotations

import json
import math
from pathlib import Path

import meshio
import numpy as np
import pytest

import tribo
from tribo.run import run_scene
from tribo.scene import load_scene, scene_path

E, NU = 200.0, 0.3


def _l2_against_hertz(problem: tribo.Problem, solution: tribo.Solution) -> float:
    """The relative L²(Γ_C, 2π r dr) distance of λ_n from the 3D Hertz pressure of the computed force
    (``plot.hertz_pressure``), on a fine grid of r in [0, 1.5 a]."""
    from tribo import plot  # imported where used: `import tribo` does not load matplotlib (test_api)

    xi, p = plot.hertz_pressure(problem, solution)
    a, p0 = float(xi[-1]), float(p.max())
    assert p0 == pytest.approx(3 * solution.normal_force / (2 * math.pi * a * a), rel=1e-12)
    r = np.linspace(0.0, 1.5 * a, 60001)
    exact = p0 * np.sqrt(np.clip(1 - (r / a) ** 2, 0.0, None))
    lam = problem.evaluate_multiplier(solution.lambda_n, r)
    return math.sqrt(np.trapezoid(r * (lam - exact) ** 2, r) / np.trapezoid(r * exact**2, r))


def test_the_sphere_scene_is_3d_hertz_and_writes_its_files(tmp_path: Path) -> None:
    """`tribo run` on the shipped sphere scene: λ_n within 1 % of 3D Hertz (a³ = 3PR/(4E*)) in L², the force for
    the approach δ (P = 4/3 E* R^½ δ^{3/2}) within 1 %, summary.json says the model and what the forces are, and
    the VTU file has the hoop stress under its own name, equal to σ_zz."""
    scene = load_scene(scene_path("sphere"))
    problem, solution, files = run_scene(scene, tmp_path, plots=False)
    assert problem.model == "axisymmetric" and solution.report.status == "converged"
    assert _l2_against_hertz(problem, solution) < 0.01
    e_star = E / (1 - NU**2)
    assert solution.normal_force == pytest.approx(4 / 3 * e_star * 0.01**1.5, rel=0.01)
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["model"] == "axisymmetric"
    assert "whole turn" in summary["conventions"]["model"] and "hoop" in summary["conventions"]["model"]
    body = meshio.read(tmp_path / "result.vtu")
    np.testing.assert_array_equal(body.cell_data["sigma_hoop"][0], body.cell_data["sigma_zz"][0])
    np.testing.assert_array_equal(body.cell_data["sigma_hoop"][0], solution.stress_zz)
    # Under the sphere the hoop stress is compressive, as the radial one (the material is pushed outward
    # and held by the rest of the half-space).
    centre = np.argmin(np.hypot(*np.asarray(problem.mesh.points)[np.asarray(problem.mesh.triangles)].mean(axis=1).T))
    assert solution.stress_zz[centre] < 0 and solution.stress[centre][0] < 0


def test_a_cylinder_pressed_on_a_flat_is_uniaxial_from_python() -> None:
    """The patch test of the Rust suite from Python: a cylinder of radius 1 and height 1 on a frictionless flat,
    its top pushed down δ: λ_n = E δ, σ_θθ = 0, u_r = ν δ r, and the force on the whole turn π E δ."""
    delta = 1e-3
    mesh = tribo.Mesh.rectangle((0.0, 1.0), (0.0, 1.0), 6, 6)
    problem = tribo.Problem(mesh, young=E, poisson=NU, contact="bottom", model="axisymmetric",
                            supports=[tribo.Support.displacement("top", y=-delta)])
    s = problem.solve()
    assert s.report.status == "converged"
    np.testing.assert_allclose(s.lambda_n, E * delta, rtol=1e-7)
    np.testing.assert_allclose(s.stress_zz, 0.0, atol=1e-7 * E * delta)
    points = np.asarray(mesh.points)
    np.testing.assert_allclose(s.displacement[:, 0], NU * delta * points[:, 0], atol=1e-9)
    assert s.normal_force == pytest.approx(math.pi * E * delta, rel=1e-7)


def test_two_stacked_cylinders_are_uniaxial() -> None:
    """Two bodies in axisymmetry on non-matching meshes: two cylinders of two materials stacked on a roller and
    pressed carry the uniaxial stress δ / (H₁/E₁ + H₂/E₂), and the force on the whole turn π R² times it."""
    delta, alu = 1e-3, (70.0, 0.33)
    lower = tribo.Body("lower", tribo.Mesh.rectangle((0.0, 1.0), (-1.0, 0.0), 4, 4), young=E, poisson=NU,
                       supports=[tribo.Support.displacement("bottom", y=0.0)])
    upper = tribo.Body("upper", tribo.Mesh.rectangle((0.0, 1.0), (0.0, 1.0), 5, 5), young=alu[0], poisson=alu[1],
                       supports=[tribo.Support.displacement("top", y=-delta)])
    problem = tribo.Problem.two_bodies(lower, upper, secondary="lower.top", primary="upper.bottom",
                                       model="axisymmetric")
    s = problem.solve()
    stress = delta / (1 / E + 1 / alu[0])
    np.testing.assert_allclose(s.lambda_n, stress, rtol=1e-6)
    assert s.normal_force == pytest.approx(math.pi * stress, rel=1e-6)
    assert s.contact_force[0] == 0.0 and s.contact_force[1] == pytest.approx(-math.pi * stress, rel=1e-6)


def test_what_axisymmetry_does_not_take_is_a_typed_error() -> None:
    """A mesh left of the axis is a MeshError naming the node; an obstacle shifted radially is refused; a model
    misspelled names the choices."""
    mesh = tribo.Mesh.rectangle((-0.5, 1.0), (0.0, 1.0), 3, 3)
    with pytest.raises(tribo.MeshError, match="node 0 lies at r") as e:
        tribo.Problem(mesh, young=E, poisson=NU, contact="bottom", clamped="top", model="axisymmetric")
    assert e.value.kind == "BadAxisymmetry"
    with pytest.raises(tribo.MeshError, match="radial component"):
        tribo.Problem(tribo.Mesh.rectangle((0.0, 1.0), (0.0, 1.0), 2, 2), young=E, poisson=NU, contact="bottom",
                      clamped="top", model="axisymmetric", shift=1e-3)
    with pytest.raises(tribo.TriboError, match="axisymmetric"):
        tribo.Problem(tribo.Mesh.rectangle((0.0, 1.0), (0.0, 1.0), 2, 2), young=E, poisson=NU, contact="bottom",
                      clamped="top", model="axisymetric")
