"""The Coulomb method from Python, scene files, `tribo run` and sweeps (issue 40): ``coulomb`` chooses the fixed
point (the default and the reference), the semismooth Newton method or ``auto``, and every report says which
method answered. That the two give the same answer, to the bound of the fixed point's contraction, is tested in
the crate (`tests/integration/coulomb_newton.rs`, and over random problems in `paths.rs`); that ``coulomb_check``
says 'differ' only where the discrete problem has several solutions, by enumerating them, in `solve/check.rs`."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import tribo
from tribo.checks import check_solution
from tribo.cli import main
from tribo.scene import scene_path


def test_the_setting_chooses_the_method_and_the_report_names_it(hertz: tribo.Problem) -> None:
    assert tribo.solver_defaults()["coulomb"] == "fixed_point"
    assert tribo.solver_settings()["coulomb"]["options"] == ["fixed_point", "newton", "auto"]
    fixed = hertz.solve(mu=0.3)
    newton = hertz.solve(mu=0.3, coulomb="newton")
    auto = hertz.solve(mu=0.3, coulomb="auto")
    assert (fixed.report.coulomb_method, fixed.report.coulomb_fallback) == ("fixed_point", False)
    assert (newton.report.coulomb_method, newton.report.coulomb_fallback) == ("newton", False)
    assert auto.report.coulomb_method == "newton" and np.array_equal(auto.lambda_t, newton.lambda_t)
    for s in (fixed, newton):
        assert s.report.converged and len(s.report.residual_history) >= s.report.iterations >= 1
    # Newton's history is its merit before each step and the one it ended on, within fp_tol.
    assert len(newton.report.residual_history) == newton.report.iterations + 1
    assert newton.report.residual_history[-1] <= tribo.solver_defaults()["fp_tol"]
    assert hertz.solve().report.coulomb_method is None
    assert hertz.solve(threshold=0.1, coulomb="newton").report.coulomb_method is None


def test_a_misspelled_method_names_the_choices(hertz: tribo.Problem) -> None:
    with pytest.raises(tribo.SettingsError, match="fixed_point, newton, auto"):
        hertz.solve(mu=0.3, coulomb="newtons")


def test_progress_reports_each_newton_step(hertz: tribo.Problem) -> None:
    seen: list[tuple[int, float, int, float]] = []

    def progress(iteration: int, change: float, size: int, seconds: float) -> bool:
        seen.append((iteration, change, size, seconds))
        return True

    s = hertz.solve(mu=0.3, coulomb="newton", progress=progress)
    # The initial frictionless QP (iteration 0), then one call per Newton step with the merit before it.
    steps = [x for x in seen if x[0] > 0]
    assert [x[0] for x in steps] == list(range(1, s.report.iterations + 1))
    assert [x[1] for x in steps] == pytest.approx(list(s.report.residual_history[:-1]), rel=0, abs=0)


def run_hertz(tmp_path: Path, solver: str) -> dict[str, Any]:
    """`tribo run` on the shipped Hertz scene with μ = 0.3 and the `[solver]` line `solver`: its summary.json."""
    scene = tmp_path / "scene.toml"
    text = scene_path("hertz").read_text(encoding="utf-8")
    scene.write_text(text + f"\n[friction]\nmu = 0.3\n\n[solver]\n{solver}\n", encoding="utf-8")
    assert main(["run", str(scene), "--out", str(tmp_path / "out")]) == 0
    return dict(json.loads((tmp_path / "out" / "summary.json").read_text(encoding="utf-8")))


def test_a_scene_chooses_the_method_and_the_run_says_which(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    summary = run_hertz(tmp_path, 'coulomb = "newton"')
    scene, text = tmp_path / "scene.toml", scene_path("hertz").read_text(encoding="utf-8")
    assert (summary["coulomb_method"], summary["coulomb_fallback"]) == ("newton", False)
    assert summary["scene"]["solver"]["coulomb"] == "newton"
    assert f"(coulomb, {summary['iterations']} Newton steps)" in capsys.readouterr().out
    scene.write_text(text + '\n[friction]\nmu = 0.3\n\n[solver]\ncoulomb = "newtons"\n', encoding="utf-8")
    assert main(["run", str(scene), "--out", str(tmp_path / "bad")]) == 1
    assert "scene key 'solver.coulomb' must be one of 'fixed_point', 'newton', 'auto'" in capsys.readouterr().err


def two_solutions_block() -> tribo.Problem:
    """2 × 1 cells of 1 × 1 (E = 1, ν = 0.4) clamped at the top, pressed by 0.01 on a rigid flat, P0 multipliers:
    at μ = 0.5 with γ0 = 0 its discrete Coulomb problem has a segment of solutions (the crate's enumeration)."""
    mesh = tribo.Mesh.rectangle((0.0, 1.0), (0.0, 1.0), 2, 1, diagonal="alternating")
    return tribo.Problem(mesh, young=1.0, poisson=0.4, contact="bottom", clamped="top", approach=0.01,
                         multiplier_ratio=1.0, space="P0")


def test_the_check_says_when_two_methods_find_two_answers() -> None:
    block = two_solutions_block()
    assert tribo.solver_defaults()["coulomb_check"] is False
    plain = block.solve(mu=0.5, gamma0=0.0)
    assert plain.report.converged and plain.report.coulomb_check is None
    for coulomb, other in (("fixed_point", "Newton"), ("newton", "the fixed point")):
        s = block.solve(mu=0.5, gamma0=0.0, coulomb=coulomb, coulomb_check=True)
        r = s.report
        assert r.converged and (r.coulomb_check, r.check_status) == ("differ", "converged")
        assert r.check_distance is not None and r.check_allowed is not None
        assert r.check_distance > 1000 * r.check_allowed
        assert any(w.startswith(f"two answers: {other} converges to another solution") for w in check_solution(block, s))
    a = block.solve(mu=0.5, gamma0=0.0, coulomb_check=True)
    b = block.solve(mu=0.5, gamma0=0.0, coulomb="newton")
    larger = max(np.linalg.norm(a.lambda_n), np.linalg.norm(b.lambda_n))
    assert np.linalg.norm(a.lambda_n - b.lambda_n) / larger == pytest.approx(a.report.check_distance, rel=1e-6)


def test_a_checked_scene_agrees_and_the_run_says_so(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    summary = run_hertz(tmp_path, "coulomb_check = true")
    check = summary["coulomb_check"]
    assert (check["agreement"], check["status"]) == ("agree", "converged")
    assert check["distance"] <= check["allowed"] < 1e-4
    assert "Newton agrees" in capsys.readouterr().out
    assert not any("two answers" in w for w in summary["warnings"])
