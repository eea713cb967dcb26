"""Study 6 — accuracy without a guess: adaptive refinement against hand-graded and uniform meshes.

Hertz (R = 1, approach 0.01, E = 200, ν = 0.3, frictionless) on the block (−2, 2) × (−2, 0), with the
cylinder at the centre and off the centre (x = 0.3). Every point is one run: `tribo.Problem(...)` and
`solve()` for the fixed meshes, `solve_adaptive(tol=…)` for the adaptive one (wall clock, every level and
every assembly included). Families:

* uniform: nx × nx/2 cells;
* graded, growth 0.3 and growth 0.15: `Mesh.graded_rectangle` toward [−0.3, 0.3] (the scene's hint, which
  covers both contact zones), h_max = 0.5, h_min halved from 0.04;
* adaptive: from the 8 × 4 uniform mesh (no node under either contact zone), tol from 0.2 to 0.01, stopping
  on the bound (`stop_on="bound"`) and on the hierarchical estimate (`stop_on="hierarchical"`, the default;
  `"enriched"` is measured by study 13).

Error: the relative L2 error of λ_n against a converged reference of the same scene (`studylib.REFERENCE`: graded
toward [c − 0.1, c + 0.1] around the cylinder's centre c, h_min 0.0003125, growth 0.03, h_max 0.05; 175k
unknowns; halving h_min to 0.00015625 at growth 0.02, 466k unknowns, changes its λ_n by 0.05 %). The L2
error against the plane-strain Hertz pressure of the computed force is given beside it (`hertz_error`):
the reference itself is 0.38 % off Hertz (the finite block and the half-space model), so errors against
Hertz floor near 0.35 %. The adaptive rows also give the estimate the loop stopped on (`relative`) and
its effectivity (relative / error).

Effectivity over levels (centred Hertz): the adaptive loop stopped after 3, 4, 5, … 16 levels, each last
level against a finer reference (`FINE_REFERENCE`, 466k unknowns: at 68k adaptive unknowns the energy
error of the 175k one is no longer small against the level's): the relative energy estimate
η / (E* a(u_h, u_h))^½ against ‖u_ref − I u_h‖_K / ‖u_ref‖_K, and the traction estimate against the L2
error of λ_n; and the hierarchical estimate of the same answer (`solve(error_bars=True)`) against it too.

    python scripts/study_adaptive.py          # docs/adaptive.{md,csv,png}, adaptive_levels.csv, adaptive_{estimates,asked}.png
    python scripts/study_adaptive.py --smoke --out /tmp/x
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import studylib as sl  # noqa: E402

import tribo  # noqa: E402

CENTERS = (0.0, 0.3)
UNIFORM = [16, 32, 64, 128, 256]
GRADED = [0.04, 0.02, 0.01, 0.005, 0.0025, 0.00125]
GROWTHS = (0.3, 0.15)
TOLS = [0.2, 0.15, 0.1, 0.08, 0.06, 0.05, 0.04, 0.03, 0.02, 0.01]
TARGETS = (0.01, 0.003)
# The reference of the effectivity over levels: h_min halved, growth 0.02 (466k unknowns).
FINE_REFERENCE = dict(sl.REFERENCE, h_min=0.00015625, growth=0.02)
REPEATS = 2  # every wall time is the best of this many runs (the machine is shared)
LEVELS = list(range(3, 17))


def problem(mesh: tribo.Mesh, center: float) -> tribo.Problem:
    return tribo.Problem(mesh, young=sl.YOUNG, poisson=sl.POISSON, clamped="bottom", contact="top",
                         obstacle=tribo.Obstacle.circle(sl.RADIUS, center=center), approach=0.01)


def hertz_error(p: tribo.Problem, sol: tribo.Solution, center: float) -> float:
    """Relative L2 error of λ_n against Hertz centred at `center` (nan without contact)."""
    if sol.normal_force <= 0.0:
        return math.nan
    pressure, a, _ = sl.hertz_pressure(sol.normal_force)
    x, w = sl._gauss_points(np.concatenate([sl.contact_breaks(p), [center - a, center + a]]))
    lam, ref = p.evaluate_multiplier(sol.lambda_n, x), pressure(x - center)
    return float(np.sqrt(np.sum(w * (lam - ref) ** 2) / np.sum(w * ref**2)))


def reference(center: float, spec: dict[str, float]) -> sl.Reference:
    """The converged reference of the scene with the cylinder at `center`."""
    return sl.make_reference(problem(sl.reference_mesh(center, spec), center))


def run(smoke: bool, out: Path) -> list[dict[str, Any]]:
    uniform = [16, 32] if smoke else UNIFORM
    graded = [0.04, 0.02] if smoke else GRADED
    tols = [0.2, 0.1] if smoke else TOLS
    spec = sl.SMOKE_REFERENCE if smoke else sl.REFERENCE
    rows: list[dict[str, Any]] = []
    refs = {center: reference(center, spec) for center in CENTERS}
    for center in CENTERS:
        ref = refs[center]

        def errors(p: tribo.Problem, sol: tribo.Solution, ref: sl.Reference = ref, c: float = center) -> dict[str, float]:
            return dict(error=ref.lambda_n_error(p, sol) if sol.normal_force > 0.0 else math.nan,
                        hertz_error=hertz_error(p, sol, c))

        def fixed(family: str, h: float, make: Any) -> None:
            seconds = math.inf
            for _ in range(REPEATS):
                clock = time.perf_counter()
                p = problem(make(), center)
                sol = p.solve()
                seconds = min(seconds, time.perf_counter() - clock)
            rows.append(dict(center=center, family=family, h=h, tol=math.nan, n_free=p.n_free, q=p.n_multipliers,
                             levels=1, seconds=seconds, **errors(p, sol),
                             relative=sol.report.estimate["traction_relative"], stop=sol.report.status))

        for nx in uniform:
            fixed("uniform", 4.0 / nx, lambda nx=nx: sl.uniform_mesh(nx))
        for growth in GROWTHS:
            for h_min in graded:
                fixed(f"graded {growth}", h_min, lambda h=h_min, g=growth: sl.graded_mesh(h, growth=g))
        for family, stop_on in (("adaptive", "bound"), ("adaptive, hierarchical stop", "hierarchical")):
            for tol in tols:
                seconds = math.inf
                for _ in range(REPEATS):
                    clock = time.perf_counter()
                    p = problem(tribo.Mesh.rectangle(*sl.BOX, 8, 4), center)
                    a = p.solve_adaptive(tol=tol, stop_on=stop_on)
                    seconds = min(seconds, time.perf_counter() - clock)
                rows.append(dict(center=center, family=family, h=math.nan, tol=tol, n_free=a.problem.n_free,
                                 q=a.problem.n_multipliers, levels=len(a.levels), seconds=seconds,
                                 **errors(a.problem, a.solution), relative=a.levels[-1].relative, stop=a.stop))
    # Effectivity over levels (centred Hertz), against the finer reference: at 68k adaptive unknowns the
    # 175k one's own energy error is no longer small (effectivity 3.05 against it, 2.60 against this one).
    ref = refs[0.0] if smoke else reference(0.0, FINE_REFERENCE)
    for levels in ([2, 5] if smoke else LEVELS):
        start = problem(tribo.Mesh.rectangle(*sl.BOX, 8, 4), 0.0)
        a = start.solve_adaptive(tol=1e-9, max_levels=levels, stop_on="bound")
        est = a.solution.report.estimate
        # The hierarchical estimate of the same answer (the whole mesh bisected, as solve(error_bars=True)).
        sharp = a.problem.solve(error_bars=True).report.estimate["traction_hierarchical_relative"]
        rows.append(dict(center=0.0, family="levels", h=math.nan, tol=math.nan, n_free=a.problem.n_free,
                         q=a.problem.n_multipliers, levels=len(a.levels), seconds=sum(x.seconds for x in a.levels),
                         error=ref.lambda_n_error(a.problem, a.solution), hertz_error=math.nan,
                         relative=est["traction_relative"], hierarchical=sharp,
                         stop=a.stop, energy_estimate=est["energy_relative"],
                         energy_error=ref.energy_error(a.problem, a.solution),
                         in_contact=int(np.count_nonzero(np.asarray(a.solution.states) != 0))))
    write(rows, out)
    return rows


def cheapest(rows: list[dict[str, Any]], target: float) -> dict[str, Any] | None:
    """The run with the fewest unknowns whose error is at most `target`."""
    ok = [r for r in rows if r["error"] <= target]
    return min(ok, key=lambda r: r["n_free"]) if ok else None


def write(rows: list[dict[str, Any]], out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)
    keys = ["center", "family", "h", "tol", "n_free", "q", "levels", "seconds", "error", "hertz_error", "relative",
            "stop"]
    sl.write_csv(out / "adaptive.csv", keys, [[r[k] for k in keys] for r in rows])
    levels = [r for r in rows if r["family"] == "levels"]
    rows = [r for r in rows if r["family"] != "levels"]
    families = sorted({r["family"] for r in rows})
    md = ["# Study 6: accuracy without a guess\n\n",
          "Regenerate with `python scripts/study_adaptive.py`; every number is in `adaptive.csv`. "
          f"Wall times on the 2-core machine, all levels and assemblies included, each the best of {REPEATS} runs "
          "in one process (after the references are built).\n\n"]
    for target in TARGETS:
        md.append(f"## The cheapest run within {target:.1%} in λ_n (against the reference)\n\n")
        table = []
        for center in CENTERS:
            for fam in families:
                best = cheapest([r for r in rows if r["center"] == center and r["family"] == fam], target)
                table.append([center, fam] + ([best["n_free"], best["seconds"], best["error"], best["hertz_error"],
                                               best["levels"]] if best else ["not reached", math.nan, math.nan,
                                                                             math.nan, ""]))
        md.append(sl.markdown_table(["cylinder at", "mesh", "unknowns", "seconds", "λ_n error", "vs Hertz", "levels"],
                                    table))
        md.append("\n")
    md.append("## Adaptive runs\n\n")
    md.append("Stopping on the bound (`adaptive`: `stop_on=\"bound\"`) and on the hierarchical estimate (`adaptive, "
              "hierarchical stop`: `stop_on=\"hierarchical\"`, the default; `\"enriched\"` is measured by study 13); "
              "`adaptive_asked.png` charts the error reached and "
              "the time against the tolerance asked.\n\n")
    md.append(sl.markdown_table(
        ["cylinder at", "stop on", "tol", "stop", "levels", "unknowns", "multipliers", "seconds", "estimate",
         "true error", "true error / tol", "effectivity", "vs Hertz"],
        [[r["center"], "bound" if r["family"] == "adaptive" else "hierarchical", r["tol"], r["stop"], r["levels"],
          r["n_free"], r["q"], r["seconds"], r["relative"], r["error"], r["error"] / r["tol"],
          r["relative"] / r["error"] if r["error"] > 0 else math.nan, r["hertz_error"]]
         for r in rows if r["family"].startswith("adaptive")]))
    md.append("\n![error reached and time against the tolerance asked](adaptive_asked.png)\n")
    md.append("\n## Effectivity over levels (centred Hertz, against the finer reference of 466k unknowns)\n\n")
    eff_e = [r["energy_estimate"] / r["energy_error"] for r in levels]
    eff_t = [r["relative"] / r["error"] for r in levels]
    eff_h = [r["hierarchical"] / r["error"] for r in levels]
    md.append("The traction estimates: the bound (`traction_relative`, what the loop stops on with "
              "`stop_on=\"bound\"`) and the hierarchical estimate of the same answer (`solve(error_bars=True)`: "
              "1.5 times the change of λ when the whole mesh is bisected and the strip along the contact zone again; "
              "sharp but not a bound, see study 12).\n\n")
    md.append(sl.markdown_table(
        ["levels", "unknowns", "dofs in contact", "energy estimate", "energy error", "effectivity",
         "traction bound", "hierarchical", "λ_n error vs reference", "bound / error", "hierarchical / error"],
        [[r["levels"], r["n_free"], r["in_contact"], r["energy_estimate"], r["energy_error"], e, r["relative"],
          r["hierarchical"], r["error"], t, h] for r, e, t, h in zip(levels, eff_e, eff_t, eff_h)]))
    md.append(sl.effectivity_summary(eff_e, [r["in_contact"] for r in levels]))
    # The levels where something touches (before, the relative estimates have no reference: inf or nan).
    fe = [e for e, t in zip(eff_e, eff_t) if math.isfinite(e) and math.isfinite(t)]
    ft = [t for e, t in zip(eff_e, eff_t) if math.isfinite(e) and math.isfinite(t)]
    if fe:
        md.append(f"\nOver the {len(fe)} levels where something touches: traction effectivity from {min(ft):.3g} to "
                  f"{max(ft):.3g} (max/min {max(ft) / min(ft):.3g}).\n")
    counted = [h for h, r in zip(eff_h, levels) if r["in_contact"] >= 10 and math.isfinite(h)]
    if counted:
        inside = sum(1 for h in counted if 1.0 <= h <= 2.0)
        md.append(f"\nThe hierarchical estimate on the {len(counted)} levels with at least 10 multiplier dofs in "
                  f"contact: effectivity {min(counted):.3g} to {max(counted):.3g}, {inside} of them in [1, 2] "
                  "\n\n![the true error and both traction estimates over the levels](adaptive_estimates.png)\n")
    (out / "adaptive.md").write_text("".join(md))
    keys = ["levels", "n_free", "q", "in_contact", "seconds", "energy_estimate", "energy_error", "relative",
            "hierarchical", "error"]
    sl.write_csv(out / "adaptive_levels.csv", keys, [[r[k] for k in keys] for r in levels])

    plt = sl.pyplot()
    fig, axes = plt.subplots(2, 2, figsize=(12, 9))
    for col, center in enumerate(CENTERS):
        for fam in families:
            rs = sorted((r for r in rows if r["center"] == center and r["family"] == fam), key=lambda r: r["n_free"])
            mk = "o-" if fam.startswith("adaptive") else ".--"
            axes[0, col].loglog([r["n_free"] for r in rs], [r["error"] for r in rs], mk, label=fam)
            axes[1, col].loglog([r["seconds"] for r in rs], [r["error"] for r in rs], mk, label=fam)
        for row, xlabel in ((0, "unknowns"), (1, "wall time, all levels [s]")):
            ax = axes[row, col]
            for target in TARGETS:
                ax.axhline(target, color="0.5", lw=0.8, ls=":")
            ax.set_xlabel(xlabel)
            ax.set_ylabel("relative L2 error of λ_n vs the reference")
            ax.set_title(f"cylinder at x = {center}")
            ax.grid(True, which="both", alpha=0.3)
    axes[0, 0].legend(fontsize=8)
    fig.suptitle("Adaptive (from an 8 × 4 uniform mesh) against uniform and hand-graded meshes")
    fig.tight_layout()
    fig.savefig(out / "adaptive.png", dpi=85)
    plt.close(fig)

    # What a user gets for the tolerance asked: the error reached and the time, for both stops.
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    for center, marker in zip(CENTERS, "os"):
        for fam, style in (("adaptive", "--"), ("adaptive, hierarchical stop", "-")):
            rs = sorted((r for r in rows if r["center"] == center and r["family"] == fam), key=lambda r: r["tol"])
            stop = "bound" if fam == "adaptive" else "hierarchical"
            kw = dict(marker=marker, ls=style, label=f"x = {center}, stop on the {stop}")
            axes[0].loglog([r["tol"] for r in rs], [r["error"] for r in rs], **kw)  # type: ignore[arg-type]
            axes[1].loglog([r["tol"] for r in rs], [r["seconds"] for r in rs], **kw)  # type: ignore[arg-type]
    asked = [r["tol"] for r in rows if r["family"] == "adaptive"]
    span = np.array([min(asked), max(asked)])
    axes[0].fill_between(span, span / 3, span, color="0.85", label="[tol / 3, tol]")
    axes[0].set_ylabel("true relative L2 error of λ_n reached")
    axes[1].set_ylabel("wall time, all levels [s]")
    for ax in axes:
        ax.set_xlabel("tolerance asked (tol)")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.suptitle("Adaptive Hertz from the 8 × 4 mesh: what the tolerance asked gives")
    fig.tight_layout()
    fig.savefig(out / "adaptive_asked.png", dpi=85)
    plt.close(fig)

    # The true error and both traction estimates over the levels of one adaptive run.
    fig, ax = plt.subplots(figsize=(7.0, 4.5))
    n = [r["n_free"] for r in levels]
    ax.loglog(n, [r["error"] for r in levels], "ko-", label="true error of λ_n (466k reference)")
    ax.loglog(n, [r["relative"] for r in levels], "s--", label="the bound (traction_relative)")
    ax.loglog(n, [r["hierarchical"] for r in levels], "^-", label="hierarchical (sharp, not a bound)")
    ax.set_xlabel("unknowns")
    ax.set_ylabel("relative L2 error of the contact tractions")
    ax.set_title("Adaptive Hertz (centred): the error and its estimates, level by level")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "adaptive_estimates.png", dpi=85)
    plt.close(fig)


def main(argv: list[str] | None = None) -> list[dict[str, Any]]:
    return sl.cli(run, __doc__, argv)  # type: ignore[no-any-return]


if __name__ == "__main__":
    main()
