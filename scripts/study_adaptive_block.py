"""Study 6c — adaptive refinement where everything touches: the block pressed onto a flat foundation.

The block (0, 4) × (0, 1) of the block scene (E = 200, ν = 0.3), clamped on its top, pressed δ = 0.01
onto a flat rigid foundation along its whole bottom edge, frictionless: λ_n is nearly uniform, with the
corners of the block as its singular points, and it depends on the stiffness of the whole body. Every
point is one run, wall clock, all levels and assemblies included:

* uniform: nx × nx/4 cells;
* graded toward the whole bottom edge (growth 0.3, h_max 0.1), h_min halved from 0.02;
* adaptive: `solve_adaptive` from the 8 × 2 uniform mesh, tol from 0.2 down.

Error: the relative L2 error of λ_n against a uniform 640 × 160 reference (205k unknowns; the 320 × 80
mesh is within 0.024 % of it), and the relative estimate the adaptive loop stopped on.

    python scripts/study_adaptive_block.py          # docs/adaptive_block.{md,csv,png}
    python scripts/study_adaptive_block.py --smoke --out /tmp/x
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
import studylib as sl  # noqa: E402

import tribo  # noqa: E402

BOX = ((0.0, 4.0), (0.0, 1.0))
UNIFORM = [20, 40, 80, 160]
GRADED = [0.02, 0.01, 0.005, 0.0025]
TOLS = [0.2, 0.1, 0.05, 0.03, 0.02, 0.01]
REFERENCE = 640
TARGETS = (0.01, 0.003)


def block(mesh: tribo.Mesh) -> tribo.Problem:
    return tribo.Problem(mesh, young=200.0, poisson=0.3, clamped="top", contact="bottom",
                         obstacle=tribo.Obstacle.flat(), approach=0.01)


def uniform(nx: int) -> tribo.Mesh:
    return tribo.Mesh.rectangle(*BOX, nx, nx // 4)


def run(smoke: bool, out: Path) -> list[dict[str, Any]]:
    ref = sl.make_reference(block(uniform(160 if smoke else REFERENCE)))
    rows: list[dict[str, Any]] = []

    def timed_row(family: str, key: float, make: Any, **adapt: Any) -> None:
        clock = time.perf_counter()
        if adapt:
            a = block(make()).solve_adaptive(**adapt)
            p, s, levels, relative, stop = a.problem, a.solution, len(a.levels), a.levels[-1].relative, a.stop
        else:
            p = block(make())
            s = p.solve()
            levels, relative, stop = 1, s.report.estimate["traction_relative"], s.report.status
        seconds = time.perf_counter() - clock
        rows.append(dict(family=family, key=key, n_free=p.n_free, q=p.n_multipliers, levels=levels,
                         seconds=seconds, error=ref.lambda_n_error(p, s), relative=relative, stop=stop))

    for nx in UNIFORM[:2] if smoke else UNIFORM:
        timed_row("uniform", nx, lambda nx=nx: uniform(nx))
    for h in GRADED[:2] if smoke else GRADED:
        timed_row("graded 0.3", h, lambda h=h: tribo.Mesh.graded_rectangle(
            *BOX, side="bottom", segment=BOX[0], h_min=h, h_max=0.1, growth=0.3))
    for tol in TOLS[:3] if smoke else TOLS:
        timed_row("adaptive", tol, lambda: uniform(8), tol=tol, stop_on="bound")
    write(rows, out)
    return rows


def write(rows: list[dict[str, Any]], out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)
    keys = ["family", "key", "n_free", "q", "levels", "seconds", "error", "relative", "stop"]
    sl.write_csv(out / "adaptive_block.csv", keys, [[r[k] for k in keys] for r in rows])
    families = ["uniform", "graded 0.3", "adaptive"]
    md = ["# Study 6c: adaptive refinement where everything touches (the block on a flat foundation)\n\n",
          "Regenerate with `python scripts/study_adaptive_block.py`; every number is in `adaptive_block.csv`. "
          "λ_n errors against the uniform 640 × 160 reference; wall times on the 2-core machine, all levels "
          "included. `key`: nx (uniform), h_min (graded), tol (adaptive).\n\n"]
    for target in TARGETS:
        md.append(f"## The cheapest run within {target:.1%} in λ_n\n\n")
        table = []
        for fam in families:
            ok = [r for r in rows if r["family"] == fam and r["error"] <= target]
            best = min(ok, key=lambda r: r["n_free"]) if ok else None
            table.append([fam] + ([best["key"], best["n_free"], best["seconds"], best["error"], best["levels"]]
                                  if best else ["not reached", math.nan, math.nan, math.nan, ""]))
        md.append(sl.markdown_table(["mesh", "key", "unknowns", "seconds", "λ_n error", "levels"], table))
        md.append("\n")
    md.append("## Every run\n\n")
    md.append(sl.markdown_table(
        ["mesh", "key", "unknowns", "multipliers", "levels", "seconds", "λ_n error", "estimate", "stop"],
        [[r[k] for k in keys] for r in rows]))
    (out / "adaptive_block.md").write_text("".join(md))

    plt = sl.pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    for fam, mk in zip(families, (".--", "s--", "o-"), strict=True):
        rs = sorted((r for r in rows if r["family"] == fam), key=lambda r: r["n_free"])
        axes[0].loglog([r["n_free"] for r in rs], [r["error"] for r in rs], mk, label=fam)
        axes[1].loglog([r["seconds"] for r in rs], [r["error"] for r in rs], mk, label=fam)
    for ax, xlabel in zip(axes, ("unknowns", "wall time, all levels [s]"), strict=True):
        for target in TARGETS:
            ax.axhline(target, color="0.5", lw=0.8, ls=":")
        ax.set_xlabel(xlabel)
        ax.set_ylabel("relative L2 error of λ_n vs the reference")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.suptitle("The block pressed on a flat foundation (frictionless): uniform, graded and adaptive meshes")
    fig.tight_layout()
    fig.savefig(out / "adaptive_block.png", dpi=85)
    plt.close(fig)


def main(argv: list[str] | None = None) -> list[dict[str, Any]]:
    return sl.cli(run, __doc__, argv)  # type: ignore[no-any-return]


if __name__ == "__main__":
    main()
