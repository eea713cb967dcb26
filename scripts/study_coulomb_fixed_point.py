"""Study 1c — where the Coulomb fixed point stops converging, and what relaxation recovers.

Hertz with Coulomb friction (approach 0.01, obstacle shift s = 0.004), graded mesh h_min = 0.01, P1, H = h,
γ0 = 0.5 × bound, working-set QP (the default, `qp_method = "auto"`), fixed point `g ← (1 − ω) g + ω Φ_H(g)`
with at most 100 iterations. Grid: μ from 0 to 2, ν ∈ {0, 0.2, 0.3, 0.45}, ω ∈ {1, 0.5, 0.25} with the QP
tolerance 1e-10 (the fallback tolerance), and ω = 1 with the default qp_tol = 1e-12; then ω = 1 with clarabel
answering every QP (`qp_method = "clarabel"`, the reference QP method) at both tolerances, each answer compared
with the default's of the same setting: the relative difference of the tangential force Q. Then μ = 0.3, ν = 0.3
under refinement (h_min 0.04 → 0.00125) for every setting.

    python scripts/study_coulomb_fixed_point.py     # docs/coulomb_fixed_point.{md,csv,png}
    python scripts/study_coulomb_fixed_point.py --smoke --out /tmp/x
"""

from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import studylib as sl  # noqa: E402

MUS = [0.0, 0.1, 0.2, 0.3, 0.5, 0.7, 0.9, 1.1, 1.3, 1.5, 2.0]
NUS = [0.0, 0.2, 0.3, 0.45]
# (relaxation ω, QP tolerance, QP method): QP tolerance 1e-10 (the fallback tolerance, and the default before 0.1)
# with three ω, and ω = 1 with the default 1e-12; then clarabel answering every QP at both tolerances.
OMEGAS = [(1.0, 1e-10, "auto"), (0.5, 1e-10, "auto"), (0.25, 1e-10, "auto"), (1.0, 1e-12, "auto"),
          (1.0, 1e-10, "clarabel"), (1.0, 1e-12, "clarabel")]
H_MINS = [0.04, 0.02, 0.01, 0.005, 0.0025, 0.00125]
SHIFT = 0.004


Setting = tuple[float, float, str]


def solve_row(problem: Any, mu: float, setting: Setting, **extra: Any) -> dict[str, Any]:
    """One fixed point; with clarabel, ``q_apart`` is the relative difference of its tangential force from the
    default method's with the same ω and qp_tol (NaN where that one did not converge)."""
    omega, qp_tol, method = setting
    sol, sec = sl.timed(lambda: problem.solve(mu=mu, fp_relaxation=omega, qp_tol=qp_tol, qp_method=method))
    rep = sol.report
    hist = rep.residual_history
    q_apart = math.nan
    if method != "auto":
        other = problem.solve(mu=mu, fp_relaxation=omega, qp_tol=qp_tol)
        if other.report.status == "converged" and rep.status == "converged":
            q_apart = abs(sol.tangential_force - other.tangential_force) / max(abs(other.tangential_force), 1e-300)
    row = dict(mu=mu, omega=omega, qp_tol=qp_tol, qp_method=method, setting=setting, status=rep.status,
               iterations=rep.iterations, last_change=float(hist[-1]) if len(hist) else 0.0, seconds=sec,
               force=sol.normal_force, stick=int(sum(1 for s in sol.state_names if s == "stick")),
               slip=int(sum(1 for s in sol.state_names if s == "slip")), qp_inaccurate=rep.qp_inaccurate,
               q_apart=q_apart, **extra)
    return row


def run(smoke: bool, out: Path) -> dict[str, Any]:
    mus = [0.0, 0.3, 1.5] if smoke else MUS
    nus = [0.3] if smoke else NUS
    omegas = [(1.0, 1e-10, "auto"), (1.0, 1e-12, "auto"), (1.0, 1e-12, "clarabel")] if smoke else OMEGAS
    h_mins = [0.04, 0.02] if smoke else H_MINS
    h_grid = 0.04 if smoke else 0.01
    grid: list[dict[str, Any]] = []
    for nu in nus:
        problem = sl.hertz_problem(sl.graded_mesh(h_grid), shift=SHIFT, poisson=nu)
        for omega in omegas:
            for mu in mus:
                grid.append(solve_row(problem, mu, omega, nu=nu, h_min=h_grid, n_free=problem.n_free))
                r = grid[-1]
                print(f"ν={nu:<5} ω, qp_tol={omega} μ={mu:<4} {r['status']:>15} it {r['iterations']:>3} "
                      f"change {r['last_change']:.1e}  {r['seconds']:.2f} s")
    refine: list[dict[str, Any]] = []
    for h in h_mins:
        problem = sl.hertz_problem(sl.graded_mesh(h), shift=SHIFT)
        for omega in omegas:
            refine.append(solve_row(problem, 0.3, omega, nu=sl.POISSON, h_min=h, n_free=problem.n_free))
            r = refine[-1]
            print(f"h_min={h:<8} ω, qp_tol={omega} {r['status']:>15} it {r['iterations']:>3} "
                  f"change {r['last_change']:.1e}  {r['seconds']:.2f} s")
    write(grid, refine, mus, nus, omegas, h_grid, out)
    return dict(grid=grid, refine=refine)


def name(setting: Setting) -> str:
    method = "" if setting[2] == "auto" else f", {setting[2]}"
    return f"ω = {setting[0]:g}, qp_tol = {setting[1]:.0e}{method}"


def first_failure(rows: list[dict[str, Any]], nu: float, omega: Setting) -> float:
    """Smallest μ whose fixed point did not converge (nan if all converged)."""
    bad = [r["mu"] for r in rows if r["nu"] == nu and r["setting"] == omega and r["status"] != "converged"]
    return min(bad) if bad else math.nan


def write(grid: list[dict[str, Any]], refine: list[dict[str, Any]], mus: list[float], nus: list[float],
          omegas: list[Setting], h_grid: float, out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)
    keys = ["h_min", "n_free", "nu", "omega", "qp_tol", "qp_method", "mu", "status", "iterations", "last_change",
            "seconds", "force", "stick", "slip", "qp_inaccurate", "q_apart"]
    sl.write_csv(out / "coulomb_fixed_point.csv", keys, [[r[k] for k in keys] for r in grid + refine])
    get = {(r["nu"], r["setting"], r["mu"]): r for r in grid}
    md = [f"# Study 1c: the Coulomb fixed point against μ, ν and the relaxation ω\n\n"
          f"Hertz, approach 0.01, shift {SHIFT}, graded h_min = {h_grid}, P1, H = h, γ0 = 0.5 × bound, "
          "working-set QP, at most 100 iterations. Entry: fixed-point iterations; for a run that did not converge "
          "its status (`stagnated`: no new smallest change for 10 iterations) and the last relative change "
          "of λ_n in brackets; with clarabel, after the slash, the relative difference of the tangential force Q "
          "from the default method's answer with the same ω and qp_tol. qp_tol = 1e-12 is the default. Regenerate with "
          "`python scripts/study_coulomb_fixed_point.py`.\n"]

    def cell(r: dict[str, Any]) -> str:
        apart = "" if math.isnan(r["q_apart"]) else f" / {r['q_apart']:.0e}"
        if r["status"] == "converged":
            return f"{r['iterations']}{apart}"
        return f"{r['status']} at {r['iterations']} ({r['last_change']:.0e})"

    for omega in omegas:
        md.append(f"\n## {name(omega)}\n\n")
        md.append(sl.markdown_table(["ν \\ μ"] + [f"{m:g}" for m in mus],
                                    [[f"{nu:g}"] + [cell(get[(nu, omega, m)]) for m in mus] for nu in nus]))
    md.append("\n## Smallest μ that does not converge\n\n")
    md.append(sl.markdown_table(["ν"] + [name(o) for o in omegas],
                                [[f"{nu:g}"] + [first_failure(grid, nu, o) for o in omegas] for nu in nus]))
    md.append("\n## Under refinement, μ = 0.3, ν = 0.3\n\n")
    hs = sorted({r["h_min"] for r in refine}, reverse=True)
    rget = {(r["h_min"], r["setting"]): r for r in refine}
    md.append(sl.markdown_table(["h_min", "unknowns"] + [name(o) for o in omegas],
                                [[h, rget[(h, omegas[0])]["n_free"]] + [f"{cell(rget[(h, o)])}, {rget[(h, o)]['seconds']:.2g} s"
                                                                          for o in omegas] for h in hs]))
    (out / "coulomb_fixed_point.md").write_text("".join(md))

    plt = sl.pyplot()
    columns = (len(omegas) + 2) // 2
    fig, grid_axes = plt.subplots(2, columns, figsize=(3.9 * columns, 8.4))
    axes = list(grid_axes.flat)
    for ax in axes[len(omegas) + 1:]:
        ax.set_visible(False)
    colors = plt.cm.plasma(np.linspace(0.0, 0.8, len(nus)))
    for ax, omega in zip(axes, omegas):
        for nu, c in zip(nus, colors):
            rs = [get[(nu, omega, m)] for m in mus]
            ax.plot(mus, [r["iterations"] for r in rs], "o-", color=c, ms=4, label=f"ν = {nu:g}")
            bad = [r for r in rs if r["status"] != "converged"]
            ax.plot([r["mu"] for r in bad], [r["iterations"] for r in bad], "x", color=c, ms=10, mew=2)
        ax.set_title(f"{name(omega)}\n(× = not converged: stagnated)")
        ax.set_xlabel("friction coefficient μ  [–]")
        ax.set_ylabel("fixed-point iterations")
        ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    ax = axes[len(omegas)]
    for omega, c in zip(omegas, [f"C{k}" for k in range(len(omegas))]):
        rs = [rget[(h, omega)] for h in hs]
        ax.plot([r["n_free"] for r in rs], [r["iterations"] for r in rs], "o-", color=c, label=name(omega))
        bad = [r for r in rs if r["status"] != "converged"]
        ax.plot([r["n_free"] for r in bad], [r["iterations"] for r in bad], "x", color=c, ms=10, mew=2)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("displacement unknowns (graded meshes)")
    ax.set_ylabel("fixed-point iterations")
    ax.set_title("μ = 0.3, ν = 0.3 under refinement")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.suptitle(f"Coulomb fixed point, Hertz with shift {SHIFT} (grid on graded h_min = {h_grid})")
    fig.tight_layout()
    fig.savefig(out / "coulomb_fixed_point.png", dpi=90)
    plt.close(fig)


def main(argv: list[str] | None = None) -> dict[str, Any]:
    return sl.cli(run, __doc__, argv)


if __name__ == "__main__":
    main()
