"""Study 6b — adaptive refinement of a loading history: Cattaneo–Mindlin from a coarse mesh.

The Hertz cylinder (R = 1, E = 200, ν = 0.45, centred) is pressed δ = 0.01 into the block, then dragged
to s = 0.0045 in `STEPS` steps (Coulomb μ = 0.3), as in study 5. Every point is one run, wall clock, all
levels and assemblies included:

* graded: study 5's meshes (growth 0.3 toward [−0.3, 0.3]), h_min from 0.02 to 0.0025, one history each;
* adaptive: `Problem.solve_history_adaptive` from the 8 × 4 uniform mesh (no node under the contact
  zone), marked on every step, tol from 0.4 down.

Measured: the largest error of the stick half-width c/a over the steps with 0.1 ≤ Q/μP ≤ 0.9 against
Cattaneo–Mindlin's √(1 − Q/μP) (`study_cattaneo_mindlin.stick_ratio`; at ν = 0.45 it settles near 0.06,
the coupling of normal and tangential response, β = 0.091, study 5) and against the c/a of the same
history on the fine reference mesh (`REFERENCE`: the discretization error alone), the unknowns and the
seconds.

Effectivity over levels: the adaptive loop stopped after `LEVELS` levels; the relative energy estimate of
the last step against ‖u_ref − I u_h‖_K / ‖u_ref‖_K, u_ref the last step of the same history on a fine
graded mesh (`REFERENCE`: h_min 0.000625, growth 0.075, h_max 0.05, so that its grading bias is a fifth of
that of the growth-0.3 family). The summary is over the levels whose last step holds at least
`tribo.checks.MIN_CONTACT_DOFS` multiplier dofs in contact, the count below which every solve warns that
the contact zone is barely resolved (the table lists every level, with that count).

    python scripts/study_adaptive_history.py          # docs/adaptive_history.{md,csv,png}
    python scripts/study_adaptive_history.py --smoke --out /tmp/x
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import study_cattaneo_mindlin as cm  # noqa: E402
import studylib as sl  # noqa: E402

import tribo  # noqa: E402

NU = 0.45
STEPS = 10
GRADED = [0.02, 0.01, 0.005, 0.0025]
TOLS = [0.4, 0.3, 0.2, 0.15, 0.1, 0.07]
LEVELS = list(range(5, 16))
REFERENCE = dict(h_min=0.000625, h_max=0.05, growth=0.075)


def problem(mesh: tribo.Mesh) -> tribo.Problem:
    return sl.hertz_problem(mesh, approach=cm.APPROACH, poisson=NU)


def in_contact(sol: tribo.Solution) -> int:
    """The multiplier dofs in contact (sticking or slipping)."""
    return int(np.count_nonzero(np.asarray(sol.states) != 0))


def shifts(steps: int) -> np.ndarray:
    return np.linspace(0.0, cm.S_MAX, steps + 1)


def run(smoke: bool, out: Path) -> list[dict[str, Any]]:
    steps = 4 if smoke else STEPS
    s = shifts(steps)
    spec = dict(h_min=0.005, h_max=0.1, growth=0.3) if smoke else REFERENCE
    ref_problem = problem(sl.graded_mesh(spec["h_min"], h_max=spec["h_max"], growth=spec["growth"]))
    ref_history = ref_problem.solve_history(cm.APPROACH, s, mu=cm.MU)
    last = ref_history.solutions[-1]
    ref = sl.Reference(ref_problem, last, ref_problem.energy_norm(last.displacement))
    ref_r, ref_ca, _ = cm.stick_ratio(ref_history)
    keep = (ref_r >= 0.1) & (ref_r <= 0.9)

    def against_reference(h: tribo.History) -> float:
        """The largest |c/a − c/a of the reference| over the steps with 0.1 ≤ Q/μP ≤ 0.9 (the reference's)."""
        return float(np.max(np.abs(cm.stick_ratio(h)[1][keep] - ref_ca[keep])))

    rows: list[dict[str, Any]] = []
    for h_min in GRADED[:2] if smoke else GRADED:
        clock = time.perf_counter()
        p = problem(sl.graded_mesh(h_min))
        h = p.solve_history(cm.APPROACH, s, mu=cm.MU)
        seconds = time.perf_counter() - clock
        rows.append(dict(family="graded", h_min=h_min, tol=math.nan, n_free=p.n_free, q=p.n_multipliers, levels=1,
                         seconds=seconds, ca_error=cm.stick_ratio(h)[2], ca_ref=against_reference(h), relative=math.nan,
                         status=h.status))
    start = tribo.Mesh.rectangle(*sl.BOX, 8, 4)
    for tol in TOLS[:2] if smoke else TOLS:
        clock = time.perf_counter()
        a = problem(start).solve_history_adaptive(cm.APPROACH, s, mu=cm.MU, tol=tol, stop_on="bound")
        seconds = time.perf_counter() - clock
        rows.append(dict(family="adaptive", h_min=math.nan, tol=tol, n_free=a.problem.n_free,
                         q=a.problem.n_multipliers, levels=len(a.levels), seconds=seconds,
                         ca_error=cm.stick_ratio(a.history)[2], ca_ref=against_reference(a.history),
                         relative=a.levels[-1].relative, status=a.stop))
    for levels in [4, 6] if smoke else LEVELS:
        a = problem(start).solve_history_adaptive(cm.APPROACH, s, mu=cm.MU, tol=1e-9, max_levels=levels,
                                                 stop_on="bound")
        sol = a.history.solutions[-1]
        rows.append(dict(family="levels", h_min=math.nan, tol=math.nan, n_free=a.problem.n_free,
                         q=a.problem.n_multipliers, levels=len(a.levels), seconds=sum(x.seconds for x in a.levels),
                         ca_error=cm.stick_ratio(a.history)[2], ca_ref=against_reference(a.history),
                         relative=a.levels[-1].relative, status=a.stop, energy_estimate=sol.report.estimate["energy_relative"],
                         energy_error=ref.energy_error(a.problem, sol), in_contact=in_contact(sol)))
    write(rows, out)
    return rows


def write(rows: list[dict[str, Any]], out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)
    keys = ["family", "h_min", "tol", "n_free", "q", "levels", "seconds", "ca_error", "ca_ref", "relative", "status"]
    extra = ["energy_estimate", "energy_error", "in_contact"]
    sl.write_csv(out / "adaptive_history.csv", keys + extra,
                 [[r[k] for k in keys] + [r.get(k, math.nan) for k in extra] for r in rows])
    runs = [r for r in rows if r["family"] != "levels"]
    levels = [r for r in rows if r["family"] == "levels"]
    md = ["# Study 6b: an adaptive loading history (Cattaneo–Mindlin)\n\n",
          "Regenerate with `python scripts/study_adaptive_history.py`; every number is in "
          "`adaptive_history.csv`. Wall times on the 2-core machine, all levels included.\n\n",
          "## The stick zone against the unknowns\n\n"]
    md.append(sl.markdown_table(
        ["mesh", "h_min", "tol", "unknowns", "multipliers", "levels", "seconds", "c/a vs CM", "c/a vs reference",
         "estimate", "status"],
        [[r["family"], r["h_min"], r["tol"], r["n_free"], r["q"], r["levels"], r["seconds"], r["ca_error"],
          r["ca_ref"], r["relative"], r["status"]] for r in runs]))
    md.append("\n## Effectivity over levels (the last step, against the fine reference)\n\n")
    eff = [r["energy_estimate"] / r["energy_error"] for r in levels]
    md.append(sl.markdown_table(
        ["levels", "unknowns", "dofs in contact", "energy estimate", "energy error", "effectivity", "c/a error"],
        [[r["levels"], r["n_free"], r["in_contact"], r["energy_estimate"], r["energy_error"], e, r["ca_error"]]
         for r, e in zip(levels, eff)]))
    md.append(sl.effectivity_summary(eff, [r["in_contact"] for r in levels]))
    (out / "adaptive_history.md").write_text("".join(md))

    plt = sl.pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    for fam, mk in (("graded", "s--"), ("adaptive", "o-")):
        rs = sorted((r for r in runs if r["family"] == fam), key=lambda r: r["n_free"])
        axes[0].loglog([r["n_free"] for r in rs], [r["ca_error"] for r in rs], mk, label=f"{fam}, vs Cattaneo–Mindlin")
        axes[0].loglog([r["n_free"] for r in rs], [r["ca_ref"] for r in rs], mk, alpha=0.5, label=f"{fam}, vs reference")
        axes[1].loglog([r["seconds"] for r in rs], [r["ca_error"] for r in rs], mk, label=f"{fam}, vs Cattaneo–Mindlin")
        axes[1].loglog([r["seconds"] for r in rs], [r["ca_ref"] for r in rs], mk, alpha=0.5, label=f"{fam}, vs reference")
    for ax, xlabel in zip(axes, ("unknowns", "wall time, all levels [s]")):
        ax.set_xlabel(xlabel)
        ax.set_ylabel("largest c/a error, 0.1 ≤ Q/μP ≤ 0.9")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.suptitle(f"Cattaneo–Mindlin (ν = {NU}): graded meshes against adaptive histories from an 8 × 4 mesh")
    fig.tight_layout()
    fig.savefig(out / "adaptive_history.png", dpi=85)
    plt.close(fig)


def main(argv: list[str] | None = None) -> list[dict[str, Any]]:
    return sl.cli(run, __doc__, argv)  # type: ignore[no-any-return]


if __name__ == "__main__":
    main()
