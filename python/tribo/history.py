"""Loading histories: what ``tribo run`` writes for a scene with a ``[history]`` table.

``Problem.solve_history`` (the core) solves the quasi-static steps on one factorization; this module
writes its results:

* ``steps/step_NNNN.vtu`` (+ ``_contact``, ``_multipliers``) per converged step (beyond ``MAX_VTU_STEPS`` = 200
  steps, every k-th step and the last, k the smallest that keeps them within 200; ``[history]
  write_every`` chooses k), and ``result.pvd``, ``result_contact.pvd``, ``result_multipliers.pvd``:
  collections ParaView opens as time series (the "time" is the step number);
* ``history.csv``: per step, the obstacle's approach and shift, the load factor, its angle (``angle``, where a
  step turns it), the prescribed
  displacement components the history moves (one column each, named 'set.x'/'set.y'), the normal and
  tangential contact forces, the stick/slip/separation counts, the extents of the contact and stick
  zones, and the step's error estimate η, relative traction estimate (the bound) and hierarchical estimate
  (``traction_error_hierarchical``, NaN where the adaptive loop did not compute it) and calibrated bound
  (``traction_error_calibrated``, NaN where it did not form it); with several contact pairs
  the forces and counts are totals, the zones the first pair's, and each pair has its own columns
  ``pair.normal_force``, ``pair.tangential_force``, ``pair.contact_from`` … ``pair.gross_sliding`` (``pair`` its
  edge set);
* with ``tribo run --plots``, ``history_loop.png``: the tangential force Q against the obstacle's
  tangential position s (for a fretting cycle, the hysteresis loop), and ``history_tractions.png``: λ_t
  against ±μλ_n at chosen steps (the first pair's, with several contact pairs: the one the steps move).

Conventions: s is the obstacle's position along the tangent t = (−n₂, n₁) of Γ_C (n the outward normal, or the
obstacle's where it is given by its geometry),
Q = ∫λ_t is the tangential force along t, and abscissae run as ``tribo.checks.abscissa_description`` says
(written into the CSV header and the plot).
"""

from __future__ import annotations

import csv
import logging
import math
import os
from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any
from xml.sax.saxutils import quoteattr

import numpy as np

from tribo.checks import abscissa_description
from tribo.io import write_vtu
from tribo.problem import Problem
from tribo.results import History

__all__ = ["MAX_VTU_STEPS", "history_table", "vtu_steps", "write_history", "write_pvd"]

# The most steps whose VTU files a history writes unless told otherwise (three files per step).
MAX_VTU_STEPS = 200
# The most threads writing a history's step files at once (never more than the cores).
WRITERS = 8

log = logging.getLogger("tribo")


def write_pvd(path: str | Path, files: Sequence[Path], times: Sequence[float]) -> Path:
    """A ParaView collection (``.pvd``) of ``files`` at ``times`` (paths relative to the collection)."""
    path = Path(path)
    rows = "\n".join(
        f'    <DataSet timestep="{t!r}" part="0" file={quoteattr(f.relative_to(path.parent).as_posix())}/>'
        for f, t in zip(files, times, strict=True)
    )
    path.write_text(
        '<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n  <Collection>\n'
        f"{rows}\n  </Collection>\n</VTKFile>\n",
        encoding="utf-8",
    )
    return path


def history_table(history: History) -> dict[str, np.ndarray]:
    """The per-step columns of ``history.csv`` (converged steps only; ``angle`` where a step turns the obstacle)."""
    k = len(history)
    contact, stick = history.contact_zone, history.stick_zone
    return {
        "step": np.arange(k),
        "approach": history.approach[:k],
        "shift": history.shift[:k],
        "load_factor": history.load_factor[:k],
        **({"angle": history.rotation[:k]} if not np.isnan(history.rotation).all() else {}),
        **{name: values[:k] for name, values in history.displacements.items()},
        "normal_force": history.normal_force,
        "tangential_force": history.tangential_force,
        "stick": history.stick_count,
        "slip": history.slip_count,
        "separation": history.separation_count,
        "contact_from": contact[:, 0],
        "contact_to": contact[:, 1],
        "stick_from": stick[:, 0],
        "stick_to": stick[:, 1],
        "gross_sliding": history.gross_sliding.astype(int),
        "error_estimate": history.error_estimate,
        "traction_error": history.traction_error,
        "traction_error_hierarchical": history.traction_error_hierarchical,
        "traction_error_calibrated": history.traction_error_calibrated,
        **(_pair_columns(history) if len(history.pairs) > 1 else {}),
    }


def _pair_columns(history: History) -> dict[str, np.ndarray]:
    """Each pair's forces, zones and gross sliding, its columns named 'pair.column' (several pairs)."""
    columns: dict[str, np.ndarray] = {}
    for name, series in history.pairs.items():
        contact, stick = series["contact_zone"], series["stick_zone"]
        for column, values in (("normal_force", series["normal_force"]), ("tangential_force", series["tangential_force"]),
                               ("contact_from", contact[:, 0]), ("contact_to", contact[:, 1]),
                               ("stick_from", stick[:, 0]), ("stick_to", stick[:, 1]),
                               ("gross_sliding", series["gross_sliding"].astype(int))):
            columns[f"{name}.{column}"] = values
    return columns


def vtu_every(n: int, every: int | None = None) -> int:
    """Every how many steps a history of ``n`` steps writes its VTU files: ``every`` if given; by default 1 up
    to ``MAX_VTU_STEPS`` steps, beyond that the smallest k that keeps the count within it (each step writes
    three files)."""
    return every if every is not None else max(1, math.ceil(n / MAX_VTU_STEPS))


def vtu_steps(n: int, every: int | None = None) -> list[int]:
    """The steps of a history of ``n`` converged steps whose VTU files are written: every ``vtu_every``-th
    step and the last one (the steps a history with ``keep_every`` set to that keeps)."""
    if n == 0:
        return []
    return sorted(set(range(0, n, vtu_every(n, every))) | {n - 1})


def write_history(out: str | Path, problem: Problem, history: History, *, plots: bool = True,
                  plot_steps: Sequence[int] | None = None, every: int | None = None) -> list[Path]:
    """Writes the VTU series of the steps ``vtu_steps`` chooses (``every``: every k-th step and the last)
    with its ``.pvd`` collections, ``history.csv`` (every step) and (``plots``) the charts."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    series: list[list[Path]] = [[], [], []]
    kept = set(history.kept.tolist())
    steps = [k for k in vtu_steps(len(history), every) if k in kept]
    if len(steps) < len(history):
        log.info("writing the VTU files of %d of the %d steps (every %s-th and the last, of those kept)", len(steps),
                 len(history), vtu_every(len(history), every))
    if steps:
        (out / "steps").mkdir(exist_ok=True)

    def write(k: int) -> list[Path]:
        return write_vtu(out / "steps" / f"step_{k:04d}.vtu", problem, history.solution(k), per_body=False)

    # A step's files are mostly zlib compression, which releases the GIL: the steps are written side by side,
    # on the cores this process may use. After an error (or Ctrl-C) the steps not begun are not written:
    # `map` cancels them when its iterator is left.
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    with ThreadPoolExecutor(max_workers=min(WRITERS, cores)) as pool:
        for vtu in pool.map(write, steps):
            for part, p in zip(series, vtu, strict=True):
                part.append(p)
    files = [p for part in series for p in part]
    for name, part in zip(("result", "result_contact", "result_multipliers"), series, strict=True):
        files.append(write_pvd(out / f"{name}.pvd", part, steps))
    table = history_table(history)
    path = out / "history.csv"
    with path.open("w", newline="", encoding="utf-8") as f:
        f.write(
            "# s (shift): obstacle position along t = (-n2, n1); angle: its turn about its rotation's centre (rad); "
            "tangential_force = ∫λ_t along t; "
            + ("a further pair's zones are on its own side; " if len(history.pairs) > 1 else "")
            + f"zones are positions on Γ_C as the {abscissa_description(problem)}\n"
        )
        w = csv.writer(f)
        w.writerow(table)
        w.writerows(zip(*(v.tolist() for v in table.values()), strict=True))
    files.append(path)
    if plots:
        files += _plots(out, problem, history, plot_steps)
    return files


def _plots(out: Path, problem: Problem, history: History, plot_steps: Sequence[int] | None) -> list[Path]:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        log.warning("matplotlib is not installed: no plots (pip install 'tribo[plot]')")
        return []
    k = len(history)
    if k == 0:
        return []
    kept = history.kept.tolist()
    middle = min(kept, key=lambda s: abs(s - k // 2))
    steps = [s for s in (plot_steps if plot_steps is not None else sorted({kept[0], middle, kept[-1]})) if s in kept]
    if plot_steps is not None and len(steps) < len(plot_steps):
        log.warning("plot_steps: steps %s did not converge or were not kept", sorted(set(plot_steps) - set(steps)))
    from tribo import plot

    files = []
    draws: tuple[tuple[str, Callable[[Any], Any]], ...] = (
        ("history_loop.png", lambda ax: plot.history_loop(history, ax)),
        ("history_tractions.png", lambda ax: plot.history_tractions(history, steps, ax, problem=problem)),
    )
    for name, draw in draws:
        fig, ax = plt.subplots(figsize=(7.0, 4.0), layout="constrained")
        draw(ax)
        fig.savefig(out / name, dpi=120)
        plt.close(fig)
        files.append(out / name)
    return files
