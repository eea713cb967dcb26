"""Study 20 — which Coulomb method converges where: the fixed point of Φ_H and the semismooth Newton method.

docs/coulomb_map.csv is written by the Rust example `cargo run --release -p tribo --example coulomb_map` (its
documentation gives the scenes: Hertz shifted along its top under displacement control, and a block held only by
the contact under force control, over μ and Poisson's ratio ν, and a wedge forced into a V-groove over μ and
its half-angle); this script writes docs/coulomb_map.md (per scene
and method: how many problems converged, the iterations, the largest difference of the two answers) and
docs/coulomb_map.png (the iterations over μ × ν, a cross where a method did not converge, a grey square where the
problem has no solution).

    cargo run --release -p tribo --example coulomb_map && python scripts/plot_coulomb_map.py
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
import studylib as sl  # noqa: E402

METHODS = ("fixed_point", "newton")
TEXT = ("scene", "method", "status", "solvable", "check")
VERDICTS = ("agree", "differ", "undecided")


def load(path: Path) -> list[dict[str, Any]]:
    """The rows, numbers as floats; `check` (the verdict of `coulomb_check` on the fixed point's answer) empty
    where the fixed point did not converge or the CSV predates it."""
    rows = [{k: (v if k in TEXT else float(v)) for k, v in r.items()} for r in sl.read_csv_rows(path)]
    return [{"check": "", **r} for r in rows]


# What τ is a fraction of, per block: min(μ, its overturning load W / (2H)).
HOLDS = {"held block": "min(μ, 1)", "tall block": "min(μ, 1/12)"}


def family(r: dict[str, Any]) -> str:
    """The scene and its load: `hertz`, `wedge`, or `held block, τ = 0.5 min(μ, 1)`."""
    if math.isnan(r["load_fraction"]) or r["scene"] in ("wedge", "two bodies"):
        return str(r["scene"])
    return f"{r['scene']}, τ = {r['load_fraction']:g} {HOLDS[r['scene']]}"


def second(r: dict[str, Any]) -> float:
    """The second axis of a problem: Poisson's ratio ν, the wedge's half-angle α in degrees or the two bodies' Dundurs
    β (which their rows carry in the load_fraction column)."""
    return float(r["load_fraction"] if r["scene"] in ("wedge", "two bodies") else r["nu"])


def summary(rows: list[dict[str, Any]]) -> dict[tuple[str, str], dict[str, Any]]:
    """Per (family, method), over the problems that have a solution: problems, converged, iterations of the
    converged (min, max, median), which did not converge, and the largest difference of the two methods' λ where
    both converged; how the method ended the problems that have none (`unsolvable`); and the verdicts of the check
    of the fixed point's answer by Newton over the problems that have a solution (`checks`: verdict → count; `differ`:
    where it said so)."""
    out: dict[tuple[str, str], dict[str, Any]] = {}
    for f in dict.fromkeys(family(r) for r in rows):
        for m in METHODS:
            every = [r for r in rows if family(r) == f and r["method"] == m]
            rs = [r for r in every if r["solvable"] == "true"]
            its = sorted(int(r["iterations"]) for r in rs if r["status"] == "converged")
            diffs = [r["lambda_difference"] for r in rs if not math.isnan(r["lambda_difference"])]
            out[(f, m)] = dict(problems=len(rs), converged=len(its), iterations=its,
                               failed=[(second(r), r["mu"], r["status"]) for r in rs if r["status"] != "converged"],
                               difference=max(diffs) if diffs else math.nan,
                               unsolvable=[(second(r), r["mu"], r["status"]) for r in every if r["solvable"] != "true"],
                               checks={v: sum(r["check"] == v for r in rs) for v in VERDICTS},
                               differ=[(second(r), r["mu"]) for r in rs if r["check"] == "differ"])
    return out


def run(csv_path: Path, out: Path) -> dict[tuple[str, str], dict[str, Any]]:
    rows = load(csv_path)
    out.mkdir(parents=True, exist_ok=True)
    s = summary(rows)
    table = []
    for (f, m), v in s.items():
        its = v["iterations"]
        ends = sorted({st for _, _, st in v["unsolvable"]})
        table.append([f, m, f"{v['converged']} of {v['problems']}",
                      f"{its[0]}–{its[-1]}" if its else "—", its[len(its) // 2] if its else "—",
                      f"{v['difference']:.1e}",
                      "; ".join(f"{ {'wedge': 'α', 'two bodies': 'β'}.get(f, 'ν')} {nu:g} μ {mu:g}: {st}"
                                for nu, mu, st in v["failed"]) or "—",
                      f"{len(v['unsolvable'])}: {', '.join(ends)}" if v["unsolvable"] else "—",
                      ", ".join(f"{n} {k}" for k, n in v["checks"].items() if n) or "—"])
    md = ["# Study 20: which Coulomb method converges where\n\n",
          "Regenerate with `cargo run --release -p tribo --example coulomb_map && python scripts/plot_coulomb_map.py`;"
          " every number is in `coulomb_map.csv`. Each problem is solved by the fixed point of Φ_H (one Tresca QP "
          "per iteration, the reference) and by the semismooth Newton method (one dense LU solve per step), over μ "
          "from 0.05 to 2 and Poisson's ratio ν from 0 (the normal and tangential problems couple the most) to "
          "0.45. `hertz`: the Hertz scene (graded, h_min 0.01) with the cylinder pushed 0.01 and shifted 0.004, "
          "displacement control. `held block`: a block (0, 2) × (0, 1) held only by the contact (no support), "
          "pressed onto a flat foundation by a traction (τ, −1), force control, τ a fraction of min(μ, 1) (beyond "
          "τ = μ it slides, beyond τ = 1 it overturns; the discrete problem, whose P1 multipliers put the pressure at "
          "best on the last dof with its centroid h/3 from the corner, has no solution beyond τ = 1 − h/3 = 0.983 on "
          "these meshes: both methods must fail there, and the last column says how each ended those problems). "
          "`tall block`: the block (0, 1) × (0, 6) loaded alike, τ a fraction of min(μ, W / (2H)) = min(μ, 1/12), "
          "its overturning (the discrete limit (W / 2 − h / 3) / H = 0.0806 lies above both fractions). `wedge`: a "
          "wedge of half-angle α (15° to 45°, the second axis in its place of ν; ν = 0.3) forced into a rigid V-groove "
          "by a traction on its top, held by nothing else (force control on a bent contact side): sliding in, the "
          "frozen bound multiplies the fixed point's error by about −μ cot α, so the plain fixed point cycles where "
          "μ > tan α and the flanks slip, until μ is large enough for the wedge to stick. `two bodies`: two-body "
          "Hertz (h_min 0.02, the upper top pushed 0.01 and held in x), ν = 0, the lower E = 200 and the upper E = "
          "200, 70, 20, 2, so that the Dundurs β (0, 0.24, 0.41, 0.49, the second axis) alone makes the friction. The "
          "difference is the largest |Δλ| of the two answers "
          "relative to the largest λ_n, where both converged: the fixed point stops at a relative change of "
          "`fp_tol` = 1e-8. The last column is the verdict of `coulomb_check` on the fixed point's answer (Newton solves "
          "the problem again and the two are compared within the bound their residuals and the fixed point's "
          "contraction give: agree, differ where the discrete problem has two solutions, undecided where Newton does "
          "not converge), over the problems with a solution where the fixed point converged.\n\n",
          sl.markdown_table(["scene", "method", "converged (of the problems with a solution)", "iterations",
                             "median", "largest difference", "not converged (ν, μ: status)",
                             "problems without a solution: how they ended", "coulomb_check"], table), "\n"]
    (out / "coulomb_map.md").write_text("".join(md))
    families = list(dict.fromkeys(family(r) for r in rows))
    plt = sl.pyplot()
    fig, axes = plt.subplots(len(METHODS), len(families), figsize=(4.2 * len(families), 7.0), squeeze=False,
                             layout="constrained")
    top = max(int(r["iterations"]) for r in rows)
    for j, f in enumerate(families):
        nus = sorted({second(r) for r in rows if family(r) == f})
        mus = sorted({r["mu"] for r in rows if family(r) == f})
        for i, m in enumerate(METHODS):
            ax = axes[i][j]
            grid = [[math.nan] * len(mus) for _ in nus]
            for r in rows:
                if family(r) == f and r["method"] == m:
                    a, b = nus.index(second(r)), mus.index(r["mu"])
                    grid[a][b] = r["iterations"] if r["status"] == "converged" else math.nan
                    if r["solvable"] != "true":
                        ax.plot(b, a, "s", color="0.6", ms=11)  # no solution: both must fail
                    if r["status"] != "converged":
                        ax.plot(b, a, "kx", ms=9)
                    else:
                        ax.text(b, a, f"{int(r['iterations'])}", ha="center", va="center", fontsize=7)
            image = ax.imshow(grid, origin="lower", aspect="auto", cmap="viridis", vmin=0, vmax=top)
            ax.set_xticks(range(len(mus)), [f"{v:g}" for v in mus], fontsize=7)
            ax.set_yticks(range(len(nus)), [f"{v:.3g}" for v in nus], fontsize=7)
            ax.set_xlabel("μ")
            ax.set_ylabel({"wedge": "wedge half-angle α (°)", "two bodies": "Dundurs β"}.get(f, "ν"))
            ax.set_title(f"{f}\n{m.replace('_', ' ')}", fontsize=9)
    fig.colorbar(image, ax=axes, label="iterations (×: not converged; grey square: no solution)", shrink=0.8)
    fig.savefig(out / "coulomb_map.png", dpi=85)
    plt.close(fig)
    return s


def main(argv: list[str] | None = None) -> dict[tuple[str, str], dict[str, Any]]:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--csv", type=Path, default=sl.DOCS / "coulomb_map.csv")
    ap.add_argument("--out", type=Path, default=sl.DOCS)
    args = ap.parse_args(argv)
    return run(args.csv, args.out)


if __name__ == "__main__":
    main()
