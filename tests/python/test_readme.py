"""The README's Python example and scene snippet run as tests, so the README cannot drift from the API."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

from tribo.scene import load_scene, parse_scene, scene_path

README = Path(__file__).resolve().parents[2] / "README.md"


def _blocks(lang: str) -> list[str]:
    return re.findall(rf"```{lang}\n(.*?)```", README.read_text(encoding="utf-8"), flags=re.S)


def test_readme_python_example_runs(capsys: object) -> None:
    blocks = _blocks("python")
    assert blocks, "README.md has no python example"
    for code in blocks:
        namespace: dict[str, object] = {}
        exec(compile(code, "README.md", "exec"), namespace)  # noqa: S102 - our own README
        solution = namespace["solution"]
        assert solution.report.status == "converged"  # type: ignore[attr-defined]
        assert solution.normal_force > 0.0  # type: ignore[attr-defined]


def test_readme_scene_snippet_is_a_valid_scene() -> None:
    blocks = _blocks("toml")
    assert blocks, "README.md has no scene example"
    scene = parse_scene(tomllib.loads(blocks[0]))
    kw = scene.solve_kwargs()
    assert kw["mu"] == 0.3 and "threshold" not in kw


def test_readme_half_model_scene_is_half_the_hertz_scene() -> None:
    """The half-model scene of the README (a roller on the symmetry line) solves to half the full Hertz
    scene's force, to round-off: its graded mesh is the right half of the full one, which is symmetric."""
    blocks = [b for b in _blocks("toml") if 'kind = "roller"' in b]
    assert len(blocks) == 1, "README.md has no half-model scene"
    _, half = parse_scene(tomllib.loads(blocks[0])).solve()
    _, full = load_scene(scene_path("hertz")).solve()
    assert half.report.status == full.report.status == "converged"
    assert abs(2.0 * half.normal_force - full.normal_force) < 1e-10 * full.normal_force
