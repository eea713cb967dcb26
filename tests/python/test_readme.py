"""The code of the README and of the documentation site's pages runs as tests (Python examples, scene
snippets), and the readings they quote are those of the studies' files, so the pages cannot drift from the
API or from the measurements."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path
from typing import Any

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
    read = [r["read_effectivity"] for r in tol.read_rows(levels) if r["in_contact"] >= 10]
    quoted = f"{sum(1 <= e <= 2 for e in read)} of the {len(read)} levels of study 13"
    assert quoted in pages["guide/python.md"], quoted
    assert f"{sum(1 <= e <= 2 for e in read)} of {len(read)} levels" in pages["measured.md"]


def _page(name: str) -> str:
    """A page of docs/ (``guide/x.md`` for the guide's), its whitespace normalised so a phrase may wrap."""
    return " ".join((DOCS / name).read_text(encoding="utf-8").split())


def _script(name: str):  # noqa: ANN202 - a module of scripts/
    import importlib
    import sys

    sys.path.insert(0, str(README.parent / "scripts"))
    return importlib.import_module(name)


def _pct(x: float, digits: int = 1) -> str:
    """A fraction as the pages write it: 0.0264 -> "2.6 %"."""
    return f"{x:.{digits}%}".replace("%", " %")


def _span(values: list[float], fmt: str) -> str:
    return f"{min(values):{fmt}}–{max(values):{fmt}}"


def test_the_docs_quote_the_tol_table_as_generated() -> None:
    """Study 13 (issue 38): the sentences of the Python guide, measured.md and STUDIES.md on the `tol` runs (the
    hierarchical stop, the bound, the enriched answer handed back) count and span what plot_tol_table reads from
    docs/tol_table/."""
    tol = _script("plot_tol_table")
    guide, measured, studies = _page("guide/python.md"), _page("measured.md"), _page("STUDIES.md")
    raw, levels = tol.load(DOCS / "tol_table")
    runs = tol.run_rows(raw)
    by = {s: [r for r in runs if r["stop_on"] == s] for s in ("hierarchical", "bound", "enriched")}
    sharp, bound, enriched = by["hierarchical"], by["bound"], by["enriched"]
    cases = len({r["case"] for r in sharp})
    # The default stop against the bound: the true error over X and the unknowns the bound costs more.
    ratios = [r["ratio"] for r in sharp]
    in_band = sum(r["in_band"] for r in sharp)
    unknowns = {(r["case"], r["tol"]): r["unknowns"] for r in sharp}
    more = [r["unknowns"] / unknowns[(r["case"], r["tol"])] for r in bound]
    # The effectivity of the hierarchical estimate, per kind of case.
    eff = {case: [r for r in rows if r["in_contact"] >= tol.MIN_IN_CONTACT]
           for case, rows in tol.effectivity_rows(levels).items()}
    of = lambda *names: [r["effectivity"] for c in names for r in eff[c]]  # noqa: E731
    one = of("hertz", "hertz@0.3", "hertz-coulomb", "hertz-tresca", "hertz-coulomb-history")
    p0, two, pairs = of("hertz-p0"), of("two-body", "two-body-coulomb"), of("pairs")
    quoted = (f"its effectivity is {_span(one, '.2f')} on one-body Hertz and histories, {_span(p0, '.2f')} with P0 "
              f"multipliers, {_span(two, '.2f')} on two bodies and {_span(pairs, '.2f')} with two contact pairs, and "
              f"`tol` = 5 %, 2 %, 1 %, 0.5 % ends with a true error of {_span(ratios, '.2f')} of `tol` (in [X/3, X] in "
              f"{in_band} of {len(sharp)} runs), where the bound ends at {_span([r['ratio'] for r in bound], '.2f')} of "
              f"it with {_span(more, '.0f')} times the unknowns")
    assert quoted in guide, quoted
    assert f"measured on the {_count(cases)} adaptive cases of study 13" in guide
    assert f"stopping on the hierarchical estimate (the default), {_count(cases)} adaptive cases" in studies
    outside = [r["effectivity"] for rows in eff.values() for r in rows if not 1.0 <= r["effectivity"] <= 2.0]
    inside = sum(len(rows) for rows in eff.values()) - len(outside)
    others = [e for c, rows in eff.items() if c != "block" for r in rows if not 1.0 <= (e := r["effectivity"]) <= 2.0]
    quoted = (f"{inside} of {inside + len(outside)} levels in [1, 2], the block's {len(eff['block'])} at "
              f"{_span([r['effectivity'] for r in eff['block']], '.2f')}"
              + (f" and the rest at {_span(others, '.2f')}" if others else ""))
    assert quoted in studies, quoted
    block = eff["block"]
    quoted = (f"it is {_span([r['effectivity'] for r in block], '.2f')} times the true error and the bound "
              f"{_span([r['bound_effectivity'] for r in block], '.2f')}.")
    assert quoted in guide, quoted
    # What the stop reads: the hierarchical estimate or, on the level after, the calibrated bound (or the bound).
    read = [r["read_effectivity"] for r in tol.read_rows(levels) if r["in_contact"] >= tol.MIN_IN_CONTACT]
    quoted = (f"is within [1, 2] of the true error on {sum(1.0 <= e <= 2.0 for e in read)} of the {len(read)} levels "
              f"of study 13 where it read one of the two ({_span(read, '.2f')}")
    assert quoted in guide, quoted
    calibrated = [r["calibrated_effectivity"] for r in tol.read_rows(levels)
                  if r["in_contact"] >= tol.MIN_IN_CONTACT and r["calibrated_effectivity"] is not None]
    quoted = f"the calibrated bound is {_span(calibrated, '.2f')}"
    assert quoted in studies, quoted
    history = [r["ratio"] for r in sharp if r["case"] == "hertz-coulomb-history"]
    quoted = (f"ends at {_span(history, '.2f')} of `tol`, every step's estimate "
              f"{_span([r['effectivity'] for r in eff['hertz-coulomb-history']], '.2f')} times its true error")
    assert quoted in guide, quoted
    timed = [r["time_ratio"] for r in sharp]
    quoted = (f"{in_band} of {len(sharp)} runs end in [X/3, X] over {_count(cases)} cases ({_span(ratios, '.2f')} X), "
              f"within twice the time of the cheapest adequate level in {sum(r['in_time'] for r in sharp)} of "
              f"{len(sharp)} ({min(timed):.2f}–{max(timed):.2f} times")
    assert quoted in measured, quoted
    quoted = (f"end at {_span([r['ratio'] for r in bound], '.2f')} X in "
              f"{_span([r['time_ratio'] for r in bound], '.0f')} times that time")
    assert quoted in measured and quoted in studies, quoted
    # The enriched answer handed back.
    in_time, in_band = sum(r["in_time"] for r in enriched), sum(r["in_band"] for r in enriched)
    ratios, timed = [r["ratio"] for r in enriched], [r["time_ratio"] for r in enriched]
    quoted = (f"{in_time} of {len(enriched)} runs within twice the cheapest adequate level's time; {in_band} of "
              f"{len(enriched)} in [X/3, X], at {_span(ratios, '.2f')} of `tol`")
    assert quoted in guide, quoted
    quoted = (f"{in_time} of {len(enriched)} runs within twice that time ({min(timed):.2f}–{max(timed):.2f}), "
              f"{in_band} of {len(enriched)} in [X/3, X] ({_span(ratios, '.2f')} X")
    assert quoted in measured, quoted
    both = sum(r["in_time"] and r["in_band"] for r in enriched)
    quoted = f"{both} of {len(enriched)} both"
    assert quoted in measured and quoted in studies, quoted


def _count(n: int) -> str:
    return {7: "seven", 8: "eight", 9: "nine", 10: "ten"}.get(n, str(n))


def test_the_history_guide_quotes_the_memory_estimate_per_step() -> None:
    """Study 18: the bytes a history step costs by the budget's estimate, as the history guide quotes them."""
    longest = max(_rows("history_memory.csv"), key=lambda r: int(r["steps"]))  # the fixed part shared out least
    quoted = (f"about {round(float(longest['estimate_per_step_bytes']), -1):.0f} bytes per step for "
              f"{longest['multipliers']} multiplier dofs")
    assert quoted in _page("guide/histories.md"), quoted


def test_the_sweep_guide_quotes_the_sweep_overhead_as_measured() -> None:
    """Study 10: the overhead of a sweep on a fresh and on a running cluster, in the sweep guide and STUDIES.md,
    are those of docs/sweep.csv."""
    guide, studies = _page("guide/sweeps.md"), _page("STUDIES.md")

    def took(ms: float) -> str:
        return f"{ms:.0f} ms" if ms < 100 else f"{ms / 1000:.2f} s"

    small, medium, large = sorted(_rows("sweep.csv"), key=lambda r: float(r["per_case_ms"]))
    fresh = {id(r): f"{float(r['wall_over_serial']):.2f}×" for r in (small, medium, large)}
    running = {id(r): f"{float(r['running_over_serial']):.2f}×" for r in (small, medium, large)}
    quoted = [f"{medium['cases']} cases of {took(float(medium['per_case_ms']))} cost {fresh[id(medium)]} their serial sum",
              f"and {running[id(medium)]} on a running one",
              f"{large['cases']} cases of {took(float(large['per_case_ms']))}, {fresh[id(large)]} and {running[id(large)]}",
              f"{small['cases']} cases of {took(float(small['per_case_ms']))}, {fresh[id(small)]} and {running[id(small)]}"]
    for q in quoted:
        assert q in guide, q
    quoted = [f"{medium['cases']} Hertz cases of {took(float(medium['per_case_ms']))} "
              f"({int(medium['unknowns']) / 1000:.1f}k unknowns) take {fresh[id(medium)]} their serial sum",
              f"{large['cases']} cases of {took(float(large['per_case_ms']))} ({int(large['unknowns']) / 1000:.0f}k "
              f"unknowns) {fresh[id(large)]} and {running[id(large)]}",
              f"{small['cases']} cases of {took(float(small['per_case_ms']))} {fresh[id(small)]} and {running[id(small)]}"]
    for q in quoted:
        assert q in studies, q


def test_the_docs_quote_the_output_cost_as_measured() -> None:
    """Study 19 (issue 38): what `tribo run` writes and how long it takes, in measured.md and getting-started.md,
    is docs/output_cost.csv (output_cost.md is generated from it)."""
    rows = _rows("output_cost.csv")

    def row(case: str, asked: str) -> dict[str, float]:
        (r,) = [r for r in rows if r["case"].startswith(case) and r["files_asked"] == asked]
        return {k: float(v) for k, v in r.items() if k not in ("case", "files_asked")}

    demo, demo_plots, demo_all = (row("demo", a) for a in ("data", "data + plots", "everything"))
    hist, hist_plots = row("history", "data"), row("history", "data + plots")
    adapt, adapt_plots, adapt_all = (row("adaptive history", a) for a in ("data", "data + plots", "everything"))
    (steps,) = {int(re.search(r"(\d+) steps", r["case"])[1]) for r in rows if r["case"].startswith("history")}
    (adapt_steps,) = {int(re.search(r"(\d+) steps", r["case"])[1]) for r in rows if r["case"].startswith("adaptive")}
    text = _page("measured.md")
    quoted = [
        f"The demo (adaptive, {demo['unknowns'] / 1000:.1f}k unknowns, with its error bars) writes {demo['files']:.0f} "
        f"files ({demo['megabytes']:.1f} MB) in {demo['write_seconds']:.2f} s of a {demo['run_seconds']:.1f}-s run "
        f"({_pct(demo['share'])}); its plots take {demo_plots['write_seconds'] - demo['write_seconds']:.1f} s more",
        f"{demo_all['files']:.0f} files ({demo_all['megabytes']:.1f} MB) in {demo_all['write_seconds']:.1f} s.",
        f"A {steps}-step history writes {hist['files']:.0f} files ({hist['megabytes']:.0f} MB) in "
        f"{hist['write_seconds']:.2f} s after a {hist['solve_seconds']:.2f}-s solve",
        f"an adaptive {adapt_steps}-step history ({adapt['unknowns'] / 1000:.0f}k unknowns) {adapt['files']:.0f} files "
        f"({adapt['megabytes']:.0f} MB) in {adapt['write_seconds']:.2f} s after a {adapt['solve_seconds']:.1f}-s solve "
        f"({_pct(adapt['share'])} of the run), everything {adapt_all['files']:.0f} files ({adapt_all['megabytes']:.0f} MB) "
        f"in {adapt_all['write_seconds']:.1f} s"]
    for q in quoted:
        assert q in text, q
    plots = [p["write_seconds"] - d["write_seconds"] for d, p in ((hist, hist_plots), (adapt, adapt_plots))]
    quoted = (f"drawing the demo's {demo_plots['files'] - demo['files']:.0f} plots adds "
              f"{demo_plots['write_seconds'] - demo['write_seconds']:.1f} s to its writing, and a history's plots "
              f"{_span(plots, '.1f')} s")
    assert quoted in _page("getting-started.md"), quoted


def test_the_docs_quote_the_cost_study_as_measured() -> None:
    """Study 4: the table of measured.md (the whole Coulomb solve and its ratios to faer's default and supernodal
    Cholesky of K), the two-body
    cost and the peak memory of STUDIES.md, are those of docs/cost.csv, each to the digits the page gives."""
    cost = _script("plot_cost")
    # The default solves (the fixed point for Coulomb); the Newton method's runs are quoted on their own, below.
    every = [r for r in cost.load(DOCS / "cost.csv") if r["status"] == "converged"]
    rows = [r for r in every if r["friction"] != "coulomb_newton"]
    text = (DOCS / "measured.md").read_text(encoding="utf-8")
    table = re.findall(r"^\| (Hertz, uniform|Hertz, graded|block on a foundation)[^|]*\| ([\d.]+)k \| ([\d.]+) s \| "
                       r"([\d.]+) \| ([\d.]+) \| ([^|]+) \|$", text, flags=re.M)
    assert len(table) == 7, table
    family = {"Hertz, uniform": "uniform", "Hertz, graded": "graded", "block on a foundation": "block"}
    by = {"partial factorization": "schur", "not formed (saddle)": "saddle"}

    def same(value: float, quoted: str) -> bool:
        digits = len(quoted.partition(".")[2])
        return f"{value:.{digits}f}" == quoted

    for scene, n, total, ratio, supernodal, path in table:
        (r,) = [r for r in rows if r["family"] == family[scene] and r["friction"] == "coulomb"
                and abs(r["n_free"] / 1000 / float(n) - 1) < 0.02]
        assert same(r["total"], total) and same(r["ratio"], ratio), (scene, n, r["total"], r["ratio"])
        assert same(r["ratio_supernodal"], supernodal), (scene, n, r["ratio_supernodal"])
        assert r["condensation"] == by[path.strip()], (scene, n, r["condensation"])
    graded = [r for r in rows if r["family"] == "graded" and r["friction"] == "coulomb" and r["n_free"] >= cost.FROM]
    assert f"like n^{cost.exponent(graded, 'total'):.2f} on the graded one" in " ".join(text.split())
    measured = " ".join(text.split())
    kb = {fam: [1024.0 * r["peak_mb"] / r["n_free"] for r in rows if r["family"] == fam and r["n_free"] >= 10_000]
          for fam in cost.FAMILIES}
    assert f"the default solve peaks at {_span([k for v in kb.values() for k in v], '.1f')} kB per unknown" in measured
    studies = _page("STUDIES.md")
    largest = {fam: max((r for r in rows if r["family"] == fam), key=lambda r: r["n_free"]) for fam in cost.FAMILIES}
    quoted = (f"{_span(kb['uniform'], '.1f')} kB per unknown on uniform meshes ({largest['uniform']['peak_mb']:.0f} MB "
              f"at {largest['uniform']['n_free'] / 1000:.0f}k), {_span(kb['block'], '.1f')} kB on the block "
              f"({largest['block']['peak_mb']:.0f} MB at {largest['block']['n_free'] / 1000:.0f}k), "
              f"{_span(kb['graded'], '.1f')} kB on graded meshes ({largest['graded']['peak_mb']:.0f} MB at "
              f"{largest['graded']['n_free'] / 1000:.0f}k) and {_span(kb['two_bodies'], '.1f')} kB for two bodies "
              f"({largest['two_bodies']['peak_mb']:.0f} MB at {largest['two_bodies']['n_free'] / 1000:.0f}k)")
    assert quoted in studies, quoted

    def at(fam: str, n: float, friction: str) -> dict[str, Any]:
        return min((r for r in rows if r["family"] == fam and r["friction"] == friction),
                   key=lambda r: abs(r["n_free"] - n))

    times = {(fam, n): tuple(at(fam, n, f)["total"] for f in ("frictionless", "coulomb"))
             for fam, n in (("two_bodies", 16_500), ("graded", 15_000), ("two_bodies", 48_600), ("graded", 55_000))}
    quoted = (f"{times['two_bodies', 16_500][0]:.2f} s frictionless and {times['two_bodies', 16_500][1]:.2f} s Coulomb "
              f"at 16.5k (one body at 15k: {times['graded', 15_000][0]:.2f} s, {times['graded', 15_000][1]:.2f} s), "
              f"{times['two_bodies', 48_600][0]:.2f} s and {times['two_bodies', 48_600][1]:.2f} s at 48.6k (one body "
              f"at 55k: {times['graded', 55_000][0]:.2f} s, {times['graded', 55_000][1]:.2f} s)")
    assert quoted in studies, quoted
    two = max((r for r in rows if r["family"] == "two_bodies" and r["friction"] == "coulomb"), key=lambda r: r["n_free"])
    one = max((r for r in rows if r["family"] == "graded" and r["friction"] == "coulomb"), key=lambda r: r["n_free"])
    quoted = (f"At {two['n_free'] / 1000:.1f}k the two-body Coulomb solve takes {two['total']:.2f} s, {two['ratio']:.1f} "
              f"Cholesky solves of K, of which the QPs take {two['qp']:.2f} s; the graded one-body family at "
              f"{one['n_free'] / 1000:.0f}k takes {one['total']:.2f} s ({one['ratio']:.1f}×)")
    assert quoted in studies, quoted
    uniform = [r for r in rows if r["family"] == "uniform" and r["friction"] == "coulomb"]
    block = [r for r in rows if r["family"] == "block" and r["friction"] == "coulomb"]
    small = min(uniform, key=lambda r: r["n_free"])
    rest = [r["ratio"] for r in uniform if r is not small]
    quoted = (f"{_span(rest, '.1f')} over the uniform sizes from {sorted(r['n_free'] for r in uniform)[1] / 1000:.1f}k "
              f"unknowns on ({small['ratio']:.1f} at {small['n_free'] / 1000:.1f}k)")
    assert quoted in studies, quoted
    assert f"{_span([r['ratio'] for r in block], '.1f')} over its sizes" in studies
    # Issue 40: the Newton method's runs at 55k and 109k graded unknowns, against the fixed point's.
    newton = [min((r for r in every if r["family"] == "graded" and r["friction"] == f), key=lambda r: abs(r["n_free"] - n))
              for n in (55_000, 109_000) for f in ("coulomb_newton", "coulomb")]
    assert all(abs(r["n_free"] / n - 1) < 0.02 for r, n in zip(newton, (55_000,) * 2 + (109_000,) * 2, strict=True))
    quoted = (f"{newton[0]['ratio']:.0f}× at 55k and {newton[2]['ratio']:.0f}× at 109k (of which the factorization and "
              f"the columns take "
              f"{newton[0]['condensed']:.1f} s and {newton[2]['condensed']:.0f} s)")
    assert quoted in studies, quoted
    times = _span([newton[0]["total"] / newton[1]["total"], newton[2]["total"] / newton[3]["total"]], ".0f")
    for page in ("guide/friction.md", "changelog.md"):
        assert f"{times} times the fixed point's time" in _page(page), (page, times)


def test_studies_quotes_the_adaptive_and_work_precision_studies_as_measured() -> None:
    """Studies 2, 6 and 6b: the adaptive runs, the hand-graded meshes they are held against, the work-precision
    table and the unknowns and time a 5 % error needs, in STUDIES.md and measured.md, are those of
    docs/adaptive.csv, adaptive_history.csv and work_precision.csv (the crossings as the study computes them)."""
    studies, measured = _page("STUDIES.md"), _page("measured.md")
    rows = _rows("adaptive.csv")

    def runs(center: str, family: str) -> list[dict[str, str]]:
        return [r for r in rows if r["center"] == center and r["family"] == family]

    def cheapest(rs: list[dict[str, str]], within: float) -> list[dict[str, str]]:
        """The runs that stop on the level with the fewest unknowns reaching ``within`` (several tols may)."""
        n = min(int(r["n_free"]) for r in rs if float(r["error"]) <= within)
        return [r for r in rs if int(r["n_free"]) == n]

    def seconds(rs: list[dict[str, str]], fmt: str) -> str:
        s = sorted({f"{float(r['seconds']):{fmt}}" for r in rs}, key=float)
        return s[0] if len(s) == 1 else f"{s[0]}–{s[-1]}"

    one = cheapest(runs("0", "adaptive"), 0.01)
    graded = cheapest(runs("0", "graded 0.15"), 0.01)
    quoted = (f"adaptive reaches 1 % ({_pct(float(one[0]['error']), 2)}) at {int(one[0]['n_free']) / 1000:.1f}k "
              f"unknowns in {seconds(one, '.3f')} s, all {one[0]['levels']} levels included; the best hand-graded mesh "
              f"(growth 0.15, graded toward [−0.3, 0.3]) needs {int(graded[0]['n_free']) / 1000:.1f}k unknowns and "
              f"{seconds(graded, '.3f')} s")
    assert quoted in studies, quoted
    fine = cheapest(runs("0", "adaptive"), 0.003)
    met = "is met" if max(float(r["seconds"]) for r in fine) < 0.5 else "is not met"
    quoted = (f"0.3 % in under 0.5 s {met}:** {_pct(float(fine[0]['error']), 2)} at "
              f"{int(fine[0]['n_free']) / 1000:.1f}k unknowns takes {seconds(fine, '.2f')} s ({fine[0]['levels']} levels")
    assert quoted in studies, quoted
    off, off_fine = cheapest(runs("0.3", "adaptive"), 0.01), cheapest(runs("0.3", "adaptive"), 0.003)
    quoted = (f"adaptive gets {_pct(float(off[0]['error']), 2)} at {int(off[0]['n_free']) / 1000:.1f}k unknowns in "
              f"{seconds(off, '.2f')} s, and {_pct(float(off_fine[0]['error']), 2)} at "
              f"{int(off_fine[0]['n_free']) / 1000:.1f}k in {seconds(off_fine, '.2f')} s")
    assert quoted in studies, quoted
    last = max((r for r in _rows("adaptive_history.csv") if r["family"] == "adaptive"), key=lambda r: float(r["seconds"]))
    assert f"the adaptive run to tol {last['tol']} takes {float(last['seconds']):.1f} s" in studies
    # Work-precision: the table of the best configuration and the 5 % crossings.
    wp = _script("study_work_precision")
    points = [{k: (float(v) if k not in ("friction", "family", "space", "status") else v) for k, v in r.items()}
              for r in _rows("work_precision.csv")]

    def series(friction: str, space: str = "P1", ratio: float = 1.0, theta: float = 0.5) -> list[dict[str, Any]]:
        return [r for r in points if r["friction"] == friction and r["family"] == "graded" and r["space"] == space
                and r["ratio"] == ratio and r["theta"] == theta]

    for r in series("frictionless"):
        row = (f"| {r['h']:g} | {r['n_free']:.0f} | {r['hertz_l2']:.3f} | {r['energy']:.3f} | "
               f"{1000 * r['seconds']:.2g} ms |")
        assert row in studies, row

    def needs(friction: str, **kw: float) -> tuple[float, float]:
        key = "hertz_l2" if friction == "frictionless" else "ref_l2"
        rs = series(friction, **kw)
        return wp.crossing(rs, key, wp.TARGET, "n_free"), 1000 * wp.crossing(rs, key, wp.TARGET, "seconds")

    (n, ms), (nc, msc) = needs("frictionless"), needs("coulomb")
    assert f"5 % λ_n error needs ≈ {n / 1000:.1f}k unknowns / {ms:.1f} ms" in studies
    assert f"at ≈ {nc / 1000:.1f}k unknowns / {msc:.0f} ms (graded P1, θ = 0.5)" in studies
    assert f"λ_n reaches 5 % at {n / 1000:.2f}k unknowns (frictionless) and {nc / 1000:.2f}k (Coulomb" in studies
    (n9, _), (nc9, _) = needs("frictionless", theta=0.9), needs("coulomb", theta=0.9)
    (h2, _), (h2_9, _) = needs("frictionless", ratio=0.5), needs("frictionless", ratio=0.5, theta=0.9)
    (n0, _), (p0, _) = needs("frictionless", theta=0.0), needs("frictionless", space="P0")
    quoted = (f"(5 % at {n9 / 1000:.2f}k against {n / 1000:.2f}k unknowns; Coulomb {nc9 / 1000:.2f}k against "
              f"{nc / 1000:.2f}k; H = h/2 at 0.9 × needs {h2_9 / 1000:.2f}k against {h2 / 1000:.2f}k at 0.5 ×); P0 needs "
              f"{_pct(p0 / n - 1, 0)} more unknowns ({p0 / 1000:.1f}k)")
    assert quoted in studies, quoted
    assert f"γ0 = 0 with H = h costs about the same ({n0 / 1000:.2f}k unknowns for 5 %)" in studies
    (nc0, _), (pc0, _) = needs("coulomb", theta=0.0), needs("coulomb", space="P0")
    quoted = (f"5 % L2 error of λ_n needs ≈ {n / 1000:.1f}k unknowns ({ms:.1f} ms) frictionless and {nc / 1000:.1f}k "
              f"({msc:.0f} ms) Coulomb with P1, H = h, γ0 = 0.5 × bound ({n9 / 1000:.1f}k and {nc9 / 1000:.1f}k at 0.9 × "
              f"bound, {n0 / 1000:.1f}k and {nc0 / 1000:.1f}k at γ0 = 0), against {p0 / 1000:.1f}k and "
              f"{pc0 / 1000:.1f}k for P0")
    assert quoted in measured, quoted


def test_the_docs_quote_the_stability_and_friction_studies_as_measured() -> None:
    """Studies 1a, 1c, 5 and 7: the checkerboard's total variation, the fixed point's iterations with and without
    relaxation, a fretting cycle's dissipation and the sizes of the path-choice scenes, as the pages quote them."""
    studies, measured = _page("STUDIES.md"), _page("measured.md")
    tv = {(r["space"], r["H/h"], r["theta"]): float(r["TV ratio"]) for r in _rows("checkerboard.csv")}
    quoted = (f"total variation {tv['P1', '0.5', '0']:.0f}× and {tv['P1', '0.25', '0']:.0f}× the Hertz one at H = h/2 "
              f"and h/4 on a uniform mesh of h = 0.05, {tv['P1', '1', '0']:.1f}× with matching meshes); γ0 = 0.5 × bound "
              f"brings it to {tv['P1', '0.5', '0.5']:.1f}× and {tv['P1', '0.25', '0.5']:.1f}×")
    assert quoted in measured, quoted
    cm = [r for r in _rows("cattaneo_mindlin.csv") if r["nu"] == "0.45"]
    finest = min(cm, key=lambda r: float(r["h_min"]))
    assert f"a fretting cycle's dissipation within {_pct(abs(float(finest['work_error'])))}" in measured
    work = [100 * abs(float(r["work_error"])) for r in cm]
    quoted = f"within **{_span(work, '.0f')} %** at ν = 0.45 ({_pct(float(finest['work_error']))} at the finest mesh)"
    assert quoted.replace("-", "−") in studies, quoted
    n = [float(r["n_free"]) for r in _rows("paths.csv")]
    small, large = f"{min(n) / 1000:.0f}k", f"{max(n) / 1000:.0f}k"
    assert f"Over {len(n)} uniform, graded, adaptive and full-contact scenes from {small} to {large}" in measured
    assert f"over {len(n)} scenes and both laws (uniform, graded, adaptive, full contact; {small}–{large}" in studies
    # (the default QP method's runs: the study runs clarabel beside it)
    fp = [r for r in _rows("coulomb_fixed_point.csv")
          if r["h_min"] == "0.01" and r["mu"] != "0" and r["qp_method"] == "auto"]
    plain = {(r["nu"], r["mu"], r["qp_tol"]): int(r["iterations"]) for r in fp if r["omega"] == "1"}
    at_nu0 = {float(r["mu"]): int(r["iterations"]) for r in fp if r["omega"] == "1" and r["nu"] == "0"}
    at_045 = [int(r["iterations"]) for r in fp if r["omega"] == "1" and r["nu"] == "0.45"]
    quoted = (f"ν = 0, {at_nu0[min(at_nu0)]} → {at_nu0[max(at_nu0)]} for μ = {min(at_nu0):g} → {max(at_nu0):g}, "
              f"and are {min(at_045)}–{max(at_045)} at ν = 0.45)")
    assert quoted in studies, quoted
    relaxed = {w: [int(r["iterations"]) for r in fp if r["omega"] == w] for w in ("0.5", "0.25")}
    assert f"({_span(relaxed['0.5'], 'd')} iterations at ω = 0.5, {_span(relaxed['0.25'], 'd')} at ω = 0.25)" in studies
    more = {w: [int(r["iterations"]) / plain[(r["nu"], r["mu"], r["qp_tol"])] for r in fp if r["omega"] == w]
            for w in ("0.5", "0.25")}
    quoted = f"{_span(more['0.5'], '.3g')} times as many at ω = 0.5, {_span(more['0.25'], '.3g')} times at ω = 0.25"
    assert quoted in studies, quoted
    # clarabel beside the default: the largest difference of their tangential forces on the grid (h_min = 0.01).
    apart = {tol: max(float(r["q_apart"]) for r in _rows("coulomb_fixed_point.csv")
                      if r["qp_method"] == "clarabel" and r["h_min"] == "0.01" and r["qp_tol"] == tol and r["mu"] != "0")
             for tol in ("1e-12", "1e-10")}
    short = {tol: f"{v:.0e}".replace("e-0", "e-") for tol, v in apart.items()}
    quoted = f"at most {short['1e-12']} relative at 1e-12, {short['1e-10']} at 1e-10"
    assert quoted in studies, quoted


def test_the_docs_quote_the_two_body_cost_as_measured() -> None:
    """Study 8: the time per unknown of a two-body solve over the one-body solve on the lower mesh, as
    plot_two_bodies computes it from docs/two_bodies.csv (solves of 10 ms or more)."""
    rows = [{k: (v if k in ("pair", "coulomb_status") else float(v)) for k, v in r.items()}
            for r in _rows("two_bodies.csv")]
    ratio = {law: [(r[f"{law}_s"] / r["n_free"]) / (r[f"one_body_{law}_s"] / r["one_body_n"]) for r in rows
                   if r[f"one_body_{law}_s"] >= 0.01] for law in ("frictionless", "coulomb")}
    every = ratio["frictionless"] + ratio["coulomb"]
    assert f"Two elastic bodies cost {_span(every, '.1f')} times the time per unknown of one body" in _page("measured.md")
    quoted = (f"a two-body solve takes {_span(ratio['frictionless'], '.1f')} times the time per unknown of the one-body "
              f"solve on the lower mesh alone (frictionless) and {_span(ratio['coulomb'], '.1f')} times with Coulomb")
    assert quoted in _page("STUDIES.md"), quoted


def test_the_docs_quote_the_coulomb_map_as_generated() -> None:
    """Study 20 (issue 40): the friction guide's and the changelog's numbers on the two Coulomb methods, read from
    docs/coulomb_map.csv through plot_coulomb_map's own summary."""
    cmap = _script("plot_coulomb_map")
    s = cmap.summary(cmap.load(DOCS / "coulomb_map.csv"))
    its = {m: s[("hertz", m)]["iterations"] for m in cmap.METHODS}
    held = {m: [v for (f, mm), v in s.items() if f.startswith("held block") and mm == m] for m in cmap.METHODS}
    problems = sum(v["problems"] for v in held["newton"])
    assert all(v["converged"] == v["problems"] for m in cmap.METHODS for v in held[m]), "both solve all of them"
    ranges = {m: _span([i for v in held[m] for i in v["iterations"]], "d") for m in cmap.METHODS}
    said = (f"on Hertz, Newton takes {its['newton'][0]}–{its['newton'][-1]} steps where the fixed point takes "
            f"{its['fixed_point'][0]}–{its['fixed_point'][-1]} iterations")
    for page in ("guide/friction.md", "changelog.md"):
        text = _page(page)
        assert said in text, (page, said)
        assert f"all {problems} problems that have a solution, Newton in {ranges['newton']} steps" in text, page
        assert f"the fixed point in {ranges['fixed_point']} iterations" in text, page
    # Where the block overturns, how each method ends, as both pages say.
    ends = {m: {st for v in held[m] for _, _, st in v["unsolvable"]} for m in cmap.METHODS}
    assert ends == {"fixed_point": {"qp_failed"}, "newton": {"qp_failed"}}, ends
    for page in ("guide/friction.md", "changelog.md"):
        assert "(no discrete solution) both end `qp_failed`" in _page(page), page
    # The tall block: the fixed point solves all, Newton stagnates on some, as the guide and the changelog say.
    tall = {m: [v for (f, mm), v in s.items() if f.startswith("tall block") and mm == m] for m in cmap.METHODS}
    total = sum(v["problems"] for v in tall["fixed_point"])
    assert all(v["converged"] == v["problems"] for v in tall["fixed_point"])
    stalled = [st for v in tall["newton"] for _, _, st in v["failed"]]
    assert set(stalled) == {"stagnated"}, stalled
    assert f"stagnates on {len(stalled)} of {total} problems" in _page("guide/friction.md")
    assert f"converges on all {total} problems; Newton stagnates on {len(stalled)}" in " ".join(_page("changelog.md").split())
    # The wedge: where the fixed point two-cycles and Newton converges, as the guide and the changelog say.
    fp, nw = s[("wedge", "fixed_point")], s[("wedge", "newton")]
    assert nw["converged"] == nw["problems"] and {st for _, _, st in fp["failed"]} == {"max_iterations"}
    guide, changelog = " ".join(_page("guide/friction.md").split()), " ".join(_page("changelog.md").split())
    said = f"on {len(fp['failed'])} of {fp['problems']} wedges"
    assert said in guide and said in changelog, said
    assert f"converges on all {nw['problems']} ({_span(nw['iterations'], 'd')} steps)" in guide
    assert f"differ by up to {fp['difference']:.1e} of the largest λ_n" in guide
    # Two bodies over the Dundurs β: both converge everywhere, as the guide says.
    fp, nw = s[("two bodies", "fixed_point")], s[("two bodies", "newton")]
    assert fp["converged"] == fp["problems"] == nw["converged"] == nw["problems"]
    said = (f"both converge on all {fp['problems']} problems, the fixed point in {_span(fp['iterations'], 'd')} "
            f"iterations and Newton in {_span(nw['iterations'], 'd')} steps, their answers within "
            f"{max(fp['difference'], nw['difference']):.1e} of each other")
    assert said in guide, said
    # The check of the fixed point's answer by Newton over the whole map (issue 40, item 3), as the guide says.
    checks = {k: sum(v["checks"][k] for (f, m), v in s.items() if m == "fixed_point") for k in cmap.VERDICTS}
    stalled = sum(len(v["failed"]) for (f, m), v in s.items() if m == "newton")
    assert checks["differ"] == 0 and checks["undecided"] == stalled, (checks, stalled)
    said = (f"agrees on {checks['agree']} of the {checks['agree'] + checks['undecided']} where the fixed point "
            f"converged and is undecided on the {checks['undecided']} where Newton stagnates")
    assert said in guide, said


def test_the_sweep_guide_quotes_study_10s_coulomb_map_as_generated() -> None:
    """Issue 38: the case count and wall time the sweep guide gives for study 1c's one command are those of the
    table scripts/study_sweeps.py writes into docs/sweep.md (on the 2-core machine it names)."""
    sweep = _page("sweep.md")
    assert "Wall times on the 2-core machine" in sweep
    row = re.search(r"\| 1c Coulomb fixed point \| `scenes/coulomb_map\.toml` \| (\d+) \| ([\d.]+) \|", sweep)
    assert row, "docs/sweep.md has no row for study 1c"
    quoted = f"({row[1]} cases in {float(row[2]):.0f} s on 2 cores)"
    assert quoted in _page("guide/sweeps.md"), quoted


def _hertz_l2(problem: Any, solution: Any, e_star: float) -> float:
    """The relative L2 error of λ_n against the Hertz pressure of the computed force, as the Rust testkit's
    ``hertz_l2_error_with``: 8-point Gauss on every segment of the union of T_H, the FE nodes of Γ_C and ±a."""
    import math

    import numpy as np

    obstacle = problem.obstacle
    a = math.sqrt(4.0 * solution.normal_force * obstacle.radius / (math.pi * e_star))
    p_max, c = 2.0 * solution.normal_force / (math.pi * a), obstacle.center
    breaks = np.unique(np.r_[problem.multiplier_abscissae, solution.node_abscissae, c - a, c + a])
    x, w = np.polynomial.legendre.leggauss(8)
    mid, half = 0.5 * (breaks[1:] + breaks[:-1]), 0.5 * (breaks[1:] - breaks[:-1])
    xi, weight = (mid[:, None] + half[:, None] * x).ravel(), (half[:, None] * w).ravel()
    p = p_max * np.sqrt(np.clip(1.0 - ((xi - c) / a) ** 2, 0.0, None))
    lam = problem.evaluate_multiplier(solution.lambda_n, xi)
    return math.sqrt(float((weight * (lam - p) ** 2).sum() / (weight * p**2).sum()))


def test_the_python_guide_quotes_the_scene_warnings_measurements() -> None:
    """Issue 38: the readings the Python guide gives for two scene warnings are those of the scenes it names,
    solved here: the dofs in contact and the λ_n error of the shipped Hertz scene (fewer than 10 dofs), and λ_n
    against the Hertz pressure of each ν on the Hertz scene graded to h_min = 0.00125 (P1 locking near ν = ½)."""
    import warnings

    import numpy as np

    import tribo
    from conftest import BLOCK, GRADING, hertz_problem
    from tribo.checks import MIN_CONTACT_DOFS

    guide = _page("guide/python.md")
    scene = load_scene(scene_path("hertz"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", tribo.SceneWarning)  # the warning the sentence explains
        problem, solution = scene.solve()
    k = int(np.count_nonzero(solution.states != 0))
    assert 0 < k < MIN_CONTACT_DOFS and scene.get("discretization", "h_min") == 0.04
    young, nu = scene.get("material", "young"), scene.get("material", "poisson")
    error = _hertz_l2(problem, solution, young / (1.0 - nu**2))
    quoted = f"the shipped Hertz scene, `hertz.toml` at h_min = 0.04, has {k} and a λ_n {_pct(error, 0)} off"
    assert quoted in guide, quoted
    h_min, growth = 0.00125, 0.1
    mesh = tribo.Mesh.graded_rectangle(BLOCK["x"], BLOCK["y"], **{**GRADING, "h_min": h_min, "growth": growth})
    errors, unknowns = {}, set()
    for poisson in (0.3, 0.49, 0.499):
        locked = hertz_problem(mesh, poisson=poisson, formulation="displacement")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", tribo.SceneWarning)
            s = locked.solve()
        assert s.report.status == "converged"
        errors[poisson], unknowns = _hertz_l2(locked, s, young / (1.0 - poisson**2)), unknowns | {locked.n_free}
    (n,) = unknowns
    quoted = (f"the Hertz scene graded to h_min = {h_min:g} at growth {growth:g}, {n / 1000:.0f}k unknowns: λ_n "
              f"{_pct(errors[0.49])} off the Hertz pressure of its ν in L2 at ν = 0.49, {_pct(errors[0.499], 0)} at "
              f"0.499, against {_pct(errors[0.3], 2)} at 0.3")
    assert quoted in guide, quoted
    # The locking warning users see quotes the same measurement.
    from tribo.checks import check_solution

    said = (f"Hertz at {n / 1000:.0f}k unknowns: {_pct(errors[0.49])} at ν = 0.49, {_pct(errors[0.499], 0)} at "
            "0.499")
    locked = hertz_problem(mesh, poisson=0.49, formulation="displacement")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", tribo.SceneWarning)
        reasons = check_solution(locked, locked.solve())
    assert any(said in r for r in reasons), (said, reasons)
