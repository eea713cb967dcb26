"""The README's Python example and scene snippet run as tests, so the README cannot drift from the API."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

from tribo.scene import parse_scene

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


def test_readme_history_snippet_samples_its_path() -> None:
    blocks = [b for b in _blocks("toml") if "[history]" in b]
    assert blocks, "README.md has no [history] example"
    base = tomllib.loads((Path(__file__).resolve().parents[2] / "python/tribo/scenes/fretting.toml").read_text())
    base["history"] = tomllib.loads(blocks[0])["history"]
    approach, shift, load_factor = parse_scene(base).history_steps()
    assert len(shift) == 1 + 8 + 16 + 16
    assert shift[8] == 0.0045 and shift[24] == -0.0045 and shift[-1] == 0.0045
    assert (approach == base["obstacle"]["approach"]).all() and (load_factor == 1.0).all()
