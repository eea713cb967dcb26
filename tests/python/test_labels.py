"""Issue 38: the labels of what ``tribo run`` writes, read back from the files (and the figures) of real runs
and checked against those runs' data, not against fixed strings: the shift a history states (it said "no
shift" while the obstacle had moved), the way ξ runs (history outputs said "along t" while positions grew
along −t), the zones of ``history.csv``, each step's legend (the Cattaneo–Mindlin gallery said "s = 0" at every
step) and who exerts the force on whom between two bodies (the plots said "the obstacle")."""

from __future__ import annotations

import json
import re
import runpy
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import pytest

from tribo.cli import main
from tribo.scene import scene_path

ROOT = Path(__file__).resolve().parents[2]
SHIFT = 0.003  # the drag's last shift
DRAG = "\n[friction]\nmu = 0.3\n\n[history]\nshift = [0.0, 0.003]\nsteps = [3]\n"


def _number(text: str) -> float:
    return float(text.replace("−", "-"))


def _vector(text: str) -> np.ndarray:
    return np.array([_number(v) for v in text.strip("()").split(",")])


def _comments(path: Path) -> dict[str, str]:
    """A CSV's ``# key: sentence`` lines."""
    lines = path.read_text(encoding="utf-8").splitlines()
    return dict(line[2:].split(": ", 1) for line in lines if line.startswith("# ") and ": " in line)


@pytest.fixture
def figures(monkeypatch: pytest.MonkeyPatch) -> Iterator[dict[str, list[dict[str, Any]]]]:
    """Every figure a run saves, by file name: per axes its title, axis labels and legend entries, read as the
    figure is written."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    seen: dict[str, list[dict[str, Any]]] = {}
    save = Figure.savefig

    def read(self: Figure, fname: Any, *args: Any, **kwargs: Any) -> Any:
        seen[Path(str(fname)).name] = [
            {"title": ax.get_title(), "xlabel": ax.get_xlabel(), "ylabel": ax.get_ylabel(),
             "legend": [t.get_text() for t in ax.get_legend().get_texts()] if ax.get_legend() else []}
            for ax in self.axes
        ]
        return save(self, fname, *args, **kwargs)

    monkeypatch.setattr(Figure, "savefig", read)
    yield seen


@pytest.fixture
def drag(tmp_path: Path, figures: dict[str, list[dict[str, Any]]],
         capsys: pytest.CaptureFixture[str]) -> tuple[Path, str, dict[str, list[dict[str, Any]]]]:
    """A ``[history]`` drag of the Hertz scene (the obstacle moved along −x in three steps), run with its plots:
    its folder, what it printed and its figures."""
    scene = tmp_path / "drag.toml"
    scene.write_text(scene_path("hertz").read_text(encoding="utf-8") + DRAG, encoding="utf-8")
    assert main(["run", str(scene), "--out", str(tmp_path / "out"), "--plots"]) == 0
    return tmp_path / "out", capsys.readouterr().out, figures


def test_a_drag_states_the_shift_of_its_last_step_everywhere(drag: tuple[Path, str, Any]) -> None:
    out, printed, figures = drag
    table = pd.read_csv(out / "history.csv", comment="#")
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    n, t = np.array(summary["normal"]), np.array(summary["tangent"])
    last = table.iloc[-1]
    assert last["shift"] == pytest.approx(SHIFT)
    # The obstacle's motion the summary states is the last step's: −δ n + s t, with δ and s from history.csv.
    motion = np.array(summary["obstacle_motion"])
    np.testing.assert_allclose(motion, -last["approach"] * n + last["shift"] * t, rtol=1e-12)
    said = summary["conventions"]["shift"]
    m = re.fullmatch(r"s = (\S+) along t = (\(.*?\)): the obstacle moved toward ([+−])([xy])", said)
    assert m, said
    assert _number(m[1]) == pytest.approx(last["shift"]) and np.array_equal(_vector(m[2]), t)
    # "toward −x": the motion's component along that axis has that sign, the other none.
    axis = "xy".index(m[4])
    assert np.sign(motion[axis] - (-last["approach"] * n)[axis]) == (1 if m[3] == "+" else -1)
    # The same sentence where the run prints it, in the nodes' CSV (the last step's) and in the tangential plot.
    assert f"shift: {said}" in printed
    assert _comments(out / "contact_nodes.csv")["shift"] == said
    (tangential,) = figures["contact_tangential.png"]
    assert said in tangential["title"]


def test_positions_run_the_way_every_file_says(drag: tuple[Path, str, Any]) -> None:
    out, _, figures = drag
    stated = _comments(out / "contact.csv")["xi"]
    m = re.fullmatch(r"abscissa ξ along Γ_C, increasing with ([xy]) \(along ([+−])t\)", stated)
    assert m, stated
    dofs = pd.read_csv(out / "contact.csv", comment="#")
    t = np.array(json.loads((out / "summary.json").read_text(encoding="utf-8"))["tangent"])
    d_xi = np.diff(dofs["xi"].to_numpy())
    d_p = np.diff(dofs[["x", "y"]].to_numpy(), axis=0)
    assert (d_xi > 0).all()
    assert (d_p[:, "xy".index(m[1])] > 0).all(), "ξ grows with the coordinate it names"
    assert (np.sign(d_p @ t) == (1 if m[2] == "+" else -1)).all(), "ξ grows along the direction of t it names"
    # history.csv and the history's plot say the same of the same ξ.
    header = (out / "history.csv").read_text(encoding="utf-8").splitlines()[0]
    assert header.endswith(f"zones are positions on Γ_C as the {stated}")
    (tractions,) = figures["history_tractions.png"]
    assert tractions["xlabel"] == stated
    # The last row's zones are the extents of the last step's dofs (contact.csv, the run's last solution) in
    # contact and in stick, in the same ξ.
    last = pd.read_csv(out / "history.csv", comment="#").iloc[-1]
    for zone, states in (("contact", ("stick", "slip")), ("stick", ("stick",))):
        xi = dofs["xi"][dofs["state"].isin(states)].to_numpy()
        assert len(xi) and (last[f"{zone}_from"], last[f"{zone}_to"]) == (xi.min(), xi.max()), (zone, last, xi)


def test_each_steps_legend_reads_its_row_of_history_csv(drag: tuple[Path, str, Any]) -> None:
    out, _, figures = drag
    table = pd.read_csv(out / "history.csv", comment="#")
    (tractions,) = figures["history_tractions.png"]
    steps = [int(m[1]) for m in (re.match(r"λ_t, step (\d+) ", label) for label in tractions["legend"]) if m]
    assert len(steps) == 3 and len(set(steps)) == 3
    for k, label in zip(steps, [label for label in tractions["legend"] if label.startswith("λ_t")], strict=True):
        row = table.iloc[k]
        assert label == f"λ_t, step {k} (s = {row['shift']:.3g}, Q = {row['tangential_force']:.3g})"
    # The loop's axes name what the history moved: the obstacle's shift.
    (loop,) = figures["history_loop.png"]
    assert loop["xlabel"].startswith("obstacle tangential position s")


def test_the_cattaneo_mindlin_gallery_labels_each_step_by_its_own_force(
        figures: dict[str, list[dict[str, Any]]]) -> None:
    """The gallery's figure: each step's legend gives that step's tangential force (they said "s = 0", the
    obstacle's shift, in a history that moves the upper block's top), read against the history it solved."""
    import matplotlib.pyplot as plt

    ran = runpy.run_path(str(ROOT / "docs" / "gallery" / "plot_cattaneo_mindlin.py"))
    history = ran["history"]
    labels = [t.get_text() for t in ran["ax"].get_legend().get_texts() if t.get_text().startswith("λ_t")]
    q = history.tangential_force
    assert labels == [f"λ_t, step {k} (Q = {q[k]:.3g})" for k in (2, 4, 6)]
    assert len({f"{q[k]:.3g}" for k in (2, 4, 6)}) == 3
    plt.close("all")


def test_two_bodies_name_the_primary_side_as_the_one_that_pushes(
        tmp_path: Path, figures: dict[str, list[dict[str, Any]]]) -> None:
    scene = tmp_path / "two.toml"
    text = scene_path("hertz_two_bodies").read_text(encoding="utf-8")
    scene.write_text(text.replace("h_min = 0.005", "h_min = 0.04") + "\n[friction]\nmu = 0.3\n", encoding="utf-8")
    assert main(["-q", "run", str(scene), "--out", str(tmp_path / "out"), "--plots"]) == 0
    summary = json.loads((tmp_path / "out" / "summary.json").read_text(encoding="utf-8"))
    primary = summary["scene"]["contact"]["primary"]
    fx, fy = summary["contact_force"]
    (normal,) = figures["contact_normal.png"]
    (tangential,) = figures["contact_tangential.png"]
    assert "obstacle" not in normal["title"] + tangential["title"]
    forces = re.search(r"force of '(.+?)' on the secondary body \(Fx, Fy\) = \((\S+), (\S+)\)", normal["title"])
    assert forces and forces[1] == primary
    assert (_number(forces[2]), _number(forces[3])) == pytest.approx((fx, fy), rel=1e-3, abs=1e-12)
    pulls = re.search(r"'(.+?)' pulls the secondary body by (\S+) along t", tangential["title"])
    assert pulls and pulls[1] == primary
    assert _number(pulls[2]) == pytest.approx(-summary["tangential_force"], rel=1e-2)
    assert summary["conventions"]["lambda_t"].startswith(f"λ_t = −σ_t, along t: the friction traction of '{primary}'")
