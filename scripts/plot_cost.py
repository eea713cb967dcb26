"""Study 4 — cost per phase against problem size, from docs/cost.csv.

docs/cost.csv is written by the Rust example `cargo run --release -p tribo --example cost`; this script
plots time against displacement unknowns (log–log) per phase, for the Hertz scene on uniform and graded
meshes and the block scene, fits the
exponent of each phase (least squares over the sizes where the phase takes ≥ 1 ms) and writes
docs/cost.png and docs/cost.md.

    cargo run --release -p tribo --example cost && python scripts/plot_cost.py
"""

from __future__ import annotations

import argparse
import csv
import math
import sys
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
import studylib as sl  # noqa: E402

FAMILIES = ("uniform", "graded", "block", "two_bodies")
# The friction laws of the runs: Coulomb by the fixed point (`coulomb`) and by the semismooth Newton method
# (`coulomb_newton`, issue 40).
FRICTIONS = ("frictionless", "coulomb", "coulomb_newton")
# The graded family's accurate regime starts here (unknowns).
FROM = 7000

PHASES = [("problem_new", "Problem::new (assembly + Γ_C)"), ("condensed", "factorization + condensation"),
          ("qp", "QPs"), ("recovery", "recovery"), ("total", "whole solve"), ("cholesky", "Cholesky of K + solve")]


def load(path: Path) -> list[dict[str, Any]]:
    with open(path) as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k, v in r.items():
            if k not in ("family", "friction", "status", "condensation"):
                r[k] = float(v)
    return rows


def exponent(rs: list[dict[str, Any]], key: str) -> float:
    pts = [(r["n_free"], r[key]) for r in rs if r[key] >= 1e-3]
    return sl.fitted_rate(*zip(*pts)) if len(pts) >= 2 else math.nan


def rate_label(rate: float) -> str:
    """The legend's fitted exponent; runs under 1 ms are timer noise and give no fit."""
    return "< 2 runs ≥ 1 ms, no fit" if math.isnan(rate) else f"n^{rate:.2f}"


def run(csv_path: Path, out: Path) -> dict[str, Any]:
    rows = load(csv_path)
    out.mkdir(parents=True, exist_ok=True)
    groups = [(fam, fr) for fam in FAMILIES for fr in FRICTIONS
              if any(r["family"] == fam and r["friction"] == fr for r in rows)]
    fits: dict[tuple[str, str, str], float] = {}
    md = ["# Study 4: cost per phase\n\n",
          "Hertz (uniform and graded meshes; Coulomb μ = 0.3, shift 0.004) and the block dragged on a flat "
          "foundation (uniform nx × nx/4; μ = 0.3, shift 0.008), P1, H = h, γ0 = 0.5 × bound, default settings "
          "(the active-set QP method; H by columns, by the partial factorization or not formed at all, the "
          "sparse saddle-point system solving every active-set step: column `condensation`). "
          "Times in seconds on the 2-core development machine (other jobs may have run concurrently). "
          "Regenerate with `cargo run --release -p tribo --example cost && python scripts/plot_cost.py`.\n\n"
          "## Fitted exponents (time ∝ n^p over the sizes where a phase takes ≥ 1 ms)\n\n"]
    table = []
    for fam, fr in groups:
        rs = [r for r in rows if r["family"] == fam and r["friction"] == fr and r["status"] == "converged"]
        for key, _ in PHASES:
            fits[(fam, fr, key)] = exponent(rs, key)
        table.append([fam, fr] + [rate_label(fits[(fam, fr, k)]).removeprefix("n^") for k, _ in PHASES])
    md.append(sl.markdown_table(["mesh", "friction"] + [name for _, name in PHASES], table))
    # The accurate regime: the graded family from about 7k unknowns on, where the contact work dominates.
    graded = [(fr, [r for r in rows if r["family"] == "graded" and r["friction"] == fr
                    and r["status"] == "converged" and r["n_free"] >= FROM]) for fr in FRICTIONS]
    graded = [(fr, rs) for fr, rs in graded if len(rs) >= 2]
    if graded:
        md.append(f"\nWhole solve on the graded family from {FROM // 1000}k unknowns on: "
                  + "; ".join(f"{fr} n^{exponent(rs, 'total'):.2f} ({int(rs[0]['n_free'])} to "
                              f"{int(rs[-1]['n_free'])} unknowns)" for fr, rs in graded) + ".\n")
        fits.update({("graded", fr, "total_from_7k"): exponent(rs, "total") for fr, rs in graded})
    memory = [r for r in rows if math.isfinite(r.get("peak_mb", math.nan)) and r["n_free"] >= 10_000]
    if memory:
        md.append("\n## Peak memory\n\nPeak resident memory of a solve (the problem included), per unknown, on the runs "
                  "from 10k unknowns: " + "; ".join(
                      f"{fam} {fr} {min(kb):.2f}–{max(kb):.2f} kB (largest: {int(big['n_free'])} unknowns, "
                      f"{big['peak_mb']:.0f} MB)"
                      for fam, fr in groups
                      for rs in [[r for r in memory if r["family"] == fam and r["friction"] == fr]] if rs
                      for kb in [[1024.0 * r["peak_mb"] / r["n_free"] for r in rs]]
                      for big in [max(rs, key=lambda r: r["n_free"])]) + ".\n")
    md.append("\n## All runs\n\n")
    md.append(sl.markdown_table(
        ["mesh", "h", "n", "q", "friction", "status", "iterations", "H by"] + [k for k, _ in PHASES]
        + ["total / Cholesky", "total / supernodal Cholesky", "peak MB"],
        [[r["family"], r["h"], int(r["n_free"]), int(r["q"]), r["friction"], r["status"], int(r["iterations"]),
          r["condensation"]] + [r[k] for k, _ in PHASES]
         + [r["ratio"], r.get("ratio_supernodal", math.nan), r.get("peak_mb", math.nan)] for r in rows]))
    (out / "cost.md").write_text("".join(md))

    plt = sl.pyplot()
    families = sorted({fam for fam, _ in groups}, key=FAMILIES.index)
    frictions = sorted({fr for _, fr in groups}, key=FRICTIONS.index)
    fig, axes = plt.subplots(len(frictions), len(families), figsize=(5.2 * len(families), 4.4 * len(frictions)),
                             sharey=True, squeeze=False)
    for ax in axes.flat:
        ax.set_visible(False)
    for fam, fr in groups:
        ax = axes[frictions.index(fr), families.index(fam)]
        ax.set_visible(True)
        rs = [r for r in rows if r["family"] == fam and r["friction"] == fr]
        for (key, name), c in zip(PHASES, ["C0", "C1", "C2", "C3", "k", "C7"]):
            ax.plot([r["n_free"] for r in rs], [max(r[key], 1e-5) for r in rs], "o-" if key != "cholesky" else "s--",
                    color=c, ms=4, lw=2.2 if key == "total" else 1.2, label=f"{name}: {rate_label(fits[(fam, fr, key)])}")
        # faer's supernodal Cholesky of K (sequential), where the run timed it: the factorization tribo takes for A.
        if all(math.isfinite(r.get("cholesky_supernodal", math.nan)) for r in rs):
            ax.plot([r["n_free"] for r in rs], [max(r["cholesky_supernodal"], 1e-5) for r in rs], "s:", color="C8", ms=4,
                    lw=1.2, label=f"supernodal Cholesky of K + solve: {rate_label(exponent(rs, 'cholesky_supernodal'))}")
        bad = [r for r in rs if r["status"] != "converged"]
        ax.plot([r["n_free"] for r in bad], [r["total"] for r in bad], "rx", ms=10, mew=2,
                label="not converged: " + ", ".join(sorted({r["status"] for r in bad})) if bad else None)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("displacement unknowns n")
        scene = {"block": "block on a foundation", "two_bodies": "two-body Hertz, graded"}.get(fam, f"Hertz, {fam} meshes")
        ax.set_title(f"{scene}, {fr}")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7, loc="upper left")
    for row in axes:
        row[0].set_ylabel("wall time  [s]")
    fig.suptitle("Cost per phase (fitted exponents over runs ≥ 1 ms, converged runs only)")
    fig.tight_layout()
    fig.savefig(out / "cost.png", dpi=70)
    plt.close(fig)
    return dict(rows=rows, fits=fits)


def main(argv: list[str] | None = None) -> dict[str, Any]:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--csv", type=Path, default=sl.DOCS / "cost.csv", help="input (default docs/cost.csv)")
    ap.add_argument("--out", type=Path, default=sl.DOCS, help="output directory (default docs/)")
    args = ap.parse_args(argv)
    return run(args.csv, args.out)


if __name__ == "__main__":
    main()
