"""Studies 14 and 15 — the error bars of P, Q and the zone widths, and the traction estimates, level by level on
every adaptive case, from the CSV files of the Rust example ``error_bars``.

Issue 36 asks for error bars on what users read (the normal and tangential forces P and Q, the widths of the
contact and stick zones) and for traction estimates whose effectivity (estimate over true error) lies in [1, 2]
on every level with at least 10 multiplier dofs in contact, on one-body Hertz, the block, two bodies and P0
multipliers. The example adapts each case from its coarse start to 80k unknowns, solves every level with at least
10 dofs in contact again on its mesh, computes its error bars (the problem solved once more with every triangle
bisected and those along the contact zone again, T_H halved with them: 8-9 times the unknowns) and compares each with the true error of its quantity
against the case's reference, and the traction estimates with the true relative L²(Γ_C) error of λ: the
hierarchical estimate the adaptive stop computes (the whole mesh bisected and the strip of half a contact width
again, the same enriched solve as the bars'), the bound ζ, and the smaller of the two (what the adaptive stop
reads). With ``STRIP`` = 1 (file ``CASE-strip.csv``) the bars come from the strip alone instead, to show
what it misses. The reference's own error limits what can be read: a width is known to its zone's resolution, a
force to its change when the reference's whole mesh is bisected once (``SKIP`` = 0, the Hertz cases; with
``SKIP`` = 1 that floor is 0: the block's and the two bodies' references are not solved again enriched, 4 times
their 500k unknowns). A true error
below twice its floor is not counted; just above it, the reference's own error (of the same sign: discrete
answers are stiffer) makes the true error look smaller and the effectivity larger.

    for c in hertz hertz@0.3 hertz-coulomb hertz-p0; do
        cargo run --release -p tribo --example error_bars $c 80000 0 0; done
    cargo run --release -p tribo --example error_bars hertz 80000 1 1
    for c in block two-body two-body-coulomb; do
        cargo run --release -p tribo --example error_bars $c 80000 0 1; done
    python scripts/plot_error_bars.py
"""

from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
import studylib as sl  # noqa: E402
from plot_tol_table import CASES, EFFECTIVITY, order  # noqa: E402

QUANTITIES = {"P": "P", "Q": "Q", "contact_width": "contact width", "stick_width": "stick width"}
TRACTIONS = {"traction_strip": "hierarchical", "traction_whole": "hierarchical (the bars' solve)",
             "traction_bound": "bound", "traction_read": "the smaller of hierarchical and bound (what the stop reads)"}
# Levels from which the cost of the bars is read (below, both solves take hundredths of a second).
COST_FROM = 6000


def load(folder: Path) -> dict[str, list[dict[str, Any]]]:
    """Every file ``CASE.csv`` (and ``CASE-strip.csv``) of ``folder``, by its stem, each row with its
    effectivities: ``<quantity>_effectivity`` (None where the true error is within twice the floor)."""
    out: dict[str, list[dict[str, Any]]] = {}
    for path in sorted(folder.glob("*.csv")):
        rows = []
        for r in sl.read_csv_rows(path):
            row: dict[str, Any] = {k: (v if k == "case" else float(v)) for k, v in r.items()}
            row["traction_read"] = sl.smaller(row["traction_strip"], row["traction_bound"])
            for t in TRACTIONS:
                row[f"{t}_effectivity"] = row[t] / row["traction_true"]
            for q in QUANTITIES:
                counted = row[f"{q}_true"] > 2 * row[f"{q}_floor"]
                row[f"{q}_effectivity"] = row[f"{q}_bar"] / row[f"{q}_true"] if counted else None
            rows.append(row)
        out[path.stem] = rows
    return out


def _values(rows: list[dict[str, Any]], key: str) -> list[float]:
    return [r[key] for r in rows if r[key] is not None and math.isfinite(r[key])]


def _span(values: list[float]) -> str:
    """``min–max (k of n in [1, 2])``, or – where nothing was counted."""
    if not values:
        return "–"
    inside = sum(EFFECTIVITY[0] <= v <= EFFECTIVITY[1] for v in values)
    return f"{min(values):.2f}–{max(values):.2f} ({inside} of {len(values)} in [1, 2])"


def _below(files: dict[str, list[dict[str, Any]]], key: str) -> list[str]:
    return [f"{r['case']} at {r['unknowns']:.0f} ({r[key]:.2f})" for rows in files.values() for r in rows
            if r[key] is not None and r[key] < 1]


def summary(files: dict[str, list[dict[str, Any]]], strip: dict[str, list[dict[str, Any]]]) -> str:
    """What the tables show, counted from them."""
    every = [r for rows in files.values() for r in rows]
    forces = _values(every, "P_effectivity") + _values(every, "Q_effectivity")
    below = _below(files, "P_effectivity") + _below(files, "Q_effectivity")
    lines = [f"* **The bars of the forces**: {_span(forces)} over the counted levels of P and Q of every case; "
             f"below 1: {', '.join(below) if below else 'never'}."]
    widths = _values(every, "contact_width_effectivity") + _values(every, "stick_width_effectivity")
    below = _below(files, "contact_width_effectivity") + _below(files, "stick_width_effectivity")
    lines.append(f"* **The bars of the widths**: {_span(widths)}; below 1: {', '.join(below) if below else 'never'}. "
                 "A width is read from the contact states, so its error is quantized by the dof spacing, and its bar "
                 "never claims better than that resolution.")
    for stem, rows in strip.items():
        lines.append(f"* **The strip misses the error of P** (`{stem}`: the bars from the strip alone, bisected "
                     f"twice): P's bar {_span(_values(rows, 'P_effectivity'))} of its true error, where the whole "
                     "mesh gives the figures above: P's error lives in the whole body.")
    read = _values(every, "traction_read_effectivity")
    lines.append(f"* **What the adaptive stop reads** (the smaller of the hierarchical estimate and the bound): "
                 f"{_span(read)} over the levels of all cases; per case in the table below.")
    costly = [r for r in every if r["unknowns"] >= COST_FROM and r["solve_seconds"] > 0]
    if costly:
        ratios = [r["enriched_seconds"] / r["solve_seconds"] for r in costly]
        lines.append(f"* **Cost**: from {COST_FROM} unknowns on, the enriched solve of the bars took "
                     f"{min(ratios):.1f}–{max(ratios):.1f} times the solve it checks: `error_bars` is off by default.")
    return "\n".join(lines) + "\n"


def chart(files: dict[str, list[dict[str, Any]]], path: Path) -> None:
    plt = sl.pyplot()
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2), constrained_layout=True)
    for case, rows in sorted(files.items(), key=lambda kv: order(kv[0])):
        colour = f"C{list(CASES).index(case)}" if case in CASES else None
        a.plot([r["unknowns"] for r in rows], [r["traction_read_effectivity"] for r in rows], "o-", color=colour,
               label=case)
        for q, style in (("P", "o-"), ("Q", "s--")):
            counted = [r for r in rows if r[f"{q}_effectivity"] is not None]
            if counted:
                b.plot([r["unknowns"] for r in counted], [r[f"{q}_effectivity"] for r in counted], style, color=colour,
                       label=f"{case}, {q}")
    for ax in (a, b):
        sl.effectivity_axes(ax, EFFECTIVITY)
    a.set_ylabel("estimate / true traction error")
    a.set_title("what the adaptive stop reads (band: [1, 2])")
    b.set_ylabel("error bar / true error")
    b.set_title("the bars of P and Q")
    a.legend(fontsize=7)
    b.legend(fontsize=6, ncol=2)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def page(files: dict[str, list[dict[str, Any]]], strip: dict[str, list[dict[str, Any]]]) -> str:
    doc = __doc__ or ""
    cases = sorted(files, key=order)
    scenes = "\n".join(f"* `{c}`: {CASES.get(c, c)}" for c in cases)
    per_case = sl.markdown_table(
        ["case", "levels", "unknowns", *TRACTIONS.values(), *(f"bar of {q}" for q in QUANTITIES.values())],
        [[c, len(files[c]), f"{files[c][0]['unknowns']:.0f}–{files[c][-1]['unknowns']:.0f}" if files[c] else "–",
          *(_span(_values(files[c], f"{t}_effectivity")) for t in TRACTIONS),
          *(_span(_values(files[c], f"{q}_effectivity")) for q in QUANTITIES)] for c in cases])

    def cell(r: dict[str, Any], q: str) -> str:
        e = r[f"{q}_effectivity"]
        return f"{r[f'{q}_true']:.2e}, " + (f"{e:.2f}" if e is not None else "~")

    levels = sl.markdown_table(
        ["case", "level", "unknowns", "dofs in contact", "λ: true error", "hierarchical / true", "bars' / true",
         "bound / true", *(f"{q}: true error, bar / true" for q in QUANTITIES.values()), "seconds (solve, bars)"],
        [[c, f"{r['level']:.0f}", f"{r['unknowns']:.0f}", f"{r['in_contact']:.0f}", f"{r['traction_true']:.2e}",
          *(f"{r[f'{t}_effectivity']:.2f}" for t in ("traction_strip", "traction_whole", "traction_bound")),
          *(cell(r, q) for q in QUANTITIES), f"{r['solve_seconds']:.3g}, {r['enriched_seconds']:.3g}"]
         for c in cases for r in files[c]])
    return "\n\n".join([
        "# Studies 14 and 15: error bars on P, Q and the zone widths, and the traction estimates on every adaptive "
        "case", doc.split("\n\n")[1],
        "**What a bar is.** The bar of a quantity J is `1.5 |J_H − J_f|`, J_f read from the problem of the "
        "hierarchical estimate (the whole mesh bisected, the strip of half a contact width again), and for a width "
        "at least the resolution of its zone (half the dof spacing at each end). The crate documentation of "
        "`tribo::adapt::enriched` derives the factor 1.5 (the enrichment leaves at most a third of the error) and why "
        "P needs the whole mesh: under a prescribed approach P's error is that of the body's compliance, "
        "`P_H − P = ‖u − u_h‖²_a / δ` in a linear problem, of order h² where the energy error is of order h, so one "
        "bisection of the whole mesh leaves about a quarter of it and the bar overestimates by about "
        "`1.5 (1 − ¼) = 1.125`.",
        "Regenerate with the commands below (one to a few minutes per case on two cores, the references and the "
        "solves of every level again most of it; read times as orders of magnitude):\n\n" + sl.commands_block(doc),
        "**Scenes** (their coarse starts and references: `tribo_testkit::adaptive_case`): the Hertz cases' "
        "reference is the same scene on a graded mesh of 466k unknowns, the others' the adaptive loop run to 500k "
        "unknowns, the block's then graded toward its corners, where its traction is singular "
        "(`tribo_testkit::graded_at_ends`). `~` marks a true error within twice what the reference knows (not counted).\n\n" + scenes,
        "## What it shows\n\n" + summary(files, strip), "![error bars](error_bars.png)",
        "## Per case\n\nEffectivity (estimate or bar over true error), smallest–largest over the counted levels.\n\n"
        + per_case,
        "## Every level\n\n" + levels])


def main(argv: list[str] | None = None) -> dict[str, Any]:
    args = sl.csv_study_args(__doc__, "error_bars", argv)
    loaded = load(args.csv_dir)
    strip = {k: v for k, v in loaded.items() if k.endswith("-strip")}
    files = {k: v for k, v in loaded.items() if k not in strip}
    if not files:
        raise SystemExit(f"no levels in {args.csv_dir}: run the example error_bars first")
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "error_bars.md").write_text(page(files, strip), encoding="utf-8")
    chart(files, args.out / "error_bars.png")
    return {"cases": sorted(files, key=order), "strip": sorted(strip)}


if __name__ == "__main__":
    main()
