"""The code of the README and of the documentation site's pages runs as tests (Python examples, scene
snippets), and the readings they quote are those of the studies' files, so the pages cannot drift from the
API or from the measurements."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

from tribo.scene import load_scene, parse_scene, scene_path

README = Path(__file__).resolve().parents[2] / "README.md"
DOCS = README.parent / "docs"
# The pages whose code runs here, in reading order: the README, then the site's getting-started page, the
# user guide and the measurements.
PAGES = [README, DOCS / "getting-started.md", *sorted((DOCS / "guide").glob("*.md")), DOCS / "measured.md"]


def _text() -> str:
    return "\n".join(p.read_text(encoding="utf-8") for p in PAGES)


def _blocks(lang: str) -> list[str]:
    return re.findall(rf"```{lang}\n(.*?)```", _text(), flags=re.S)


def _embeds(text: str, name: str) -> bool:
    """Whether a page embeds the chart ``docs/name.png`` (from the README, a page of docs/ or of docs/guide/)."""
    return re.search(rf"!\[[^\]]*\]\((?:docs/|\.\./)?{name}\.png\)", text) is not None


def test_readme_python_example_runs(capsys: object) -> None:
    blocks = _blocks("python")
    assert blocks, "README.md has no python example"
    for code in blocks:
        if "tribo.sweep" in code:
            continue  # the sweep example starts a Dask cluster: tests/python/test_sweep.py runs it
        namespace: dict[str, object] = {}
        exec(compile(code, "docs", "exec"), namespace)  # noqa: S102 - our own pages
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


def _rows(name: str) -> list[dict[str, str]]:
    import csv

    with (README.parent / "docs" / name).open(encoding="utf-8") as f:
        return list(csv.DictReader(f))


def test_readme_embeds_the_study_charts_with_true_readings() -> None:
    """The work-precision, checkerboard and γ0 charts are embedded (and exist), and the numbers their
    readings quote are those of the studies' CSV files."""
    text = _text()
    for name in ("work_precision", "checkerboard", "gamma0_bound"):
        assert _embeds(text, name), name
        assert (README.parent / "docs" / f"{name}.png").stat().st_size > 0
    fine = [r for r in _rows("checkerboard.csv") if float(r["H/h"]) < 1]

    def span(theta: str, key: str) -> tuple[float, float]:
        v = [float(r[key]) for r in fine if r["theta"] == theta]
        return min(v), max(v)

    assert [round(x) for x in span("0", "TV ratio")] == [8, 23] and "total variation 8–23×" in text
    assert [round(x, 2) for x in span("0", "L2 error")] == [0.66, 2.12] and "L2 error 0.66–2.1 " in text
    assert [round(x, 1) for x in span("0.9", "TV ratio")] == [1.4, 2.0] and "to 1.4–2.0× and 0.11–0.15" in text
    assert [round(x, 2) for x in span("0.9", "L2 error")] == [0.11, 0.15]
    rows = _rows("gamma0_bound.csv")
    at_bound = [round(float(r["l2"]), 3) for r in rows if r["fraction"] == "1"]
    assert at_bound == [0.088, 0.042, 0.027] and "(0.088, 0.042, 0.027 at 1 ×)" in text
    for h in ("0.02", "0.01", "0.005"):
        l2 = [float(r["l2"]) for r in rows if r["h_min"] == h and r["outcome"] == "converged"]
        assert 1 - min(l2) / max(l2) < 0.4, h


def test_readme_half_model_scene_is_half_the_hertz_scene() -> None:
    """The half-model scene of the README (a roller on the symmetry line) solves to half the full Hertz
    scene's force, to round-off: its graded mesh is the right half of the full one, which is symmetric."""
    blocks = [b for b in _blocks("toml") if 'kind = "roller"' in b]
    assert len(blocks) == 1, "README.md has no half-model scene"
    _, half = parse_scene(tomllib.loads(blocks[0])).solve()
    _, full = load_scene(scene_path("hertz")).solve()
    assert half.report.status == full.report.status == "converged"
    assert abs(2.0 * half.normal_force - full.normal_force) < 1e-10 * full.normal_force


def test_readme_quotes_the_two_body_and_path_studies_as_measured() -> None:
    """The two-body and path-choice readings of the README are those of docs/two_bodies.csv and paths.csv."""
    text = _text()
    assert _embeds(text, "two_bodies")
    rows = _rows("two_bodies.csv")
    finest = max(float(r["n_free"]) for r in rows)
    at = {r["pair"]: float(r["hertz_l2"]) for r in rows if float(r["n_free"]) == finest}
    assert f"{at['equal']:.2%}".replace("%", " %") in text and f"{at['dissimilar']:.2%}".replace("%", " %") in text
    assert f"{finest / 1000:.1f}k unknowns" in text
    worst = max(float(r["minimax"]) for r in _rows("paths.csv"))
    assert f"at most {worst:.2f}× the fastest" in text


def test_the_python_guide_quotes_the_adaptive_study_as_measured() -> None:
    """Issue 38: the guide said "22 levels at 6.3k unknowns, 0.69 %" where the study gives 12 levels, 7,240
    unknowns and 0.83 %. Its readings are now those of docs/adaptive.csv and adaptive_levels.csv."""
    text = (DOCS / "guide" / "python.md").read_text(encoding="utf-8")
    text = " ".join(text.split())
    row = next(r for r in _rows("adaptive.csv") if r["center"] == "0.3" and r["family"] == "adaptive"
               and r["tol"] == "0.1")
    quoted = (f"stops after {row['levels']} levels at {int(row['n_free']):,} unknowns, {float(row['seconds']):.2f} s "
              f"in all, with an estimate of {float(row['relative']):.2%} and a true L2 error of λ_n of "
              f"{float(row['error']):.2%}").replace("%", " %")
    assert quoted in text, quoted
    levels = [r for r in _rows("adaptive_levels.csv") if int(r["in_contact"]) >= 10]
    ratios = [float(r["relative"]) / float(r["error"]) for r in levels]
    assert f"by {min(ratios):.1f} to {max(ratios):.1f} over the {len(levels)} levels" in text


def test_the_docs_quote_the_memory_studies_as_measured() -> None:
    """Studies 17 and 18 (issue 37): the peaks and ratios quoted by STUDIES.md, measured.md and the history
    guide are those of docs/python_memory.csv and docs/history_memory.csv."""
    pages = {name: " ".join((DOCS / name).read_text(encoding="utf-8").split())
             for name in ("STUDIES.md", "measured.md", "guide/histories.md")}
    rust, shipped, never, at_once = _rows("python_memory.csv")
    quoted = (f"{float(shipped['peak_mb']):.0f} MB from Python and {float(rust['peak_mb']):.0f} MB from Rust "
              f"({float(shipped['peak_over_rust']):.2f} times)")
    assert quoted in pages["STUDIES.md"], quoted
    assert f"never returning them gives a Python peak of {float(never['peak_mb']):.0f} MB" in pages["STUDIES.md"]
    assert f"{float(at_once['peak_mb']):.0f} MB ({float(at_once['peak_over_rust']):.2f} times)" in pages["STUDIES.md"]
    assert (f"at {float(rust['peak_mb']):.0f} MB from Rust and {float(shipped['peak_mb']):.0f} MB from Python "
            f"({float(shipped['peak_over_rust']):.2f} times" in pages["measured.md"])
    long = [r for r in _rows("history_memory.csv") if int(r["steps"]) >= 30_000]
    ratios = [float(r["growth_over_estimate"]) for r in long]
    span, rounded = f"{min(ratios):.2f}–{max(ratios):.2f} times", f"{min(ratios):.1f}–{max(ratios):.1f} times"
    assert span in pages["STUDIES.md"] and f"within {span} its measured growth" in pages["measured.md"], span
    assert f"within {rounded} the measured growth" in pages["guide/histories.md"], rounded
    last = long[-1]
    assert (f"grows the Python process by {float(last['growth_mb']):.0f} MB ({float(last['growth_per_step_bytes']):.0f} "
            f"bytes per step" in pages["STUDIES.md"])


def test_the_docs_quote_the_error_bar_and_tol_studies_as_generated() -> None:
    """Studies 13–15 (issue 36): the ranges and counts the guide, STUDIES.md and measured.md quote are those the
    scripts compute from docs/error_bars/ and docs/tol_table/ (the pages themselves are generated from them)."""
    import importlib
    import sys

    sys.path.insert(0, str(README.parent / "scripts"))
    bars, tol = importlib.import_module("plot_error_bars"), importlib.import_module("plot_tol_table")
    pages = {name: " ".join((DOCS / name).read_text(encoding="utf-8").split())
             for name in ("STUDIES.md", "measured.md", "guide/python.md")}
    files = {k: v for k, v in bars.load(DOCS / "error_bars").items() if not k.endswith("-strip")}
    every = [r for rows in files.values() for r in rows]
    forces = [r[f"{q}_effectivity"] for r in every for q in ("P", "Q") if r[f"{q}_effectivity"] is not None]
    inside = sum(1 <= e <= 2 for e in forces)
    quoted = f"{min(forces):.2f}–{max(forces):.2f} times the true error ({inside} of {len(forces)} bars in [1, 2]"
    assert quoted in pages["guide/python.md"], quoted
    assert f"{min(forces):.2f}–{max(forces):.2f} times their true error" in pages["STUDIES.md"]
    _, levels = tol.load(DOCS / "tol_table")
    resolved = [r for rows in tol.effectivity_rows(levels).values() for r in rows if r["in_contact"] >= 10]
    read = [r["read_effectivity"] for r in resolved]
    quoted = f"{sum(1 <= e <= 2 for e in read)} of the {len(read)} levels of study 13"
    assert quoted in pages["guide/python.md"], quoted
    assert f"{sum(1 <= e <= 2 for e in read)} of {len(read)} levels" in pages["measured.md"]
