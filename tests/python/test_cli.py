"""The scene files and the command line: tribo run, tribo demo, errors that name the key."""

from __future__ import annotations

import csv
import json
import re
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import tribo
from tribo.cli import build_parser, main
from tribo.run import run_scene
from tribo.scene import SceneError, demo_scene_path, load_scene, parse_scene

SCENE = """
title = "small Tresca scene"
[body]
x = [-1.0, 1.0]
y = [-1.0, 0.0]
[material]
young = 100.0
poisson = 0.25
[supports]
clamped = ["bottom"]
[contact]
edge_set = "top"
[obstacle]
shape = "parabola"
radius = 2.0
approach = 0.005
shift = 0.001
[friction]
threshold = 0.2
[discretization]
h = 0.25
h_min = 0.03
space = "P0"
multiplier_ratio = 2.0
gamma0_fraction = 0.3
[solver]
qp_tol = 1e-9
"""


def test_demo_scene_runs_in_process(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["demo", "--out", str(tmp_path / "demo")]) == 0
    out = capsys.readouterr()
    assert "status converged" in out.out and str((tmp_path / "demo").resolve()) in out.out
    # The demo adapts: a progress line per level, and the stick zone resolved by many multiplier dofs (the
    # first, graded mesh has 5 there).
    assert "adaptive level" in out.err and "adaptive solve stopped (tolerance)" in out.err
    summary = json.loads((tmp_path / "demo" / "summary.json").read_text())
    assert summary["status"] == "converged" and summary["friction"] == "coulomb"
    assert summary["states"]["stick"] >= 20 and summary["states"]["slip"] > 0
    est = summary["estimate"]
    assert est["traction_hierarchical_relative"] <= 0.01 < est["traction_relative"] and (tmp_path / "demo" / "adapt.csv").is_file()
    assert summary["kkt_max"] < 1e-6 and summary["normal_force"] > 0
    # The description states the contact and stick zones of this answer (issue 38: it said the centre sticks).
    zones = re.findall(r"ξ ∈ \[(−?[0-9.]+), (−?[0-9.]+)\]", load_scene(demo_scene_path()).description)
    (c0, c1), (s0, s1) = [(float(a.replace("−", "-")), float(b.replace("−", "-"))) for a, b in zones]
    assert summary["contact_width"] == pytest.approx(c1 - c0, rel=0.05)
    assert summary["stick_width"] == pytest.approx(s1 - s0, rel=0.05) and 0 < s0 < s1 < c1
    for name in ("contact.csv", "result.vtu", "result_contact.vtu", "contact_normal.png", "von_mises.png"):
        assert (tmp_path / "demo" / name).stat().st_size > 0
    # Issue 36, item 3: the demo prints its error bars, and those of P and Q cover the reference values its
    # description states (466k unknowns, graded).
    assert re.search(r"P = 0\.8546\d* ± 0\.0018\d*, Q = ", out.out), out.out
    said = re.findall(r"(P|Q) = (−?[0-9.]+) ± ([0-9.]+) where the reference has (−?[0-9.]+)|"
                      r"(Q) = (−?[0-9.]+) ± ([0-9.]+) \(reference (−?[0-9.]+)\)",
                      " ".join(load_scene(demo_scene_path()).description.split()))
    stated = {m[0] or m[4]: [float(v.replace("−", "-")) for v in (m[1:4] if m[0] else m[5:8])] for m in said}
    for name, key in (("P", "normal_force"), ("Q", "tangential_force")):
        value, bar, reference = stated[name]
        assert summary[key] == pytest.approx(value, abs=1e-4) and est[f"{key}_error"] == pytest.approx(bar, rel=0.05)
        assert abs(summary[key] - reference) <= est[f"{key}_error"]


def test_demo_scene_is_the_documented_one() -> None:
    """The demo scene is the one README.md, the getting-started page and the scene's description state."""
    s = load_scene(demo_scene_path())
    assert s.solve_kwargs()["mu"] == 0.3
    assert s.get("obstacle", "radius") == 1.0 and s.get("obstacle", "approach") == 0.01
    assert s.get("obstacle", "shift") == 0.004 and s.get("discretization", "h_min") == 0.01
    assert s.get("discretization", "gamma0_fraction") == 0.5 and s.get("adapt", "tol") == 0.01
    assert s.get("adapt", "stop_on") == "hierarchical"


def test_run_scene_subprocess(tmp_path: Path) -> None:
    scene = tmp_path / "tresca.toml"
    scene.write_text(SCENE)
    r = subprocess.run(
        [sys.executable, "-m", "tribo.cli", "run", str(scene), "--out", str(tmp_path / "o"), "--no-plots"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert r.returncode == 0, r.stderr
    summary = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert summary["friction"] == "tresca" and summary["space"] == "P0"
    assert summary["gamma0"] == pytest.approx(0.3 * summary["gamma0_bound"])
    assert not (tmp_path / "o" / "contact_normal.png").exists()


def test_run_says_how_to_get_error_bars(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """A solve without error bars says how to ask for them; with them, it prints them instead."""
    scene = tmp_path / "tresca.toml"
    scene.write_text(SCENE)
    assert main(["-q", "run", str(scene), "--out", str(tmp_path / "o")]) == 0
    printed = capsys.readouterr().out
    assert "set error_bars = true in [estimate]" in printed and " ± " not in printed
    scene.write_text(SCENE + "[estimate]\nerror_bars = true\n")
    assert main(["-q", "run", str(scene), "--out", str(tmp_path / "b")]) == 0
    printed = capsys.readouterr().out
    assert "set error_bars" not in printed and re.search(r"P = [0-9.e+-]+ ± [0-9.e+-]+, Q = ", printed)


def test_run_draws_plots_only_when_asked(tmp_path: Path) -> None:
    """Issue 38 (output cost): `tribo run` writes the data files by default, the plots with --plots; the files
    it lists are the files it wrote, and the VTU file written beside the others is whole."""
    import meshio

    scene = tmp_path / "tresca.toml"
    scene.write_text(SCENE)
    plots = ["contact_normal.png", "contact_tangential.png", "von_mises.png", "von_mises_contact.png"]
    for args, drawn in (([], False), (["--plots"], True), (["--no-plots"], False)):
        out = tmp_path / f"o{len(args)}{drawn}"
        assert main(["-q", "run", str(scene), "--out", str(out), *args]) == 0
        assert all((out / name).is_file() == drawn for name in plots)
        written = sorted(f.name for f in out.iterdir())
        assert written == sorted(["summary.json", "contact.csv", "contact_nodes.csv", "contact_edges.csv", "result.vtu",
                                  "result_contact.vtu", "result_multipliers.vtu", *(plots if drawn else [])])
        assert len(meshio.read(out / "result.vtu").cells_dict["triangle"]) == json.loads(
            (out / "summary.json").read_text())["mesh"]["triangles"]
    # The demo draws its plots unless told not to.
    assert build_parser().parse_args(["demo"]).plots and not build_parser().parse_args(["demo", "--no-plots"]).plots
    assert not build_parser().parse_args(["run", "s.toml", "--out", "o"]).plots


def test_scene_friction_levels() -> None:
    """The scene passes mu/threshold on; the core decides the law (μ = 0 is frictionless)."""
    base = load_toml(SCENE)
    for friction, law in (({}, "frictionless"), ({"mu": 0.0}, "frictionless"), ({"mu": 0.4}, "coulomb")):
        base["friction"] = friction
        scene = parse_scene(base)
        assert scene.solve_kwargs().get("mu") == friction.get("mu")
        _, solution = scene.solve()
        assert solution.friction == law


def test_scene_auto_grading_targets_the_contact_zone() -> None:
    s = parse_scene(load_toml(SCENE))
    a = (2 * 2.0 * 0.005) ** 0.5
    assert s.contact_segment((-1.0, 1.0)) == pytest.approx((-2 * a, 2 * a))
    s.sections["obstacle"] = {"shape": "flat"}
    assert s.contact_segment((-1.0, 1.0)) == (-1.0, 1.0)
    s.sections["obstacle"] = {"shape": "polyline", "xi": [-1.0, 0.0, 1.0], "gap": [0.1, 0.0, 0.1], "approach": 0.01}
    lo, hi = s.contact_segment((-1.0, 1.0))
    assert lo == pytest.approx(-0.2, abs=2e-3) and hi == pytest.approx(0.2, abs=2e-3)


def load_toml(text: str) -> dict:  # type: ignore[type-arg]
    import tomllib

    return tomllib.loads(text)


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (lambda d: d["obstacle"].update(radus=1.0), "scene key 'obstacle.radus' is not known"),
        (lambda d: d.update(solvr={}), "scene key 'solvr' is not known"),
        (lambda d: d["material"].update(young="stiff"), "scene key 'material.young' must be a number"),
        (lambda d: d["material"].pop("poisson"), "scene key 'material.poisson' is required"),
        (lambda d: d["body"].update(x=[0.0]), "scene key 'body.x' must be a list of two numbers"),
        (lambda d: d["obstacle"].update(shape="cone"), "scene key 'obstacle.shape' must be one of"),
        (lambda d: d["friction"].update(mu=0.3), "exclude each other"),
        (lambda d: d["solver"].update(qp_max_iter=1.5), "scene key 'solver.qp_max_iter' must be an integer"),
        (lambda d: d["discretization"].update(grading="some"), "scene key 'discretization.grading'"),
        (lambda d: d["material"].update(model="plane"), "'material.model' must be one of 'plane_strain', 'plane_stress'"),
    ],
)
def test_scene_errors_name_the_key(edit, message: str) -> None:  # type: ignore[no-untyped-def]
    d = load_toml(SCENE)
    edit(d)
    with pytest.raises(SceneError, match=message.replace("(", r"\(")) as info:
        parse_scene(d)
    assert isinstance(info.value, tribo.TriboError)


def test_a_plane_stress_scene_runs_and_says_so(tmp_path: Path) -> None:
    """`[material] model = "plane_stress"` (issue 41): the run's summary names the model and its VTU file has
    σ_zz = 0; the same scene in plane strain has σ_zz ≠ 0."""
    import meshio

    for model, zero in (("plane_stress", True), ("plane_strain", False)):
        d = load_toml(SCENE)
        d["material"]["model"] = model
        out = tmp_path / model
        run_scene(parse_scene(d), out, plots=False)
        assert json.loads((out / "summary.json").read_text())["model"] == model
        szz = meshio.read(out / "result.vtu").cell_data["sigma_zz"][0]
        assert bool(np.all(szz == 0.0)) is zero


def test_scene_build_errors(tmp_path: Path) -> None:
    d = load_toml(SCENE)
    d["obstacle"] = {"shape": "circle"}
    with pytest.raises(SceneError, match="obstacle.radius"):
        parse_scene(d).build()
    d = load_toml(SCENE)
    d["material"]["young"] = -1.0
    with pytest.raises(tribo.SettingsError) as info:
        parse_scene(d).build()
    assert any("scene" in n for n in info.value.__notes__)


def test_cli_reports_errors(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    bad = tmp_path / "bad.toml"
    bad.write_text(SCENE.replace("radius = 2.0", "radus = 2.0"))
    assert main(["run", str(bad), "--out", str(tmp_path / "o")]) == 1
    assert "scene key 'obstacle.radus' is not known" in capsys.readouterr().err
    assert main(["run", str(tmp_path / "missing.toml"), "--out", str(tmp_path / "o")]) == 1
    (tmp_path / "broken.toml").write_text("[body\n")
    assert main(["run", str(tmp_path / "broken.toml"), "--out", str(tmp_path / "o")]) == 1


def test_cli_not_converged_exit_code(tmp_path: Path) -> None:
    scene = tmp_path / "cap.toml"
    scene.write_text(SCENE.replace("threshold = 0.2", "mu = 0.3") + "fp_max_iter = 1\n")
    assert main(["-q", "run", str(scene), "--out", str(tmp_path / "o"), "--no-plots"]) == 3
    assert json.loads((tmp_path / "o" / "summary.json").read_text())["status"] == "max_iterations"


def test_mesh_file_scene(tmp_path: Path) -> None:
    from test_io import MSH22

    (tmp_path / "square.msh").write_text(MSH22)
    scene = tmp_path / "sq.toml"
    scene.write_text(
        'body.mesh = "square.msh"\nmaterial.young = 1.0\nmaterial.poisson = 0.3\nsupports.clamped = "bottom"\n'
        'contact.edge_set = "top"\nobstacle.approach = 0.01\n'
    )
    problem, solution = load_scene(scene).solve()
    assert solution.report.converged and problem.mesh.n_triangles == 4


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        # D14: values the binding could not convert (OverflowError) are refused in the scene, naming the key.
        (lambda d: d["solver"].update(qp_max_iter=-1), "'solver.qp_max_iter' must be an integer in [0, 4294967295]"),
        (lambda d: d["solver"].update(qp_max_iter=2**32), "'solver.qp_max_iter' must be an integer in [0, 4294967295]"),
        (lambda d: d["solver"].update(fp_max_iter=-5), "'solver.fp_max_iter' must be an integer in [0, "),
        (lambda d: d["material"].update(young=float("nan")), "'material.young' must be a finite number"),
        (lambda d: d["obstacle"].update(approach=float("inf")), "'obstacle.approach' must be a finite number"),
        (lambda d: d["material"].update(young=10**400), "'material.young' must be a finite number"),
        (lambda d: d["body"].update(x=[1.0, 1.0]), "'body.x' must be an increasing range"),
        # D15: keys of another obstacle shape are refused, as they were for a flat obstacle.
        (lambda d: d["obstacle"].update(xi=[0.0, 1.0]), "'obstacle.xi' does not apply to a parabola obstacle"),
        (lambda d: d["obstacle"].update(shape="circle", gap=[0.0]), "'obstacle.gap' does not apply to a circle"),
        (
            lambda d: d["obstacle"].update(shape="polyline", xi=[-1.0, 1.0], gap=[0.0, 0.0]),
            "'obstacle.radius' does not apply to a polyline obstacle",
        ),
        (lambda d: d["obstacle"].update(shape="flat"), "'obstacle.radius' does not apply to a flat obstacle"),
        (lambda d: d["obstacle"].pop("radius"), "'obstacle.radius' is required for a parabola"),
    ],
)
def test_scene_values_the_core_cannot_take(edit, message: str) -> None:  # type: ignore[no-untyped-def]
    d = load_toml(SCENE)
    edit(d)
    with pytest.raises(SceneError, match=re.escape(message)) as info:
        parse_scene(d)
    assert info.value.details["key"] in message


def test_polyline_center_is_refused() -> None:
    d = load_toml(SCENE)
    d["obstacle"] = {"shape": "polyline", "xi": [-1.0, 1.0], "gap": [0.0, 0.0], "center": 0.5}
    with pytest.raises(SceneError, match="'obstacle.center' does not apply to a polyline obstacle"):
        parse_scene(d)


def test_scene_build_checks_before_the_grading_uses_values() -> None:
    """D14: a negative radius with automatic grading was a 'math domain error' in contact_segment; a tiny h
    on a uniform grid overflowed the binding's integer conversion."""
    d = load_toml(SCENE)
    d["obstacle"]["radius"] = -1.0
    with pytest.raises(tribo.ContactGeometryError, match="radius"):
        parse_scene(d).build()
    with pytest.raises(tribo.ContactGeometryError, match="radius"):
        parse_scene(d).contact_segment((-1.0, 1.0))
    d = load_toml(SCENE)
    d["discretization"] = {"grading": "none", "h": 1e-300}
    with pytest.raises(SceneError, match=r"'discretization.h' = 1e-300 makes a grid of about 2e\+300 x 1e\+300"):
        parse_scene(d).build()


def test_scene_file_not_utf8(tmp_path: Path) -> None:
    path = tmp_path / "latin1.toml"
    path.write_bytes(SCENE.replace("small", "caf\xe9").encode("latin-1"))
    with pytest.raises(SceneError, match="is not UTF-8 text"):
        load_scene(path)


def test_a_scene_nested_too_deeply_is_a_scene_error(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """Defect D32: 600 nested arrays made the TOML reader raise RecursionError, which `tribo run` reported
    as an internal error (exit 2) and `load_scene` raised as it was."""
    path = tmp_path / "nested.toml"
    path.write_text(SCENE + "\n[extra]\nvalue = " + "[" * 600 + "]" * 600 + "\n")
    with pytest.raises(SceneError, match="nests arrays or inline tables too deeply"):
        load_scene(path)
    assert main(["-q", "run", str(path), "--out", str(tmp_path / "o")]) == 1
    assert "too deeply" in one_error_line(capsys)


def one_error_line(capsys: pytest.CaptureFixture[str], prefix: str = "tribo: error: ") -> str:
    """The only line on stderr besides scene warnings (the runs below are quiet), which starts with
    `prefix`; no traceback."""
    err = "".join(
        line for line in capsys.readouterr().err.splitlines(keepends=True) if not line.startswith("tribo: warning: ")
    )
    assert "Traceback" not in err and len(err.splitlines()) == 1 and err.startswith(prefix), err
    return err


@pytest.mark.parametrize(
    ("scene", "message"),
    [
        (SCENE.replace("radius = 2.0", "radius = -1.0"), "radius must be positive"),
        (SCENE.replace("qp_tol = 1e-9", "qp_max_iter = -1"), "'solver.qp_max_iter' must be an integer in [0, "),
        (SCENE.replace("qp_tol = 1e-9", "qp_max_iter = 4294967296"), "'solver.qp_max_iter' must be an integer in [0, "),
        (SCENE.replace("qp_tol = 1e-9", "fp_max_iter = -5"), "'solver.fp_max_iter' must be an integer in [0, "),
        (SCENE.replace("h = 0.25\nh_min = 0.03", 'grading = "none"\nh = 1e-300'), "'discretization.h' = 1e-300"),
        (SCENE.replace("radius = 2.0", "radius = 2.0\nxi = [0.0, 1.0]"), "'obstacle.xi' does not apply"),
    ],
)
def test_cli_bad_scenes_give_one_error_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], scene: str, message: str
) -> None:
    """D14: each of these printed a traceback (math domain error, OverflowError…)."""
    path = tmp_path / "bad.toml"
    path.write_text(scene)
    assert main(["-q", "run", str(path), "--out", str(tmp_path / "o"), "--no-plots"]) == 1
    assert message in one_error_line(capsys)


def test_cli_unreadable_input_and_output(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    good = tmp_path / "good.toml"
    good.write_text(SCENE)
    latin1 = tmp_path / "latin1.toml"
    latin1.write_bytes(SCENE.replace("small", "caf\xe9").encode("latin-1"))
    assert main(["-q", "run", str(latin1), "--out", str(tmp_path / "o")]) == 1
    assert "is not UTF-8 text" in one_error_line(capsys)
    (tmp_path / "file").write_text("")
    assert main(["-q", "run", str(good), "--out", str(tmp_path / "file")]) == 1
    assert "exists and is not a directory" in one_error_line(capsys)
    assert main(["-q", "run", str(good), "--out", str(tmp_path / "file" / "sub"), "--no-plots"]) == 1
    assert "cannot write the results into" in one_error_line(capsys)


def test_cli_error_notes_stay_on_the_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "soft.toml"
    path.write_text(SCENE.replace("young = 100.0", "young = -1.0"))
    assert main(["-q", "run", str(path), "--out", str(tmp_path / "o")]) == 1
    assert "(SettingsError; while building the scene 'small Tresca scene')" in one_error_line(capsys)


def test_cli_ctrl_c_ends_with_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """A KeyboardInterrupt (here from the progress callback, as Ctrl-C during a solve arrives) is not an
    internal error: one line, exit code 130."""
    import tribo.run

    def interrupt(*args: object) -> None:
        raise KeyboardInterrupt

    monkeypatch.setattr(tribo.run, "_progress", interrupt)
    path = tmp_path / "coulomb.toml"
    path.write_text(SCENE.replace("threshold = 0.2", "mu = 0.3"))
    assert main(["-q", "run", str(path), "--out", str(tmp_path / "o"), "--no-plots"]) == 130
    assert one_error_line(capsys, "tribo: interrupted") == "tribo: interrupted\n"


class PanicException(BaseException):
    """Stands for pyo3's PanicException, which derives from BaseException, not Exception."""


@pytest.mark.parametrize("exception", [RuntimeError("boom"), PanicException("boom")])
def test_cli_internal_errors_give_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch, exception: BaseException
) -> None:
    import tribo.run

    def fail(*args: object) -> None:
        raise exception

    monkeypatch.setattr(tribo.run, "write_contact_csv", fail)
    path = tmp_path / "good.toml"
    path.write_text(SCENE)
    assert main(["-q", "run", str(path), "--out", str(tmp_path / "o"), "--no-plots"]) == 2
    line = one_error_line(capsys, "tribo: internal error: ")
    assert f"{type(exception).__name__}: boom (please report it)" in line


def test_run_reports_the_estimated_error(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """Every run prints its estimated error, and the same numbers are in summary.json (strict JSON: a
    relative estimate without a reference is null), in the report and as cell data in the VTU."""
    import meshio

    path = tmp_path / "s.toml"
    path.write_text(SCENE, encoding="utf-8")
    assert main(["run", str(path), "--out", str(tmp_path / "o"), "--no-plots"]) == 0
    printed = re.search(r"estimated error: ([0-9.e+-]+) % in the contact tractions", capsys.readouterr().out)
    assert printed, "the run prints the traction estimate"
    summary = json.loads((tmp_path / "o" / "summary.json").read_text(), parse_constant=lambda c: pytest.fail(c))
    est = summary["estimate"]
    assert set(est) == {"total", "bulk", "gamma_c", "contact", "friction", "energy_relative", "traction", "traction_relative",
                        "traction_hierarchical", "traction_hierarchical_relative", "traction_calibrated_relative",
                        "normal_force_error",
                        "tangential_force_error", "contact_width_error", "stick_width_error"}
    # Computed only when asked (an adaptive run with stop_on, or solve(error_bars=True)); formed only by a loop.
    assert est["traction_hierarchical"] is None and est["normal_force_error"] is None
    assert est["traction_calibrated_relative"] is None
    assert est["total"] ** 2 == pytest.approx(est["bulk"] ** 2 + est["gamma_c"] ** 2 + est["contact"] ** 2 + est["friction"] ** 2)
    assert float(printed.group(1)) == pytest.approx(100 * est["traction_relative"], rel=0.05)
    problem, solution = load_scene(path).solve()
    assert solution.report.estimate["total"] == pytest.approx(est["total"])
    eta = meshio.read(tmp_path / "o" / "result.vtu").cell_data["error_indicator"][0]
    assert eta.shape == (problem.mesh.n_triangles,) and np.allclose(eta, solution.estimator)
    assert np.sqrt(np.sum(eta**2)) == pytest.approx(est["total"])
    zeta = meshio.read(tmp_path / "o" / "result.vtu").cell_data["traction_indicator"][0]
    assert np.allclose(zeta, solution.traction_estimator) and np.sqrt(np.sum(zeta**2)) == pytest.approx(est["traction"])


ADAPT_SCENE = """
title = "off-centre cylinder on a coarse uniform mesh"
[body]
x = [-2.0, 2.0]
y = [-2.0, 0.0]
[material]
young = 200.0
poisson = 0.3
[supports]
clamped = ["bottom"]
[contact]
edge_set = "top"
[obstacle]
shape = "circle"
radius = 1.0
center = 0.3
approach = 0.01
[discretization]
grading = "none"
h = 0.5
[adapt]
tol = 0.05
"""


def test_run_adapts_a_scene_with_an_adapt_table(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """``[adapt]``: the outputs are the last level's, on its refined mesh, and adapt.csv lists the levels; the
    enriched answer handed back (``stop_on = "enriched"``) is said, and so is what its estimate is."""
    import meshio

    path = tmp_path / "a.toml"
    enriched = ADAPT_SCENE + 'stop_on = "enriched"\n'
    path.write_text(enriched, encoding="utf-8")
    assert main(["run", str(path), "--out", str(tmp_path / "o"), "--plots"]) == 0
    printed = capsys.readouterr().out
    with (tmp_path / "o" / "adapt.csv").open(encoding="utf-8") as f:
        assert f.readline().startswith("# stop: tolerance")
        rows = list(csv.DictReader(f))
    assert len(rows) > 3 and rows[0]["unknowns"] == "72"
    assert float(rows[-1]["relative"]) <= 0.05 < float(rows[-2]["relative"])
    summary = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert summary["n_free"] == int(rows[-1]["unknowns"]) and summary["status"] == "converged"
    assert summary["adapt_stop"] == "tolerance" and summary["warnings"] == []
    assert summary["adapt_handed_back"] is True and float(rows[-1]["seconds"]) == 0.0
    assert [r["enriched"] for r in rows[-2:]] == ["False", "True"]
    assert "the answer enriched for the last level's estimate handed back" in printed
    assert "half its change from the level it enriched, sharp but not a bound" in printed
    assert _read(summary["estimate"]) == pytest.approx(float(rows[-1]["relative"]))
    vtu = meshio.read(tmp_path / "o" / "result.vtu")
    assert len(vtu.cells_dict["triangle"]) == int(rows[-1]["triangles"])
    assert (tmp_path / "o" / "adapt.png").stat().st_size > 0
    # Only the last level is written by default (issue 38: the levels were solved again to be written).
    assert not (tmp_path / "o" / "levels").exists() and not (tmp_path / "o" / "adapt.pvd").exists()
    # With write_levels, the level series: one VTU per level in adapt.pvd, each on its level's mesh.
    import xml.etree.ElementTree as ET

    path.write_text(enriched + "write_levels = true\n", encoding="utf-8")
    assert main(["-q", "run", str(path), "--out", str(tmp_path / "o"), "--no-plots"]) == 0
    files = [d.get("file") for d in ET.parse(tmp_path / "o" / "adapt.pvd").getroot().iter("DataSet")]
    assert files == [f"levels/level_{k:03d}.vtu" for k in range(len(rows))]
    for f, row in zip(files, rows, strict=True):
        assert len(meshio.read(tmp_path / "o" / str(f)).cells_dict["triangle"]) == int(row["triangles"])
    # `tribo run --all-files` writes them too, the scene unchanged.
    path.write_text(enriched, encoding="utf-8")
    assert main(["-q", "run", str(path), "--out", str(tmp_path / "all"), "--all-files"]) == 0
    written = [d.get("file") for d in ET.parse(tmp_path / "all" / "adapt.pvd").getroot().iter("DataSet")]
    assert written == files and all((tmp_path / "all" / str(f)).is_file() for f in files)


def _read(estimate: dict[str, Any]) -> float:
    """The relative traction estimate the adaptive loop reads in a summary's ``estimate``: the smaller of the
    bound and the hierarchical estimate where the loop computed the latter (by default), the calibrated bound on the
    level after, else the bound."""
    sharp = estimate["traction_hierarchical_relative"]
    if sharp is None:
        sharp = estimate.get("traction_calibrated_relative")
    bound = float(estimate["traction_relative"])
    return bound if sharp is None else min(bound, float(sharp))


def test_a_tolerance_not_reached_is_said(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """Issue 37: with ``adapt.tol = 1e-6`` out of reach, ``tribo -q run`` printed ``converged`` and
    summary.json had no stop reason and no warning. Now the status lines say why the loop stopped,
    summary.json has ``adapt_stop`` and the warning, which names the tolerance and the last estimate."""
    path = tmp_path / "a.toml"
    path.write_text(ADAPT_SCENE.replace("tol = 0.05", "tol = 1e-6\nmax_unknowns = 2000"), encoding="utf-8")
    assert main(["-q", "run", str(path), "--out", str(tmp_path / "o"), "--no-plots"]) == 0
    out, err = capsys.readouterr()
    assert "adaptive loop stopped on max_unknowns" in out
    summary = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert summary["adapt_stop"] == "max_unknowns" and summary["status"] == "converged"
    relative = _read(summary["estimate"])
    (warning,) = [w for w in summary["warnings"] if "adaptive loop" in w]
    assert "max_unknowns" in warning and "adapt.tol = 1e-06" in warning and f"{relative:.3g}" in warning
    assert f"tribo: warning: {warning}" in err


def test_run_prints_error_bars_when_the_scene_asks(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """``[estimate] error_bars = true``: ``tribo run`` prints ``P = … ± …`` for P, Q and both widths, as
    summary.json has them; without the key no bars; a history refuses the key by name."""
    path = tmp_path / "s.toml"
    path.write_text(SCENE + "[estimate]\nerror_bars = true\n", encoding="utf-8")
    assert main(["run", str(path), "--out", str(tmp_path / "o"), "--no-plots"]) == 0
    out = capsys.readouterr().out
    said = json.loads((tmp_path / "o" / "summary.json").read_text())
    printed = re.search(r"P = ([0-9.e+-]+) ± ([0-9.e+-]+), Q = ([0-9.e+-]+) ± ([0-9.e+-]+), contact width = "
                        r"([0-9.e+-]+) ± ([0-9.e+-]+), stick width = ([0-9.e+-]+) ± ([0-9.e+-]+)", out)
    assert printed, out
    values = [float(v) for v in printed.groups()]
    keys = ("normal_force", "tangential_force", "contact_width", "stick_width")
    for k, (value, bar) in zip(keys, zip(values[::2], values[1::2])):
        assert value == pytest.approx(said[k], rel=1e-5, abs=1e-12)
        assert bar == pytest.approx(said["estimate"][f"{k}_error"], rel=0.05)
    assert said["estimate"]["normal_force_error"] > 0 and said["contact_width"] > 0
    path.write_text(SCENE, encoding="utf-8")
    assert main(["run", str(path), "--out", str(tmp_path / "p"), "--no-plots"]) == 0
    assert " ± " not in capsys.readouterr().out
    # With [adapt], the last level solved again with its bars: the same mesh as adapt.csv's last row.
    path.write_text(ADAPT_SCENE + "[estimate]\nerror_bars = true\n", encoding="utf-8")
    assert main(["run", str(path), "--out", str(tmp_path / "a"), "--no-plots"]) == 0
    assert re.search(r"P = [0-9.e+-]+ ± [0-9.e+-]+, Q = ", capsys.readouterr().out)
    said = json.loads((tmp_path / "a" / "summary.json").read_text())
    with (tmp_path / "a" / "adapt.csv").open(encoding="utf-8") as f:
        f.readline()
        last = list(csv.DictReader(f))[-1]
    assert said["n_free"] == int(last["unknowns"]) and said["estimate"]["normal_force_error"] > 0
    path.write_text(SCENE + "[estimate]\nerror_bars = true\n[history]\nshift = [0.0, 0.001]\n", encoding="utf-8")
    with pytest.raises(SceneError, match="estimate.error_bars"):
        load_scene(path)


def test_run_stops_on_the_hierarchical_estimate_and_says_which(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """``[adapt] stop_on = "hierarchical"`` (the default): the run prints the estimate it stopped on and the bound, each
    named: here the calibrated bound (the bound times the ratio of the two estimates on the level before, which the
    loop estimated); summary.json and adapt.csv carry it; a name that is not an option is a SceneError."""
    path = tmp_path / "a.toml"
    path.write_text(ADAPT_SCENE, encoding="utf-8")
    assert main(["run", str(path), "--out", str(tmp_path / "o"), "--no-plots"]) == 0
    out = capsys.readouterr().out
    printed = re.search(r"estimated error: ([0-9.e+-]+) % in the contact tractions \(L2 of Γ_C; the bound calibrated "
                        r"on the level before, sharp but not a bound; the bound: ([0-9.e+-]+) %\)", out)
    assert printed, "the run names the estimate it prints"
    est = json.loads((tmp_path / "o" / "summary.json").read_text())["estimate"]
    # No enriched solve on the last level: no error bars from the loop, and the run says how to ask for them.
    assert " ± " not in out and "set error_bars = true" in out and est["normal_force_error"] is None
    assert est["traction_hierarchical_relative"] is None
    assert float(printed.group(1)) == pytest.approx(100 * est["traction_calibrated_relative"], rel=0.05)
    assert float(printed.group(2)) == pytest.approx(100 * est["traction_relative"], rel=0.05)
    assert est["traction_calibrated_relative"] <= 0.05 < est["traction_relative"]
    with (tmp_path / "o" / "adapt.csv").open(encoding="utf-8") as f:
        f.readline()
        rows = list(csv.DictReader(f))
    last, before = rows[-1], rows[-2]
    assert float(last["estimate_traction_calibrated_relative"]) == pytest.approx(est["traction_calibrated_relative"])
    # The level before was estimated: its ratio of the two estimates times the last bound.
    ratio = float(before["relative"]) / float(before["estimate_traction_relative"])
    assert float(before["estimate_traction_hierarchical_relative"]) == pytest.approx(float(before["relative"]))
    assert est["traction_calibrated_relative"] == pytest.approx(ratio * est["traction_relative"], rel=1e-9)
    assert rows[0]["estimate_traction_hierarchical_relative"] == rows[0]["estimate_traction_calibrated_relative"] == "nan"
    path.write_text(ADAPT_SCENE + 'stop_on = "sharpest"\n', encoding="utf-8")
    with pytest.raises(SceneError, match="adapt.stop_on"):
        load_scene(path)


@pytest.mark.parametrize("turned", [False, True])
def test_run_adapts_a_history(tmp_path: Path, turned: bool) -> None:
    """``[adapt]`` with ``[history]``: every level solves the history; the history's outputs are those of
    the last mesh, with adapt.csv beside them. The cylinder is dragged by its shift, or (``turned``) given as a disc
    turned about its centre step by step (``[history] angle``), which each level's files turn alike."""
    import meshio

    scene = ADAPT_SCENE.replace("tol = 0.05", "tol = 0.2\non = [0, 4]\nwrite_levels = true") + (
        "[friction]\nmu = 0.3\n[history]\nshift = [0.0, 0.004]\nsteps = 4\n"
    )
    if turned:
        scene = scene.replace('shape = "circle"\nradius = 1.0\ncenter = 0.3\n', 'shape = "disc"\nradius = 1.0\n'
                              'center = [0.3, 1.0]\nrotation = { center = [0.3, 1.0], angle = 0.0 }\n')
        scene = scene.replace("shift = [0.0, 0.004]", "angle = [0.0, 0.004]")
        assert "angle = [0.0, 0.004]" in scene and 'shape = "disc"' in scene
    path = tmp_path / "h.toml"
    path.write_text(scene, encoding="utf-8")
    assert main(["run", str(path), "--out", str(tmp_path / "o"), "--no-plots"]) == 0
    with (tmp_path / "o" / "adapt.csv").open(encoding="utf-8") as f:
        assert f.readline().startswith("# stop: tolerance")
        rows = list(csv.DictReader(f))
    lines = (tmp_path / "o" / "history.csv").read_text(encoding="utf-8").splitlines()
    history = list(csv.DictReader(line for line in lines if not line.startswith("#")))
    assert len(history) == 5 and float(rows[-1]["relative"]) <= 0.2
    step = meshio.read(tmp_path / "o" / "steps" / "step_0004.vtu")
    assert len(step.cells_dict["triangle"]) == int(rows[-1]["triangles"]), "the steps are on the last mesh"
    summary = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert summary["n_free"] == int(rows[-1]["unknowns"]) and summary["status"] == "converged"
    assert summary["adapt_stop"] == "tolerance"
    # The level series: each level's history solved again, its last step on the level's mesh; the last
    # level's equals the history's own last step.
    import xml.etree.ElementTree as ET

    files = [d.get("file") for d in ET.parse(tmp_path / "o" / "adapt.pvd").getroot().iter("DataSet")]
    assert files == [f"levels/level_{k:03d}.vtu" for k in range(len(rows))]
    for f, row in zip(files, rows, strict=True):
        assert len(meshio.read(tmp_path / "o" / str(f)).cells_dict["triangle"]) == int(row["triangles"])
    last = meshio.read(tmp_path / "o" / str(files[-1]))
    np.testing.assert_allclose(last.point_data["displacement"], step.point_data["displacement"], rtol=0, atol=1e-12)


def test_adapt_table_errors_name_the_key(tmp_path: Path) -> None:
    with pytest.raises(SceneError, match="adapt.marking"):
        parse_scene(tomllib_loads(ADAPT_SCENE + 'marking = "greedy"\n'))
    with pytest.raises(SceneError, match="adapt.on"):
        parse_scene(tomllib_loads(ADAPT_SCENE + "on = [1]\n"))
    with pytest.raises(SceneError, match="adapt.on"):
        parse_scene(tomllib_loads(ADAPT_SCENE + "on = [-1]\n[history]\nshift = [0.0, 0.004]\n"))
    with pytest.raises(SceneError, match="adapt.theta") as e:
        parse_scene(tomllib_loads(ADAPT_SCENE + "theta = 2.0\n")).solve_adaptive()
    assert isinstance(e.value.__cause__, tribo.SettingsError), "the core's check, converted"


def tomllib_loads(text: str) -> dict[str, object]:
    import tomllib

    return tomllib.loads(text)


def test_a_closed_pipe_stops_quietly(tmp_path: Path) -> None:
    """``tribo run … | head``: the reader of the printed report is gone before it is printed; the results
    are written, the exit code is a shell's for SIGPIPE (141) and nothing calls it an internal error."""
    from tribo.scene import scene_path

    proc = subprocess.Popen(
        [sys.executable, "-m", "tribo.cli", "-q", "run", str(scene_path("block")), "--out", str(tmp_path / "o"),
         "--no-plots"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE,
    )
    assert proc.stdout is not None
    proc.stdout.close()
    _, err = proc.communicate()
    assert proc.returncode == 141 and "internal error" not in err.decode() and not err.strip(), err.decode()
    assert (tmp_path / "o" / "summary.json").is_file()


def test_run_reports_its_time_and_peak_memory(tmp_path: Path) -> None:
    """``tribo run`` prints and writes the wall time and the process's peak resident memory at the end of
    the solve: at most the kernel's high-water mark read from /proc after the run, and not the peak of
    the (larger) process that started it, which ``getrusage`` would carry across ``exec``."""
    scene = tmp_path / "s.toml"
    scene.write_text(SCENE)
    code = (
        "import sys; from tribo.cli import main; code = main(sys.argv[1:]); "
        "print('VmHWM', [l.split()[1] for l in open('/proc/self/status') if l.startswith('VmHWM')][0]); "
        "sys.exit(code)"
    )

    def run() -> tuple[str, dict[str, Any], float]:
        """The run's output, its summary and the child's VmHWM after it, in MiB."""
        r = subprocess.run(
            [sys.executable, "-c", code, "run", str(scene), "--out", str(tmp_path / "o"), "--no-plots"],
            capture_output=True,
            text=True,
            timeout=120,
        )
        assert r.returncode == 0, r.stderr
        hwm = re.search(r"VmHWM (\d+)", r.stdout)
        assert hwm is not None, r.stdout
        return r.stdout, json.loads((tmp_path / "o" / "summary.json").read_text()), int(hwm.group(1)) / 1024.0

    stdout, summary, vm_hwm_mib = run()
    peak, seconds = summary["process_peak_memory_mb"], summary["wall_seconds"]
    assert 0.0 < seconds < 120.0
    assert re.search(rf"{seconds:.3g} s \(factorization .* s, QPs .* s\), peak memory {peak:.0f} MiB", stdout)
    # An interpreter with numpy and the extension loaded holds tens of MiB. The high-water mark read later is
    # the larger, up to Linux's bookkeeping: VmHWM is max(hiwater_rss, rss), hiwater_rss is recorded when memory
    # is unmapped (not when the allocator hands pages back with madvise, as mimalloc does) and rss counts each
    # thread's pages in batches of 64 (256 KiB per thread; the writers run in threads), so a later read may fall
    # short (by 44 KiB once in CI). 1 MiB covers that and still tells apart the parent's 64 MiB below.
    slack = 1.0
    assert 20.0 < peak <= vm_hwm_mib + slack
    ballast = np.ones(64 << 20, dtype=np.uint8)  # this process's peak: 64 MiB above the child's
    _, summary, vm_hwm_mib = run()
    del ballast
    assert summary["process_peak_memory_mb"] <= vm_hwm_mib + slack


def test_a_bad_adaptive_setting_names_the_scene_key(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """Issue 37: ``[adapt] tol = 0`` was refused naming the core's setting ``adapt_tol``, after meshing; the
    scene's reader refuses it and ``tribo run`` names the scene key ``adapt.tol`` (the core's check and words,
    converted)."""
    path = tmp_path / "a.toml"
    history = "[friction]\nmu = 0.3\n[history]\nshift = [0.0, 0.004]\nsteps = 2\n"
    for edit, key, more in (("tol = 0.0", "adapt.tol", ""), ("tol = 0.05\ntheta = 1.5", "adapt.theta", ""),
                            ("tol = 0.05\nmax_unknowns = 10", "adapt.max_unknowns", ""),
                            ("tol = 0.05\non = [9]", "adapt.on", history)):
        path.write_text(ADAPT_SCENE.replace("tol = 0.05", edit) + more, encoding="utf-8")
        with pytest.raises(SceneError, match=f"scene key '{key}'") as e:
            # tol and theta when the scene is read, before any mesh; the steps and the first mesh's size
            # when the loop starts.
            scene = load_scene(path)
            assert key in ("adapt.max_unknowns", "adapt.on"), f"{key} passed the reader"
            scene.solve_history_adaptive() if scene.has_history else scene.solve_adaptive()
        assert e.value.details == {"key": key} and "None" not in str(e.value) and ".0:" not in str(e.value)
        assert main(["-q", "run", str(path), "--out", str(tmp_path / "o"), "--no-plots"]) == 1
        assert f"tribo: error: scene key '{key}'" in capsys.readouterr().err
