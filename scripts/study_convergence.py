"""Study 3 — observed convergence rates under refinement.

Hertz (R = 1, approach 0.01), P1 multipliers on T_H = the FE edges, γ0 = 0.5 × bound, frictionless and
Coulomb (μ = 0.3, shift 0.004; QP tolerance 1e-12 so that the fixed point converges on every mesh, see
study 1c). Three mesh families:

* "graded": toward [−0.3, 0.3] at growth 0.3, h_min 0.04 → 0.00125. Its growth stays, so it converges to
  that grading's own bias (1.4 % in λ_n), not to the solution;
* "graded, growth ∝ h_min": the same with growth = 15 h_min (0.6 → 0.0375), so that the grading refines
  with h_min (h_min 0.04 → 0.0025);
* "uniform": h = 0.2 → 0.025.

Measured, all against the converged reference of study 2 (`studylib.REFERENCE`, 175k unknowns, for each
law), and for frictionless λ_n also against Hertz (whose half-space model is 0.38 % off the finite block):

* λ_n: relative L2 error;
* σ_n(u_h) (−σ_n, constant per FE edge): relative L2 error against the reference λ_n;
* u_h: relative energy-norm error.

The observed rate is the least-squares slope of log(error) against log(h) (h_min for graded meshes) and
against log(n) (n = displacement unknowns; an error ~ h^r on a uniform 2D mesh is ~ n^(−r/2)).

    python scripts/study_convergence.py             # docs/convergence.{md,csv,png}
    python scripts/study_convergence.py --smoke --out /tmp/x
"""

from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
import studylib as sl  # noqa: E402
import study_work_precision as wp  # noqa: E402

GRADED = [0.04, 0.02, 0.01, 0.005, 0.0025, 0.00125]
REFINED = [0.04, 0.02, 0.01, 0.005, 0.0025]  # growth = 15 h_min
FAMILIES = ("graded", "graded, growth ∝ h_min", "uniform")
UNIFORM = [20, 40, 80, 160]
QP_TOL = 1e-12
QUANTITIES = [("lam", "λ_n (L2)"), ("sig", "σ_n(u_h) (L2)"), ("energy", "u_h (energy)"),
              ("hertz", "λ_n vs Hertz (L2)")]


def family_mesh(family: str, size: float) -> tuple[float, Any]:
    """(h, mesh) of `family` at `size` (h_min, or nx for uniform meshes)."""
    if family == "uniform":
        return 4.0 / size, sl.uniform_mesh(int(size))
    return size, sl.graded_mesh(size, growth=0.3 if family == "graded" else 15.0 * size)


def run(smoke: bool, out: Path) -> dict[str, Any]:
    sizes = {"graded": [0.04, 0.02, 0.01] if smoke else GRADED,
             "graded, growth ∝ h_min": [0.04, 0.02, 0.01] if smoke else REFINED,
             "uniform": [20, 40, 80] if smoke else UNIFORM}
    rows: list[dict[str, Any]] = []
    refs: dict[str, Any] = {}
    for friction in ("frictionless", "coulomb"):
        coulomb = friction == "coulomb"
        ref, refs[friction] = wp.reference(coulomb, smoke)
        for family in FAMILIES:
            for size in sizes[family]:
                h, mesh = family_mesh(family, size)
                problem = sl.hertz_problem(mesh, shift=wp.SHIFT if coulomb else 0.0)
                sol = problem.solve(**(dict(mu=wp.MU, qp_tol=QP_TOL) if coulomb else {}))
                row = dict(friction=friction, family=family, h=h, n_free=problem.n_free, status=sol.report.status,
                           lam=ref.lambda_n_error(problem, sol), sig=ref.sigma_n_error(problem, sol),
                           energy=ref.energy_error(problem, sol),
                           hertz=math.nan if coulomb else sl.lambda_l2_error(problem, sol))
                rows.append(row)
                print(f"{friction:>12} {family:>7} h={h:<8.4g} n={row['n_free']:>6} {row['status']:>10} "
                      f"λ_n {row['lam']:.3e}  σ_n {row['sig']:.3e}  energy {row['energy']:.3e}")
    rates = write(rows, refs, out)
    return dict(rows=rows, refs=refs, rates=rates)


def write(rows: list[dict[str, Any]], refs: dict[str, Any], out: Path) -> dict[tuple[str, str, str], tuple[float, float]]:
    out.mkdir(parents=True, exist_ok=True)
    keys = ["friction", "family", "h", "n_free", "status", "lam", "sig", "energy", "hertz"]
    sl.write_csv(out / "convergence.csv", keys, [[r[k] for k in keys] for r in rows])
    rates: dict[tuple[str, str, str], tuple[float, float]] = {}
    table = []
    for friction in ("frictionless", "coulomb"):
        for family in FAMILIES:
            rs = [r for r in rows if r["friction"] == friction and r["family"] == family]
            for key, name in QUANTITIES:
                if key == "hertz" and friction == "coulomb":
                    continue
                vs_h = sl.fitted_rate([r["h"] for r in rs], [r[key] for r in rs])
                vs_n = sl.fitted_rate([r["n_free"] for r in rs], [r[key] for r in rs])
                rates[(friction, family, key)] = (vs_h, vs_n)
                against = "Hertz" if key == "hertz" else "reference"
                table.append([friction, family, name, against, f"{vs_h:.2f}", f"{-vs_n:.2f}",
                              f"{rs[0][key]:.3g} → {rs[-1][key]:.3g}", f"{rs[0]['n_free']} → {rs[-1]['n_free']}"])
    md = ["# Study 3: observed convergence rates\n\n",
          "Hertz, P1, H = h, γ0 = 0.5 × bound; Coulomb μ = 0.3, shift 0.004 (QP tolerance 1e-12). Rate vs h: "
          "slope of log(error) against log(h) (h_min for graded meshes, all sizes fitted); rate vs n: minus the "
          "slope against the number of displacement unknowns. Regenerate with `python scripts/study_convergence.py`.\n\n",
          "References: " + "; ".join(f"{k}: graded toward [−{v['half']}, {v['half']}], h_min = {v['h_min']}, growth "
                                     f"{v['growth']}, h_max = {v['h_max']}, {v['n_free']} unknowns"
                                     for k, v in refs.items()) + ".\n\n"]
    md.append(sl.markdown_table(["friction", "mesh", "quantity", "against", "rate vs h", "rate vs n", "error (coarsest → finest)",
                                 "unknowns"], table))
    (out / "convergence.md").write_text("".join(md))

    plt = sl.pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8), sharey=True)
    for ax, friction in zip(axes, ("frictionless", "coulomb")):
        for (key, name), c in zip(QUANTITIES, ["C0", "C1", "C2", "C3"]):
            if key == "hertz" and friction == "coulomb":
                continue
            for family, ls, mk in (("graded", "-", "o"), ("graded, growth ∝ h_min", "--", "^"), ("uniform", ":", "s")):
                rs = [r for r in rows if r["friction"] == friction and r["family"] == family]
                vs_n = rates[(friction, family, key)][1]
                ax.plot([r["n_free"] for r in rs], [r[key] for r in rs], ls, marker=mk, color=c, ms=4,
                        label=f"{family}: {name}, rate n^{vs_n:.2f}")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("displacement unknowns n")
        ax.set_ylabel("relative error  [–]")
        ax.set_title("frictionless (vs the reference; λ_n also vs Hertz)" if friction == "frictionless"
                     else f"Coulomb μ = {wp.MU}, shift {wp.SHIFT} (vs the reference)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "convergence.png", dpi=90)
    plt.close(fig)
    return rates


def main(argv: list[str] | None = None) -> dict[str, Any]:
    return sl.cli(run, __doc__, argv)


if __name__ == "__main__":
    main()
