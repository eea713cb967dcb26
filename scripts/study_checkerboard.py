"""Study 1a — where the classic method fails: T_H finer than T_h.

Uniform mesh 80 × 40 on (−2, 2) × (−2, 0) (h = 0.05), approach 0.05 (Hertz half-width a ≈ 0.18),
frictionless. For H/h ∈ {1/4, 1/2, 1, 2, 4}, γ0 ∈ {0, 0.1, 0.3, 0.5, 0.9} × the admissible bound and P1 / P0
multipliers: the oscillation indicator TV(λ_n)/(2 p_max), the relative L2 error of λ_n against Hertz, and
the traction estimate the solve reports (`report.estimate["traction_relative"]`): a checkerboard
must show in the estimate, not hide behind a smooth σ_h n.

    python scripts/study_checkerboard.py            # docs/checkerboard.{md,csv,png}
    python scripts/study_checkerboard.py --smoke --out /tmp/x
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import studylib as sl  # noqa: E402

HEADERS = ["space", "H/h", "theta", "gamma0", "status", "TV ratio", "L2 error", "estimate", "force", "q", "seconds"]


def run(smoke: bool, out: Path) -> list[dict[str, Any]]:
    nx, approach = (20, 0.2) if smoke else (80, 0.05)
    ratios = [0.25, 1.0] if smoke else [0.25, 0.5, 1.0, 2.0, 4.0]
    thetas = [0.0, 0.5] if smoke else [0.0, 0.1, 0.3, 0.5, 0.9]
    spaces = ["P1", "P0"]
    mesh = sl.uniform_mesh(nx)
    rows: list[dict[str, Any]] = []
    for space in spaces:
        for ratio in ratios:
            problem = sl.hertz_problem(mesh, approach=approach, space=space, ratio=ratio)
            for theta in thetas:
                sol, sec = sl.timed(lambda: problem.solve(gamma0_fraction=theta))
                rows.append(
                    dict(
                        space=space,
                        ratio=ratio,
                        theta=theta,
                        gamma0=sol.report.gamma0,
                        status=sol.report.status,
                        tv=sl.oscillation(sol),
                        l2=sl.lambda_l2_error(problem, sol),
                        estimate=sol.report.estimate["traction_relative"],
                        force=sol.normal_force,
                        q=problem.n_multipliers,
                        seconds=sec,
                    )
                )
                r = rows[-1]
                print(f"{space} H/h={ratio:<5} θ={theta:<4} {r['status']:>10} TV {r['tv']:7.2f}  L2 {r['l2']:.3e}"
                      f"  estimate {r['estimate']:.3e}")
    write(rows, ratios, thetas, spaces, out, nx, approach)
    return rows


def write(rows: list[dict[str, Any]], ratios: list[float], thetas: list[float], spaces: list[str], out: Path,
          nx: int, approach: float) -> None:
    out.mkdir(parents=True, exist_ok=True)
    keys = ["space", "ratio", "theta", "gamma0", "status", "tv", "l2", "estimate", "force", "q", "seconds"]
    sl.write_csv(out / "checkerboard.csv", HEADERS, [[r[k] for k in keys] for r in rows])
    get = {(r["space"], r["ratio"], r["theta"]): r for r in rows}
    md = [
        f"# Study 1a: T_H finer than T_h (uniform {nx} × {nx // 2}, h = {4 / nx:g}, approach {approach:g})\n",
        "Oscillation indicator TV(λ_n)/(2 p_max) (1 = smooth single peak) / relative L2 error of λ_n "
        "against Hertz / the traction estimate ζ / min(‖λ_H‖, ‖σ_h n‖) the solve reports; θ = γ0 / admissible "
        "bound "
        "(θ = 0: classic method). Regenerate with "
        "`python scripts/study_checkerboard.py`.\n",
    ]
    for space in spaces:
        md.append(f"\n## {space} multipliers\n\n")
        table = []
        for ratio in ratios:
            table.append(
                [f"{ratio:g}"]
                + [f"{get[(space, ratio, t)]['tv']:.2f} / {get[(space, ratio, t)]['l2']:.3f} / "
                   f"{get[(space, ratio, t)]['estimate']:.3f}" for t in thetas]
            )
        md.append(sl.markdown_table(["H/h"] + [f"θ = {t:g}" for t in thetas], table))
    failed = [r for r in rows if r["status"] != "converged"]
    md.append(f"\nSolves not converged: {len(failed)} of {len(rows)}.\n")
    (out / "checkerboard.md").write_text("".join(md))

    plt = sl.pyplot()
    fig, axes = plt.subplots(2, len(spaces), figsize=(11, 7.5), sharex=True)
    colors = plt.cm.viridis(np.linspace(0.0, 0.85, len(thetas)))
    for j, space in enumerate(spaces):
        for t, c in zip(thetas, colors):
            tv = [get[(space, r, t)]["tv"] for r in ratios]
            l2 = [get[(space, r, t)]["l2"] for r in ratios]
            label = "γ0 = 0 (classic)" if t == 0 else f"γ0 = {t:g} × bound"
            axes[0, j].plot(ratios, tv, "o-", color=c, label=label)
            axes[1, j].plot(ratios, l2, "o-", color=c, label=label)
            est = [get[(space, r, t)]["estimate"] for r in ratios]
            axes[1, j].plot(ratios, est, "s--", color=c, alpha=0.6)
        axes[0, j].axhline(1.0, color="0.6", lw=0.8, ls=":")
        axes[0, j].set_title(f"{space} multipliers")
        axes[0, j].set_ylabel("oscillation TV(λ_n) / (2 p_max)  [–]")
        axes[1, j].set_ylabel("λ_n: L2 error vs Hertz (solid), estimate (dashed)  [–]")
        axes[1, j].set_xlabel("H / h  (multiplier size / FE size)")
        for ax in axes[:, j]:
            ax.set_xscale("log", base=2)
            ax.set_yscale("log")
            ax.set_xticks(ratios, [f"{r:g}" for r in ratios])
            ax.grid(True, which="both", alpha=0.3)
        axes[0, j].legend(fontsize=8)
    fig.suptitle(f"T_H finer than T_h: uniform mesh h = {4 / nx:g}, Hertz approach {approach:g}, frictionless")
    fig.tight_layout()
    fig.savefig(out / "checkerboard.png", dpi=90)
    plt.close(fig)


def main(argv: list[str] | None = None) -> list[dict[str, Any]]:
    return sl.cli(run, __doc__, argv)


if __name__ == "__main__":
    main()
