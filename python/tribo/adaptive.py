"""Adaptive solves: what ``tribo run`` writes for a scene with an ``[adapt]`` table.

``Problem.solve_adaptive`` (the core) solves, estimates, marks and bisects level by level; this module
writes, beside the last level's usual outputs (``summary.json``, the contact CSVs, ``result.vtu``, whose
mesh is the refined one):

* ``adapt.csv``: per level, the unknowns, multiplier dofs and triangles, the relative estimate the loop
  stops on (of the contact tractions, or of the energy while nothing touches), the estimate η with its
  bulk, Γ_C, contact and friction parts, the traction bound and (where the loop computed it, unless
  ``stop_on = "bound"``) the hierarchical traction estimate (on an enriched answer handed back, the last level,
  ``enriched`` and with 0 seconds, ½‖λ_H − λ_f‖: that answer's own) and on the level after it the calibrated
  bound, the level's seconds, status and ``enriched``;
* ``adapt.png`` (``tribo run --plots``): the relative estimate, the bound and the hierarchical estimate,
  and η against the unknowns (log-log), with the tolerance;
* ``levels/level_NNN.vtu`` and ``adapt.pvd`` (``write_levels``, only with the scene's ``[adapt]
  write_levels = true``: the loop keeps no level's solution but the last, so each level before it is solved
  again, to full tolerance, for a history the whole history with its last step written; it costs about what
  the loop did): every level's mesh and solution, a series ParaView steps through.
"""

from __future__ import annotations

import csv
import logging
from pathlib import Path
from typing import Any

import numpy as np

from tribo.history import write_pvd
from tribo.io import write_vtu
from tribo.results import Adaptive, AdaptiveHistory

__all__ = ["adapt_table", "handed_back", "write_adaptive", "write_levels"]

log = logging.getLogger("tribo")


def adapt_table(adaptive: Adaptive | AdaptiveHistory) -> dict[str, list[Any]]:
    """The per-level columns of ``adapt.csv``."""
    lv = adaptive.levels
    table: dict[str, list[Any]] = {
        "level": list(range(len(lv))),
        "unknowns": [x.unknowns for x in lv],
        "multipliers": [x.multipliers for x in lv],
        "triangles": [x.triangles for x in lv],
        "relative": [x.relative for x in lv],
    }
    for key in ("total", "bulk", "gamma_c", "contact", "friction", "traction_relative", "energy_relative",
                "traction_hierarchical_relative", "traction_calibrated_relative"):
        table[f"estimate_{key}"] = [x.estimate[key] for x in lv]
    table["seconds"] = [x.seconds for x in lv]
    table["status"] = [x.status for x in lv]
    table["enriched"] = [x.enriched for x in lv]
    return table


def handed_back(adaptive: Adaptive | AdaptiveHistory) -> bool:
    """Whether the loop handed back the answer enriched for the last estimated level (``stop_on='enriched'``): the
    last level is ``enriched``. Its hierarchical estimate is then ½‖λ_H − λ_f‖, half its change from
    the level it enriched."""
    return adaptive.levels[-1].enriched


def write_levels(out: str | Path, adaptive: Adaptive | AdaptiveHistory, **solve: Any) -> list[Path]:
    """Solves every level's problem but the last again (``solve`` keywords, to their full tolerances; the last is
    the answer handed back, as it is) and writes the series ``levels/level_NNN.vtu`` (+ ``_contact``,
    ``_multipliers``) with ``adapt.pvd`` (and ``adapt_contact.pvd``, ``adapt_multipliers.pvd``): ParaView steps
    through the refinement, the level as the time (two bodies in one mesh, cell data ``body``). For an adaptive
    history, each level solves the whole history again (its steps are ``adaptive.history``'s) and writes its last
    converged step (the failed one if none converged; a level with neither is left out of the series, with a log
    line)."""
    out = Path(out)
    (out / "levels").mkdir(parents=True, exist_ok=True)
    series: list[list[Path]] = [[], [], []]
    levels: list[int] = []
    last = len(adaptive.levels) - 1
    for k in range(len(adaptive.levels)):
        problem = adaptive.problem if k == last else adaptive.level_problem(k)
        if isinstance(adaptive, AdaptiveHistory):
            h = adaptive.history
            history = h if k == last else problem.solve_history(
                h.approach, h.shift, h.load_factor, displacements=h.displacements or None, rotation=h.rotation, **solve)
            solution = history.solutions[-1] if len(history) else history.failed
            if solution is None:
                log.info("level %d: the history's first step ended with status '%s'; not written", k, history.status)
                continue
        else:
            solution = adaptive.solution if k == last else problem.solve(**solve)
        # Two bodies: the joined mesh, whose cell data 'body' tells them apart (as a history's series).
        paths = write_vtu(out / "levels" / f"level_{k:03d}.vtu", problem, solution, per_body=False)
        for part, p in zip(series, paths, strict=True):
            part.append(p)
        levels.append(k)
    files = [p for part in series for p in part]
    for name, part in zip(("adapt", "adapt_contact", "adapt_multipliers"), series, strict=True):
        files.append(write_pvd(out / f"{name}.pvd", part, levels))
    return files


def write_adaptive(
    out: str | Path, adaptive: Adaptive | AdaptiveHistory, *, tol: float | None = None, plots: bool = True
) -> list[Path]:
    """Writes ``adapt.csv`` and (``plots``, matplotlib installed) ``adapt.png`` into ``out``."""
    out = Path(out)
    table = adapt_table(adaptive)
    path = out / "adapt.csv"
    with path.open("w", newline="", encoding="utf-8") as f:
        f.write(f"# stop: {adaptive.stop}; relative: the traction estimate, or the energy one while nothing touches\n")
        w = csv.writer(f)
        w.writerow(table)
        w.writerows(zip(*table.values(), strict=True))
    files = [path]
    if plots:
        try:
            import matplotlib

            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError:
            return files
        fig, ax = plt.subplots(figsize=(6, 4))
        n = np.array(table["unknowns"], dtype=float)
        rel = np.array(table["relative"], dtype=float)
        ok = np.isfinite(rel)
        ax.loglog(n[ok], rel[ok], "o-", label="relative estimate (tractions, or energy)")
        sharp = np.array(table["estimate_traction_hierarchical_relative"], dtype=float)
        if np.any(np.isfinite(sharp)):
            bound = np.array(table["estimate_traction_relative"], dtype=float)
            ax.loglog(n, bound, "^:", ms=4, label="traction bound")
            ax.loglog(n, sharp, "D", ms=5, label="traction, hierarchical")
        eta = np.array(table["estimate_total"], dtype=float)
        if np.any(eta > 0):
            ax.loglog(n, eta / eta[eta > 0][0] * (rel[ok][0] if np.any(ok) else 1.0), "s--", ms=3,
                      label="η (scaled to the first)")
        if tol is not None:
            ax.axhline(tol, color="k", lw=0.8, ls=":", label=f"tol = {tol:g}")
        ax.set_xlabel("unknowns")
        ax.set_ylabel("estimated error")
        ax.set_title(f"adaptive levels (stop: {adaptive.stop})")
        ax.legend(fontsize=8)
        fig.tight_layout()
        path = out / "adapt.png"
        fig.savefig(path, dpi=120)
        plt.close(fig)
        files.append(path)
    return files
