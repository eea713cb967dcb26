"""Two-body scene files (``[[bodies]]``, ``[contact] secondary/primary/gap``) and what ``tribo run`` writes for
them: the shipped scenes run as tests, the outputs are read back, bad scenes are errors naming the key."""

from __future__ import annotations

import csv
import json
import math
import tomllib
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

import meshio
import numpy as np
import pytest

import tribo
from tribo.cli import main
from tribo.scene import SceneError, load_scene, parse_scene, scene_path

DOCS = Path(__file__).resolve().parents[2] / "docs"


def hertz_l2(problem: tribo.Problem, sol: tribo.Solution, e_star: float, radius: float = 1.0) -> float:
    """Relative L2 error of λ_n (P1, on T_H) against the plane-strain Hertz pressure of the computed force."""
    a = math.sqrt(4.0 * sol.normal_force * radius / (math.pi * e_star))
    p0 = 2.0 * sol.normal_force / (math.pi * a)
    xi = np.unique(np.r_[problem.multiplier_mesh, -a, a])
    x = np.concatenate([np.linspace(l, r, 9)[:-1] for l, r in zip(xi[:-1], xi[1:])] + [xi[-1:]])
    lam = np.interp(x, problem.multiplier_abscissae, sol.lambda_n)
    p = p0 * np.sqrt(np.clip(1.0 - (x / a) ** 2, 0.0, None))
    return float(np.sqrt(np.trapezoid((lam - p) ** 2, x) / np.trapezoid(p**2, x)))


def test_the_two_body_hertz_scene_is_study_8(tmp_path: Path) -> None:
    """The shipped scene is study 8's equal pair at h_min 0.005 (the Rust example): the same unknowns and
    force to round-off, and its pressure as close to Hertz as the study measured on that mesh."""
    out = tmp_path / "out"
    assert main(["-q", "run", str(scene_path("hertz_two_bodies")), "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    with (DOCS / "two_bodies.csv").open(encoding="utf-8") as f:
        row = next(r for r in csv.DictReader(f) if r["pair"] == "equal" and float(r["h_min"]) == 0.005)
    assert summary["n_free"] == int(row["n_free"])
    assert summary["normal_force"] == pytest.approx(float(row["force"]), rel=1e-9)
    # Per body: nodes, triangles and unknowns add up, and the reactions balance the contact force.
    bodies = summary["bodies"]
    assert [b["name"] for b in bodies] == ["lower", "upper"]
    assert sum(b["unknowns"] for b in bodies) == summary["n_free"]
    assert sum(b["nodes"] for b in bodies) == summary["mesh"]["nodes"]
    (lx, ly), (ux, uy) = (b["reaction"] for b in bodies)
    force = summary["normal_force"]
    assert ly == pytest.approx(force, rel=1e-9) and uy == pytest.approx(-force, rel=1e-9)
    assert abs(lx) < 1e-9 * force and abs(ux) < 1e-9 * force
    assert "secondary body" in summary["conventions"]["contact_force"]
    # Against Hertz of the combined modulus, as study 8 measured (the same meshes; this quadrature is not the
    # study's, so the two agree to a few parts in a hundred of the error).
    problem = load_scene(scene_path("hertz_two_bodies")).build()
    sol = problem.solve()
    error = hertz_l2(problem, sol, e_star=200.0 / (2 * (1 - 0.3**2)))
    assert error == pytest.approx(float(row["hertz_l2"]), rel=0.05)


def test_run_writes_one_file_per_body_and_a_multiblock(tmp_path: Path) -> None:
    text = scene_path("hertz_two_bodies").read_text(encoding="utf-8").replace("h_min = 0.005", "h_min = 0.04")
    (tmp_path / "s.toml").write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    assert main(["-q", "run", str(tmp_path / "s.toml"), "--out", str(out), "--no-plots"]) == 0
    problem = load_scene(tmp_path / "s.toml").build()
    whole = meshio.read(out / "result.vtu")
    blocks = ET.parse(out / "result.vtm").getroot()
    files = {d.get("name"): d.get("file") for d in blocks.iter("DataSet")}
    assert files == {"lower": "result_lower.vtu", "upper": "result_upper.vtu"}
    for name, (n0, n1, t0, t1), _ in problem.bodies:
        part = meshio.read(out / files[name])
        np.testing.assert_array_equal(part.points, whole.points[n0:n1])
        np.testing.assert_array_equal(part.cells_dict["triangle"], whole.cells_dict["triangle"][t0:t1] - n0)
        np.testing.assert_array_equal(part.point_data["displacement"], whole.point_data["displacement"][n0:n1])
        np.testing.assert_array_equal(part.cell_data["von_mises"][0], whole.cell_data["von_mises"][0][t0:t1])
    # The upper body went down by its prescribed 0.01 at the top.
    top = meshio.read(out / "result_upper.vtu")
    at_top = np.isclose(top.points[:, 1], 1.0)
    np.testing.assert_allclose(top.point_data["displacement"][at_top, 1], -0.01)


def test_the_two_body_fretting_scene_traces_a_loop(tmp_path: Path) -> None:
    out = tmp_path / "out"
    assert main(["-q", "run", str(scene_path("fretting_two_bodies")), "--out", str(out), "--plots"]) == 0
    with (out / "history.csv").open(encoding="utf-8") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    assert len(rows) == 34
    x = np.array([float(r["upper.top.x"]) for r in rows])
    y = np.array([float(r["upper.top.y"]) for r in rows])
    q = np.array([float(r["tangential_force"]) for r in rows])
    p = np.array([float(r["normal_force"]) for r in rows])
    assert y[0] == -0.0025 and np.all(y[3:] == -0.01) and x[9] == pytest.approx(0.003)
    # Equal materials (β = 0): shearing leaves the normal force where the press put it.
    assert np.abs(p[3:] / p[3] - 1.0).max() < 1e-3
    # Below μP, with hysteresis: at x = 0 on the way back and on the way out, Q has opposite signs.
    assert np.all(np.abs(q) < 0.3 * p)
    back, out_again = 15, 27
    assert x[back] == pytest.approx(0.0, abs=1e-12) and x[out_again] == pytest.approx(0.0, abs=1e-12)
    assert q[back] * q[out_again] < 0.0
    assert (out / "history_loop.png").is_file() and (out / "result.pvd").is_file()
    assert (out / "steps" / "step_0000.vtu").is_file()
    assert not (out / "steps" / "step_0000.vtm").exists(), "the series keeps the joined mesh (cell data 'body')"


def test_an_adaptive_two_body_history_runs_and_writes_its_levels(tmp_path: Path) -> None:
    """``[adapt]`` with ``[[bodies]]`` and a ``[history]`` that moves a support: the loop refines both bodies
    from coarse uniform meshes, the history runs on the last mesh, and every level's joined mesh is written
    in the series (read back with meshio: cell data 'body' splits it as the level's bodies)."""
    text = scene_path("hertz_two_bodies").read_text(encoding="utf-8")
    text = text.replace("grading = [-0.15, 0.15], h = 0.5, h_min = 0.005, growth = 0.15",
                        'grading = "none", h = 0.5')
    text = text.replace('{ kind = "displacement", edge_set = "top", y = -0.01 }',
                        '{ kind = "displacement", edge_set = "top", x = 0.0, y = -0.01 }')
    text = text.replace('  { kind = "displacement", edge_set = "left", x = 0.0 },\n', "")
    text += (
        "\n[friction]\nmu = 0.3\n"
        '\n[history]\ndisplacements = { "upper.top.x" = [0.0, 0.001] }\nsteps = 2\n'
        "\n[adapt]\ntol = 0.3\nwrite_levels = true\n"
    )
    scene = tmp_path / "s.toml"
    scene.write_text(text, encoding="utf-8")
    assert load_scene(scene).build().n_free < 1000, "the bodies start coarse"
    out = tmp_path / "out"
    assert main(["-q", "run", str(scene), "--out", str(out), "--no-plots"]) == 0
    with (out / "adapt.csv").open(encoding="utf-8") as f:
        levels = list(csv.DictReader(line for line in f if not line.startswith("#")))
    assert len(levels) > 2 and float(levels[-1]["relative"]) <= 0.3
    with (out / "history.csv").open(encoding="utf-8") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    assert [float(r["upper.top.x"]) for r in rows] == [0.0, 0.0005, 0.001]
    q = [float(r["tangential_force"]) for r in rows]
    assert q[0] < q[1] < q[2] < 0.3 * float(rows[2]["normal_force"])
    series = ET.parse(out / "adapt.pvd").getroot()
    files = [d.get("file") for d in series.iter("DataSet")]
    assert len(files) == len(levels)
    last = meshio.read(out / str(files[-1]))
    assert len(last.cells_dict["triangle"]) == int(levels[-1]["triangles"])
    body = last.cell_data["body"][0]
    assert set(np.unique(body)) == {0, 1} and np.all(np.diff(body) >= 0), "the lower body's triangles first"


def test_a_punch_held_by_the_contact_runs_from_a_scene(tmp_path: Path) -> None:
    """The upper block of the two-body Hertz scene without a support in y, pushed down by a traction on
    its top (``supports`` leaves it free, ``loads`` presses it): the contact holds it and carries the load,
    and the summary's reactions say the lower body's clamp takes it all."""
    text = scene_path("hertz_two_bodies").read_text(encoding="utf-8")
    text = text.replace('  { kind = "displacement", edge_set = "top", y = -0.01 },\n', "")
    text = text.replace('name = "upper"\n', 'name = "upper"\nloads = { tractions = { top = [0.0, -0.07] } }\n')
    text = text.replace("h_min = 0.005", "h_min = 0.02")
    scene = tmp_path / "punch.toml"
    scene.write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    assert main(["-q", "run", str(scene), "--out", str(out), "--no-plots"]) == 0
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    assert summary["status"] == "converged"
    assert summary["normal_force"] == pytest.approx(4.0 * 0.07, rel=1e-9)
    lower, upper = summary["bodies"]
    assert lower["reaction"][1] == pytest.approx(0.28, rel=1e-9) and abs(upper["reaction"][1]) < 1e-9


def two_body_scene(**changes: Any) -> dict[str, Any]:
    data = tomllib.loads(scene_path("hertz_two_bodies").read_text(encoding="utf-8"))
    for dotted, value in changes.items():
        *path, key = dotted.split("__")
        table: Any = data
        for p in path:
            table = table[int(p)] if p.isdigit() else table.setdefault(p, {})
        if value is None:
            del table[key]
        else:
            table[key] = value
    return data


@pytest.mark.parametrize(
    ("changes", "key"),
    [
        ({"body": {"x": [0.0, 1.0], "y": [0.0, 1.0]}}, "body"),
        ({"obstacle": {"shape": "flat"}}, "obstacle"),
        ({"contact__edge_set": "top"}, "contact.edge_set"),
        ({"contact__primary": None}, "contact.primary"),
        ({"contact__gap": {"shape": "parabola"}}, "contact.gap.radius"),
        ({"contact__gap": {"shape": "flat", "radius": 1.0}}, "contact.gap.radius"),
        ({"contact__gap": {"shape": "flat", "approach": 1.0}}, "contact.gap.approach"),
        ({"bodies__0__name": None}, "bodies[0].name"),
        ({"bodies__1__name": "lower"}, "bodies[1].name"),
        ({"bodies__0__material": {"young": 1.0}}, "bodies[0].material.poisson"),
        ({"bodies__0__colour": "red"}, "bodies[0].colour"),
        ({"bodies__0__discretization": {"multiplier_ratio": 2.0}}, "bodies[0].discretization.multiplier_ratio"),
        ({"bodies__1__supports": [{"kind": "glue", "edge_set": "top"}]}, "bodies[1].supports[0].kind"),
        ({"bodies__1__supports": {}}, "bodies[1].supports"),
        ({"history": {"shift": [0.0, 0.1]}}, "history.shift"),
        ({"discretization": {"h_min": 0.1}}, "discretization.h_min"),
        ({"history": {"displacements": {"upper.top.y": "down"}}}, "history.displacements.upper.top.y"),
    ],
)
def test_bad_two_body_scenes_name_the_key(changes: dict[str, Any], key: str) -> None:
    with pytest.raises(SceneError) as info:
        parse_scene(two_body_scene(**changes))
    assert info.value.details["key"] == key, str(info.value)


def test_three_bodies_and_one_body_keys_are_refused() -> None:
    data = two_body_scene()
    data["bodies"].append(dict(data["bodies"][0], name="third"))
    with pytest.raises(SceneError, match="two bodies, got 3"):
        parse_scene(data)
    one = tomllib.loads(scene_path("hertz").read_text(encoding="utf-8"))
    one["contact"]["secondary"] = "a.top"
    with pytest.raises(SceneError, match="needs \\[\\[bodies\\]\\]"):
        parse_scene(one)


def test_scene_errors_the_core_finds_name_what_is_wrong(tmp_path: Path) -> None:
    # An unknown body in the pair: a graded body cannot find its side; on uniform meshes the core's typed
    # error names it.
    with pytest.raises(SceneError, match="body 'lower' is on neither side.*'middle.top'"):
        parse_scene(two_body_scene(contact__secondary="middle.top")).build()
    uniform = {"grading": "none", "h": 0.5}
    with pytest.raises(tribo.ContactGeometryError, match="no body named 'middle'"):
        parse_scene(two_body_scene(contact__secondary="middle.top", bodies__0__discretization=uniform,
                                   bodies__1__discretization=uniform)).build()
    # A history that moves a component no support prescribes.
    data = tomllib.loads(scene_path("fretting_two_bodies").read_text(encoding="utf-8"))
    data["history"]["displacements"]["lower.bottom.x"] = 0.001
    scene = parse_scene(data)
    problem = parse_scene(two_body_scene(bodies__0__discretization={"h_min": 0.04, "grading": [-0.15, 0.15]},
                                         bodies__1__discretization={"h_min": 0.04, "grading": [-0.15, 0.15]})).build()
    with pytest.raises(tribo.SettingsError, match="no prescribed component 'lower.bottom.x'"):
        scene.solve_history(problem)


def test_a_body_with_no_support_is_left_to_the_contact(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """``supports = []``: the upper block rests on the lower one (a flat gap: touching along the line) and
    is held by the contact alone. Pressed by a traction with friction, friction holds it sideways and the
    run converges; without friction nothing holds it along the line, and ``tribo run`` says so, naming the
    body and the motion, with exit code 1 (an input error)."""
    data = two_body_scene(bodies__0__discretization={"h_min": 0.02, "grading": [-0.15, 0.15]},
                          bodies__1__discretization={"h_min": 0.02, "grading": [-0.15, 0.15]})
    data["contact"]["gap"] = {"shape": "flat"}
    data["bodies"][1]["supports"] = []
    data["bodies"][1]["loads"] = {"tractions": {"top": [0.0, -0.07]}}
    problem, solution = parse_scene({**data, "friction": {"mu": 0.3}}).solve()
    assert solution.report.status == "converged" and solution.normal_force == pytest.approx(0.28, rel=1e-9)
    scene = tmp_path / "free.toml"
    lines = [f'[[bodies]]\nname = "{b["name"]}"\nx = {list(b["x"])}\ny = {list(b["y"])}\n'
             f'material = {{ young = {b["material"]["young"]}, poisson = {b["material"]["poisson"]} }}\n'
             f'discretization = {{ grading = [-0.15, 0.15], h_min = 0.02 }}\n' for b in data["bodies"]]
    lines[0] += 'supports = [{ kind = "clamp", edge_set = "bottom" }]\n'
    lines[1] += "supports = []\nloads = { tractions = { top = [0.0, -0.07] } }\n"
    contact = '[contact]\nsecondary = "lower.top"\nprimary = "upper.bottom"\n'
    scene.write_text("\n".join(lines) + contact, encoding="utf-8")
    assert main(["-q", "run", str(scene), "--out", str(tmp_path / "out"), "--no-plots"]) == 1
    err = capsys.readouterr().err
    assert "body 'upper' is held only by the contact" in err and "translation along (1.000, 0.000)" in err, err


def test_auto_grading_of_two_bodies_follows_the_press() -> None:
    """``grading = "auto"`` refines a body toward [c − 2a, c + 2a], a = √(2Rδ) with δ the largest prescribed
    displacement (0.01 here: a = 0.14)."""
    scene = parse_scene(two_body_scene(bodies__0__discretization={"h_min": 0.02},
                                       bodies__1__discretization={"h_min": 0.02}))
    a = math.sqrt(2 * 1.0 * 0.01)
    d = scene.sections["bodies"]["entries"][0].get("discretization", {})
    assert scene.contact_segment((-2.0, 2.0), d) == pytest.approx((-2 * a, 2 * a))
    problem = scene.build()
    assert problem.solve().report.status == "converged"


def test_the_guide_two_body_scene_runs() -> None:
    import re

    page = (DOCS / "guide" / "two-bodies.md").read_text(encoding="utf-8")
    blocks = [b for b in re.findall(r"```toml\n(.*?)```", page, flags=re.S) if "[[bodies]]" in b]
    assert blocks, "docs/guide/two-bodies.md has no two-body scene"
    scene = parse_scene(tomllib.loads(blocks[0]))
    problem, history = scene.solve_history()
    assert history.converged and len(history) == 1 + 3 + 6
    assert history.tangential_force[-1] > 0.0 and np.all(np.abs(history.tangential_force) < 0.3 * history.normal_force)
    picture = re.search(r"!\[[^\]]*\]\(\.\./(two_bodies_scene\.png)\)", page)
    assert picture and (DOCS / picture.group(1)).is_file()
