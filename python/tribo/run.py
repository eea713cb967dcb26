"""Running a scene and writing its files: what ``tribo run`` does (``tribo.cli`` prints it) and what every case
of a sweep runs (``tribo.sweep``, on a Dask worker). ``run_scene`` solves a scene (one step, a ``[history]`` or
an ``[adapt]`` loop) and writes ``summary.json`` and, unless ``fields=False``, the contact CSVs, the VTU files,
the history's or the levels' outputs and the plots; the files are listed in ``tribo.cli``.
"""

from __future__ import annotations

import importlib
import json
import logging
import math
import sys
import threading
import time
import warnings
from collections.abc import Sequence
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

import numpy as np

from tribo._tribo import __version__
from tribo.adaptive import handed_back, write_adaptive, write_levels
from tribo.checks import SceneWarning, conventions, warn_missing_error_bars, warn_solution
from tribo.history import vtu_every, write_history
from tribo.io import write_contact_csv, write_text_atomic, write_vtu
from tribo.problem import Problem
from tribo.results import Adaptive, AdaptiveHistory, History, Solution, dof_span
from tribo.scene import Scene, SceneError

__all__ = ["peak_memory_mb", "run_adaptive", "run_history", "run_scene", "summary"]

log = logging.getLogger("tribo")


def _progress(iteration: int, change: float, qp_iterations: int, qp_seconds: float) -> None:
    if math.isnan(change):
        log.info("initial QP: %d interior-point iterations, %.3f s", qp_iterations, qp_seconds)
    else:
        log.info(
            "fixed point %3d: change of λ_n %.3e, QP %d iterations in %.3f s",
            iteration,
            change,
            qp_iterations,
            qp_seconds,
        )


def _phase(phase: str, seconds: float) -> None:
    log.info("%s: %.3f s (factorization of K − G, and H where formed at once)", phase, seconds)


def peak_memory_mb() -> float | None:
    """The peak resident memory of this process so far, in MiB: Linux's high-water mark ``VmHWM`` of
    ``/proc/self/status`` (``getrusage``'s ``ru_maxrss`` is not used there: it keeps the parent's peak
    across ``exec``, so a run started from a large process would report that process's), else
    ``ru_maxrss`` (bytes on macOS); ``None`` where neither exists (Windows). In a sweep worker it covers
    every case the worker ran."""
    try:
        with open("/proc/self/status", encoding="ascii") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024.0
    except (OSError, ValueError, IndexError):
        pass
    try:
        import resource
    except ImportError:
        return None
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return peak / 1048576.0 if sys.platform == "darwin" else peak / 1024.0



def _rotation(problem: Problem) -> dict[str, Any] | None:
    """The obstacle's rotation as given (``rotation=((cx, cy), angle)``), for summary.json; None when it does not
    turn."""
    given = getattr(problem, "_arguments", {}).get("rotation")
    return None if given is None else {"center": [float(v) for v in given[0]], "angle": float(given[1])}

def summary(
    scene: Scene, problem: Problem, solution: Solution, seconds: float, warned: Sequence[str] = (),
    adapt_stop: str | None = None, adapt_handed_back: bool | None = None,
) -> dict[str, Any]:
    """The JSON summary of a run; ``adapt_stop``: why an adaptive loop stopped (None without ``[adapt]``), and
    ``adapt_handed_back`` whether it handed back an enriched answer (``tribo.adaptive.handed_back``)."""
    r = solution.report
    states = solution.state_names
    return {
        "tribo_version": __version__,
        "scene": scene.to_dict(),
        "status": r.status,
        "adapt_stop": adapt_stop,
        "adapt_handed_back": adapt_handed_back,
        "failure": {"iteration": r.failed_iteration, "reason": r.failure_reason} if r.status == "qp_failed" else None,
        "friction": solution.friction,
        "mu": solution.mu,
        "iterations": r.iterations,
        "coulomb_method": r.coulomb_method,
        "coulomb_fallback": r.coulomb_fallback,
        "coulomb_check": None if r.coulomb_check is None else {
            "agreement": r.coulomb_check, "status": r.check_status,
            **{k: v if v is not None and math.isfinite(v) else None  # strict JSON: NaN and inf as null
               for k, v in (("distance", r.check_distance), ("allowed", r.check_allowed))}},
        "residual_history": r.residual_history.tolist(),
        "qp_iterations": r.qp_iterations.tolist(),
        "qp_factorizations": r.qp_factorizations.tolist(),
        "qp_methods": {m: r.qp_methods.count(m) for m in ("clarabel", "active_set")},
        "qp_fallbacks": r.qp_fallbacks,
        "condensation": r.condensation,
        "qp_inaccurate": r.qp_inaccurate,
        "gamma0": r.gamma0,
        "gamma0_bound": r.gamma0_bound,
        "mesh": {"nodes": problem.mesh.n_nodes, "triangles": problem.mesh.n_triangles, "h": problem.mesh.max_diameter},
        "n_free": problem.n_free,
        "n_multipliers": problem.n_multipliers,
        "space": problem.space,
        "model": problem.model,
        "formulation": problem.formulation,
        "normal_force": solution.normal_force,
        "tangential_force": solution.tangential_force,
        "contact_force": list(solution.contact_force),
        "obstacle_motion": list(solution.obstacle_motion),
        "obstacle_rotation": _rotation(problem),
        "normal": [v + 0.0 for v in problem.contact_normal],
        "tangent": [v + 0.0 for v in problem.contact_tangent],
        "max_penetration": solution.max_penetration,
        "contact_width": solution.contact_width,
        "stick_width": solution.stick_width,
        "pairs": [{"name": r.name, "normal_force": r.normal_force, "tangential_force": r.tangential_force,
                   "contact_force": list(r.contact_force), "contact_width": r.contact_width,
                   "stick_width": r.stick_width, "mu": r.mu} for r in solution.pairs],
        "states": {name: states.count(name) for name in ("separation", "stick", "slip")},
        "kkt": solution.kkt,
        "kkt_max": solution.kkt_max,
        "timings": r.timings,
        # The a posteriori estimate; a relative one that has no reference (nothing touches, no energy) is null.
        "estimate": {k: (v if math.isfinite(v) else None) for k, v in r.estimate.items()},
        "bodies": bodies(problem, solution),
        "materials": materials(problem, solution),
        "wall_seconds": seconds,
        "process_peak_memory_mb": peak_memory_mb(),
        "warnings": list(warned),
        "conventions": conventions(problem, solution),
    }


def materials(problem: Problem, solution: Solution) -> list[dict[str, Any]]:
    """Per material (``problem.materials``, by region): E, ν, its triangles and their area, the largest von
    Mises stress of its triangles, and its part of the estimates, ``sqrt(Σ η_K²)`` and ``sqrt(Σ ζ_K²)`` over its
    triangles (the squares of all materials add up to the totals): where a coating or a substrate holds the
    largest stress, and where the error is."""
    regions = np.asarray(problem.regions)
    p = np.asarray(problem.mesh.points)[np.asarray(problem.mesh.triangles)]
    area = 0.5 * np.abs((p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1])
                        - (p[:, 2, 0] - p[:, 0, 0]) * (p[:, 1, 1] - p[:, 0, 1]))
    eta, zeta, von_mises = (np.asarray(v) for v in (solution.estimator, solution.traction_estimator,
                                                     solution.von_mises))
    def norm(v: np.ndarray) -> float:
        """The 2-norm, scaled by the largest value: η_K of 1e200 (E of 1e300) square beyond a float."""
        top = float(np.max(np.abs(v), initial=0.0))
        return top * float(np.sqrt(np.sum((v / top) ** 2))) if 0.0 < top < math.inf else top

    out = []
    for k, (young, poisson) in enumerate(problem.materials):
        mine = regions == k
        out.append({"young": young, "poisson": poisson, "triangles": int(mine.sum()), "area": float(area[mine].sum()),
                    "max_von_mises": float(np.max(von_mises[mine], initial=0.0)),
                    "estimate": norm(eta[mine]), "traction_estimate": norm(zeta[mine])})
    return out


def bodies(problem: Problem, solution: Solution) -> list[dict[str, Any]]:
    """Per body: its name, nodes, triangles and unknowns, and the total reaction of its supports (Rx, Ry),
    which balances the contact force it takes and its loads (in axisymmetry the resultant on the whole turn, Rx 0:
    the nodes' radial ring forces cancel over the turn)."""
    out = []
    for name, (n0, n1, t0, t1), unknowns in problem.bodies:
        rx, ry = (float(v) for v in solution.reactions[n0:n1].sum(axis=0))
        rx = 0.0 if problem.model == "axisymmetric" else rx
        out.append({"name": name, "nodes": n1 - n0, "triangles": t1 - t0, "unknowns": unknowns, "reaction": [rx, ry]})
    return out


def run_history(
    scene: Scene, problem: Problem, *, fields: bool = True, every: int | None = None
) -> tuple[Problem, History, AdaptiveHistory | None]:
    """Solves the scene's ``[history]`` with a progress bar over the steps; with an ``[adapt]`` table,
    adaptively (a log line per level, then the history on the last mesh). Returns the problem the history
    was solved on, the history and the adaptive run (None without ``[adapt]``); the caller writes their files
    (``write_history``, ``write_adaptive``) once the solve is timed. ``fields=False`` keeps the last
    solution only (no step files will be written); ``every``: the steps whose files will be written (every k-th
    and the last; by default the scene's ``[history] write_every``, else ``tribo.history.vtu_every``'s)."""
    from tqdm import tqdm

    n_steps = len(scene.history_steps()[0])
    clock = time.perf_counter()
    adaptive: AdaptiveHistory | None = None
    if scene.has_adapt:
        adaptive = scene.solve_history_adaptive(problem, progress=_level_progress)
        log.info("adaptive history stopped (%s) after %d levels", adaptive.stop, len(adaptive.levels))
        warn_adapt_stop(scene, adaptive)
        problem, history = adaptive.problem, adaptive.history
    else:
        with tqdm(total=n_steps, desc="steps", unit="step", disable=not log.isEnabledFor(logging.INFO)) as bar:

            def progress(step: int, steps: int, status: str, seconds: float) -> None:
                bar.update(1)
                bar.set_postfix_str(status)

            # Only the solutions whose VTU files are written are kept (every step's forces and states are).
            keep = vtu_every(n_steps, every or scene.get("history", "write_every")) if fields else max(n_steps, 1)
            problem, history = scene.solve_history(problem, progress=progress, keep_every=keep)
    seconds = time.perf_counter() - clock
    log.info("history ended: %s after %d of %d steps, %.2f s", history.status, len(history), n_steps, seconds)
    sliding = np.flatnonzero(history.gross_sliding)
    if len(sliding):
        log.info("gross sliding (every contact dof slips, |Q| = μP) at %d steps, first at step %d", len(sliding), sliding[0])
    return problem, history, adaptive


def _level_progress(unknowns: int, relative: float, seconds: float) -> None:
    log.info("adaptive level: %d unknowns, relative estimate %.3g, %.3f s", unknowns, relative, seconds)


def run_adaptive(scene: Scene, problem: Problem) -> Adaptive:
    """Solves the scene adaptively (its ``[adapt]`` table), logging one line per level."""
    adaptive = scene.solve_adaptive(problem, progress=_level_progress)
    log.info("adaptive solve stopped (%s) after %d levels", adaptive.stop, len(adaptive.levels))
    warn_adapt_stop(scene, adaptive)
    return adaptive


def warn_adapt_stop(scene: Scene, adaptive: Adaptive | AdaptiveHistory) -> None:
    """A ``SceneWarning`` when the adaptive loop stopped before its estimate reached ``adapt.tol``: on
    ``max_unknowns``, ``max_levels``, a level that did not converge, or an interruption."""
    if adaptive.stop not in ("tolerance", "exact"):
        tol = scene.get("adapt", "tol")
        asked = f"adapt.tol = {tol:g}" if tol is not None else "the default adapt.tol"
        warnings.warn(f"the adaptive loop stopped on {adaptive.stop} before its estimate reached {asked}: the last "
                      f"level's relative estimate is {adaptive.levels[-1].relative:.3g}", SceneWarning, stacklevel=2)


def run_scene(
    scene: Scene, out: Path, *, plots: bool = True, fields: bool = True, all_files: bool = False
) -> tuple[Problem, Solution, list[Path]]:
    """Solves a scene and writes every output into ``out``; returns the problem, solution and files.
    ``fields=False`` writes ``summary.json`` only (no CSV, VTU, history or level files, no plots);
    ``all_files=True`` writes every level of an adaptive run (as ``[adapt] write_levels = true``) and every
    step of a history (as ``[history] write_every = 1``), which ``tribo run --all-files`` asks for.

    For a scene with a ``[history]``, the solution is that of the last converged step, and the history's
    outputs (``tribo.history``) are written beside the summary; for a scene with ``[adapt]``, the problem
    and solution are those of the last level (with a ``[history]`` too: the history on the last mesh), and
    ``adapt.csv``/``adapt.png`` (``tribo.adaptive``) are written beside them."""
    out.mkdir(parents=True, exist_ok=True)
    clock = time.perf_counter()
    every = 1 if all_files else scene.get("history", "write_every")
    log.info("scene: %s", scene.title or "(untitled)")
    problem = scene.build()
    # The writers' libraries load while the solve runs (it releases the GIL): a second to import matplotlib,
    # a tenth of one for meshio, which would otherwise be spent after it.
    imports = _import_beside((["meshio"] if fields else []) + (["matplotlib.pyplot"] if fields and plots else []))
    log.info(
        "mesh: %d nodes, %d triangles; %d free dofs; %d multiplier dofs (%s); γ0 bound %.3e",
        problem.mesh.n_nodes,
        problem.mesh.n_triangles,
        problem.n_free,
        problem.n_multipliers,
        problem.space,
        problem.gamma0_bound,
    )
    given = ", ".join(f"{k} = {v}" for k, v in scene.sections.get("friction", {}).items())
    log.info("solving (%s)", given or "no friction given: frictionless")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", SceneWarning)
        if scene.has_history:
            problem, history, adapted = run_history(scene, problem, fields=fields, every=every)
            adapt_stop = adapted.stop if adapted is not None else None
            adaptive: Adaptive | AdaptiveHistory | None = adapted
            # The step that failed if one did (its status then sets the exit code), else the last one.
            last = history.failed if history.failed is not None else (history.solutions[-1] if len(history) else None)
            if last is None:
                raise SceneError(f"the history's first step ended with status '{history.status}'", "history")
            solution = last
            warn_solution(problem, solution)
        elif scene.has_adapt:
            static = run_adaptive(scene, problem)
            problem, solution, adapt_stop = static.problem, static.solution, static.stop
            adaptive = static
            # The last level's hierarchical estimate brings its bars (the same enriched solve): solved again only
            # where it has none (the loop did not estimate its last level, or handed back an enriched answer).
            has_bars = math.isfinite(solution.report.estimate.get("normal_force_error", math.nan))
            if scene.get("estimate", "error_bars", False) and not has_bars:
                log.info("solving the last level again with its error bars")
                solution = problem.solve(error_bars=True, **scene.solve_kwargs())
                warn_missing_error_bars(solution)
            history = None
            warn_solution(problem, solution)
        else:
            history, adapt_stop, adaptive = None, None, None
            problem, solution = scene.solve(problem, progress=_progress, on_phase=_phase)
    warned = []
    for w in caught:
        if issubclass(w.category, SceneWarning):
            warned.append(str(w.message))
            print(f"tribo: warning: {w.message}", file=sys.stderr)
        else:
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    seconds = time.perf_counter() - clock
    log.info("solve ended: %s after %.2f s", solution.report.status, seconds)
    clock = time.perf_counter()
    imports.join()
    with ThreadPoolExecutor(max_workers=1) as pool:
        # The body's VTU file, mostly zlib compression (which releases the GIL), is written beside the others.
        vtu = pool.submit(write_vtu, out / "result.vtu", problem, solution) if fields else None
        history_files: list[Path] = []
        if fields and history is not None:
            history_files += write_history(out, problem, history, plots=plots,
                                           plot_steps=scene.get("history", "plot_steps"),
                                           every=every)
        if fields and adaptive is not None:
            history_files += write_adaptive(out, adaptive, tol=scene.get("adapt", "tol"), plots=plots)
            if all_files or scene.get("adapt", "write_levels", False):
                history_files += write_levels(out, adaptive, **scene.solve_kwargs())
        files = []
        path = out / "summary.json"
        said = summary(scene, problem, solution, seconds, warned, adapt_stop,
                       None if adaptive is None else handed_back(adaptive))
        write_text_atomic(path, json.dumps(said, indent=2) + "\n")
        files.append(path)
        if vtu is None:
            return problem, solution, files
        files += write_contact_csv(out, problem, solution)
        files += vtu.result()
    if plots:
        files += _plots(out, problem, solution)
    log.info("wrote %d files in %.2f s", len(files) + len(history_files), time.perf_counter() - clock)
    return problem, solution, files + history_files


def _import_beside(modules: Sequence[str]) -> threading.Thread:
    """Imports ``modules`` in a thread (started here); a module that cannot be imported is left to its writer,
    which says so when it needs it. Join the thread before writing."""

    # Only what is not loaded yet: a caller's own pyplot (and its backend) is left alone.
    missing = [name for name in modules if name not in sys.modules]

    def load() -> None:
        if "matplotlib.pyplot" in missing:
            try:
                import matplotlib

                matplotlib.use("Agg")
            except Exception as e:  # noqa: BLE001 - the writer says so when it needs the module
                log.debug("matplotlib not loaded ahead: %s", e)
        for name in missing:
            try:
                importlib.import_module(name)
            except Exception as e:  # noqa: BLE001 - the writer says so when it needs the module
                log.debug("%s not loaded ahead: %s", name, e)

    thread = threading.Thread(target=load, name="tribo-imports", daemon=True)
    thread.start()
    return thread


def _plots(out: Path, problem: Problem, solution: Solution) -> list[Path]:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        from tribo import plot
    except ImportError:
        log.warning("matplotlib is not installed: no plots (pip install 'tribo[plot]')")
        return []
    files = []
    for name, draw in (("contact_normal.png", plot.contact_pressure), ("contact_tangential.png", plot.tangential)):
        fig, ax = plt.subplots(figsize=(7.0, 4.0), layout="constrained")
        draw(problem, solution, ax)
        fig.savefig(out / name, dpi=120)
        plt.close(fig)
        files.append(out / name)
    fig, ax = plt.subplots(figsize=(8.0, 4.5), layout="constrained")
    plot.von_mises(problem, solution, ax, edges=problem.mesh.n_triangles < 20000)
    fig.savefig(out / "von_mises.png", dpi=120)
    plt.close(fig)
    files.append(out / "von_mises.png")
    # A close-up of the contact zone, where the stresses concentrate.
    first = solution.pair(0)  # the first pair's zone (the problem's points are its side's)
    x = first.node_abscissae
    span = dof_span(first.multiplier_abscissae, first.states != 0, x[-1] - x[0] if first.closed else None)
    if span is not None:
        a, b = span
        w = max(b - a, problem.mesh.max_diameter * 1e-3)
        p = problem.contact_points([a - w, b + w])
        half = max(float(abs(p[1] - p[0]).max()), w) / 2.0
        # Centre the window a little inside the body (against the outward normal n); on the interface of
        # two bodies, to show both.
        n = problem.contact_normal
        inside = 0.0 if problem.primary is not None else 0.5
        cx, cy = p.mean(axis=0) - inside * half * np.asarray(n)
        hx, hy = (half, 0.6 * half) if abs(n[1]) >= abs(n[0]) else (0.6 * half, half)
        fig, ax = plt.subplots(figsize=(8.0, 4.5), layout="constrained")
        plot.von_mises(
            problem, solution, ax, scale=1.0, window=(cx - hx, cx + hx, cy - hy, cy + hy), obstacle=True
        )
        ax.set_title("Contact zone (true displacement), von Mises stress")
        fig.savefig(out / "von_mises_contact.png", dpi=120)
        plt.close(fig)
        files.append(out / "von_mises_contact.png")
    return files
