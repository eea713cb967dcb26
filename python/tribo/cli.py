"""The ``tribo`` command line.

``tribo run SCENE.toml --out DIR`` solves a scene and writes into DIR:

* ``summary.json``: the scene, the status, iterations, forces (normal and tangential resultants and the
  global components Fx, Fy), the obstacle's motion in global axes, KKT residuals, timings, the a posteriori
  error estimate (``estimate``: η, its parts and the relative traction and energy estimates), ``bodies``
  (per body: name, nodes, triangles, unknowns and the total reaction of its supports), the wall time
  (``wall_seconds``) and the peak resident memory of the process up to the end of the solve
  (``process_peak_memory_mb``, MiB, Linux's VmHWM; null where the platform does not report it),
  warnings, and the conventions (n, t, the direction of ξ, the signs of λ_t, of the shift and of the
  forces);
* ``adapt.csv``, ``adapt.png`` and the level series ``levels/level_NNN.vtu`` with ``adapt.pvd`` for a
  scene with ``[adapt]`` (the outputs above are then the last level's, on its refined mesh; see
  ``tribo.adaptive``);
* ``contact.csv`` (per multiplier dof), ``contact_nodes.csv``, ``contact_edges.csv``: the contact fields;
* ``result.vtu``, ``result_contact.vtu``, ``result_multipliers.vtu``: for ParaView; for two bodies also
  ``result.vtm``, a multiblock of one file per body (``result_<name>.vtu``), the contact fields on the
  secondary side;
* ``contact_normal.png``, ``contact_tangential.png``, ``von_mises.png``, ``von_mises_contact.png``
  (when matplotlib is installed; ``--no-plots`` skips them).

The run prints the status, the forces and the estimated error of the solve.

``tribo sweep SCENE.toml --set KEY=V1,V2,… [--zip KEY=…] --out DIR`` runs the scene over axes of values on
Dask (``tribo.sweep``): ``DIR/results.parquet``, ``DIR/results.csv``, ``DIR/cases/<hash>/`` per case and,
with ``--plot COLUMN``, ``DIR/sweep_COLUMN.png``; exit 0 when every case converged, 3 when one did not.

``tribo demo [--out DIR]`` runs the built-in scene (``tribo/scenes/demo.toml``) into ``tribo-demo-out``.

Progress (the condensation's time, then per QP: fixed-point iteration, change of λ_n, QP iterations and
time) is logged to stderr; a scene that is probably not what was meant (``tribo.checks``) prints a line
``tribo: warning: …`` per reason. Exit codes:
0 converged, 1 bad input or unwritable output (one line ``tribo: error: …`` says what and where), 3 the
solve ended without converging (results are still written), 2 an internal error (a bug: one line
``tribo: internal error: …``, please report it), 130 interrupted (Ctrl-C), 141 the reader of the
printed report went away (``tribo run … | head``; the results are written).
"""

from __future__ import annotations

import argparse
import json
import logging
import math
import os
import sys
import time
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from tribo._tribo import TriboError, __version__
from tribo.adaptive import write_adaptive, write_levels
from tribo.checks import SceneWarning, conventions, warn_solution
from tribo.history import vtu_every, write_history
from tribo.io import write_contact_csv, write_text_atomic, write_vtu
from tribo.problem import Problem
from tribo.results import Adaptive, AdaptiveHistory, History, Solution
from tribo.scene import Scene, SceneError, demo_scene_path, load_scene

__all__ = ["main", "run_scene"]

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


def summary(
    scene: Scene, problem: Problem, solution: Solution, seconds: float, warned: Sequence[str] = (),
    adapt_stop: str | None = None,
) -> dict[str, Any]:
    """The JSON summary of a run; ``adapt_stop``: why an adaptive loop stopped (None without ``[adapt]``)."""
    r = solution.report
    states = solution.state_names
    return {
        "tribo_version": __version__,
        "scene": scene.to_dict(),
        "status": r.status,
        "adapt_stop": adapt_stop,
        "failure": {"iteration": r.failed_iteration, "reason": r.failure_reason} if r.status == "qp_failed" else None,
        "friction": solution.friction,
        "mu": solution.mu,
        "iterations": r.iterations,
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
        "normal_force": solution.normal_force,
        "tangential_force": solution.tangential_force,
        "contact_force": list(solution.contact_force),
        "obstacle_motion": list(solution.obstacle_motion),
        "normal": [v + 0.0 for v in problem.contact_normal],
        "tangent": [v + 0.0 for v in problem.contact_tangent],
        "max_penetration": solution.max_penetration,
        "states": {name: states.count(name) for name in ("separation", "stick", "slip")},
        "kkt": solution.kkt,
        "kkt_max": solution.kkt_max,
        "timings": r.timings,
        # The a posteriori estimate; a relative one that has no reference (nothing touches, no energy) is null.
        "estimate": {k: (v if math.isfinite(v) else None) for k, v in r.estimate.items()},
        "bodies": bodies(problem, solution),
        "wall_seconds": seconds,
        "process_peak_memory_mb": peak_memory_mb(),
        "warnings": list(warned),
        "conventions": conventions(problem, solution),
    }


def bodies(problem: Problem, solution: Solution) -> list[dict[str, Any]]:
    """Per body: its name, nodes, triangles and unknowns, and the total reaction of its supports (Rx, Ry),
    which balances the contact force it takes and its loads."""
    out = []
    for name, (n0, n1, t0, t1), unknowns in problem.bodies:
        rx, ry = (float(v) for v in solution.reactions[n0:n1].sum(axis=0))
        out.append({"name": name, "nodes": n1 - n0, "triangles": t1 - t0, "unknowns": unknowns, "reaction": [rx, ry]})
    return out


def run_history(
    scene: Scene, problem: Problem, out: Path, *, plots: bool = True, fields: bool = True
) -> tuple[Problem, History, list[Path], str | None]:
    """Solves the scene's ``[history]`` with a progress bar over the steps and writes its outputs; with an
    ``[adapt]`` table, adaptively (a log line per level, then the history on the last mesh, and
    ``adapt.csv``/``adapt.png``). Returns the problem the history was solved on, the history, the files and
    why the adaptive loop stopped (None without ``[adapt]``)."""
    from tqdm import tqdm

    n_steps = len(scene.history_steps()[0])
    clock = time.perf_counter()
    files: list[Path] = []
    stop = None
    if scene.has_adapt:
        adaptive = scene.solve_history_adaptive(problem, progress=_level_progress)
        log.info("adaptive history stopped (%s) after %d levels", adaptive.stop, len(adaptive.levels))
        warn_adapt_stop(scene, adaptive)
        problem, history, stop = adaptive.problem, adaptive.history, adaptive.stop
        if fields:
            files += write_adaptive(out, adaptive, tol=scene.get("adapt", "tol"), plots=plots)
            files += write_levels(out, adaptive, **scene.solve_kwargs())
    else:
        with tqdm(total=n_steps, desc="steps", unit="step", disable=not log.isEnabledFor(logging.INFO)) as bar:

            def progress(step: int, steps: int, status: str, seconds: float) -> None:
                bar.update(1)
                bar.set_postfix_str(status)

            # Only the solutions whose VTU files are written are kept (every step's forces and states are).
            every = vtu_every(n_steps, scene.get("history", "write_every")) if fields else max(n_steps, 1)
            problem, history = scene.solve_history(problem, progress=progress, keep_every=every)
    seconds = time.perf_counter() - clock
    log.info("history ended: %s after %d of %d steps, %.2f s", history.status, len(history), n_steps, seconds)
    sliding = np.flatnonzero(history.gross_sliding)
    if len(sliding):
        log.info("gross sliding (every contact dof slips, |Q| = μP) at %d steps, first at step %d", len(sliding), sliding[0])
    if fields:
        files = write_history(out, problem, history, plots=plots, plot_steps=scene.get("history", "plot_steps"),
                              every=scene.get("history", "write_every")) + files
    return problem, history, files, stop


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
    scene: Scene, out: Path, *, plots: bool = True, fields: bool = True
) -> tuple[Problem, Solution, list[Path]]:
    """Solves a scene and writes every output into ``out``; returns the problem, solution and files.
    ``fields=False`` writes ``summary.json`` only (no CSV, VTU, history or level files, no plots).

    For a scene with a ``[history]``, the solution is that of the last converged step, and the history's
    outputs (``tribo.history``) are written beside the summary; for a scene with ``[adapt]``, the problem
    and solution are those of the last level (with a ``[history]`` too: the history on the last mesh), and
    ``adapt.csv``/``adapt.png`` (``tribo.adaptive``) are written beside them."""
    out.mkdir(parents=True, exist_ok=True)
    clock = time.perf_counter()
    log.info("scene: %s", scene.title or "(untitled)")
    problem = scene.build()
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
            problem, history, history_files, adapt_stop = run_history(scene, problem, out, plots=plots, fields=fields)
            # The step that failed if one did (its status then sets the exit code), else the last one.
            last = history.failed if history.failed is not None else (history.solutions[-1] if len(history) else None)
            if last is None:
                raise SceneError(f"the history's first step ended with status '{history.status}'", "history")
            solution = last
            warn_solution(problem, solution)
        elif scene.has_adapt:
            adaptive = run_adaptive(scene, problem)
            problem, solution, adapt_stop = adaptive.problem, adaptive.solution, adaptive.stop
            history_files = []
            if fields:
                history_files += write_adaptive(out, adaptive, tol=scene.get("adapt", "tol"), plots=plots)
                history_files += write_levels(out, adaptive, **scene.solve_kwargs())
            warn_solution(problem, solution)
        else:
            history_files, adapt_stop = [], None
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
    files = []
    path = out / "summary.json"
    said = summary(scene, problem, solution, seconds, warned, adapt_stop)
    write_text_atomic(path, json.dumps(said, indent=2) + "\n")
    files.append(path)
    if not fields:
        return problem, solution, files
    files += write_contact_csv(out, problem, solution)
    files += write_vtu(out / "result.vtu", problem, solution)
    if plots:
        files += _plots(out, problem, solution)
    return problem, solution, files + history_files


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
    active = solution.multiplier_abscissae[solution.states != 0]
    if len(active):
        a, b = float(active.min()), float(active.max())
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


def _one_line(text: str) -> str:
    return " ".join(text.split())


def _error(message: str) -> int:
    print(f"tribo: error: {_one_line(message)}", file=sys.stderr)
    return 1


def _percent(x: float) -> str:
    """A relative estimate as people read it ('n/a' where it has no reference)."""
    return f"{100 * x:.2g} %" if math.isfinite(x) else "n/a"


def _run(scene_path: Path, out: Path, plots: bool) -> int:
    if out.exists() and not out.is_dir():
        return _error(f"--out {out} exists and is not a directory")
    try:
        scene = load_scene(scene_path)
        problem, solution, files = run_scene(scene, out, plots=plots)
    except TriboError as e:
        context = "; ".join([type(e).__name__, *getattr(e, "__notes__", [])])
        return _error(f"{e} ({context})")
    except OSError as e:  # reading went through load_scene and read_mesh: this is writing the results
        return _error(f"cannot write the results into {out}: {e.strerror or e} ({e.filename or out})")
    r = solution.report
    print(f"{scene.title or scene_path}")
    print(
        f"  status {r.status} ({solution.friction}, {r.iterations} fixed-point iterations), "
        f"normal force {solution.normal_force:.6g}, tangential force {solution.tangential_force:.6g}, "
        f"max KKT residual {solution.kkt_max:.2e}"
    )
    est = r.estimate
    sharp = est.get("traction_hierarchical_relative", math.nan)
    traction = (f"{_percent(sharp)} in the contact tractions (L2 of Γ_C; hierarchical, sharp but not a bound; "
                f"the bound: {_percent(est['traction_relative'])}), " if math.isfinite(sharp) else
                f"{_percent(est['traction_relative'])} in the contact tractions (L2 of Γ_C, a bound), ")
    print(
        f"  estimated error: {traction}"
        f"{_percent(est['energy_relative'])} in energy (η = {est['total']:.3g}: bulk {est['bulk']:.3g}, Γ_C "
        f"{est['gamma_c']:.3g}, contact {est['contact']:.3g}, friction {est['friction']:.3g})"
    )
    fx, fy = solution.contact_force
    said = conventions(problem, solution)
    on = "the obstacle on the body" if problem.primary is None else f"'{problem.primary}' on the secondary body"
    print(f"  force of {on} (Fx, Fy) = ({fx:.6g}, {fy:.6g}) in global axes")
    print(f"  {said['n']}; {said['t']}; shift: {said['shift']}")
    states = solution.state_names
    print(
        "  multiplier dofs: "
        + ", ".join(f"{states.count(n)} {n}" for n in ("separation", "stick", "slip"))
    )
    said_json = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    if said_json["adapt_stop"] is not None:
        print(f"  adaptive loop stopped on {said_json['adapt_stop']}")
    peak = said_json["process_peak_memory_mb"]
    t = r.timings
    print(
        f"  {said_json['wall_seconds']:.3g} s (factorization {t['factorization']:.3g} s, QPs {t['qp']:.3g} s)"
        + (f", peak memory {peak:.0f} MiB" if peak is not None else "")
    )
    print(f"  wrote {len(files)} files to {out.resolve()}:")
    for f in files:
        print(f"    {f.name}")
    if r.status != "converged":
        print(f"tribo: the solve ended with status '{r.status}' (results written anyway)", file=sys.stderr)
        return 3
    return 0


def _axes(specs: Sequence[str]) -> dict[str, list[Any]]:
    from tribo.sweep import SweepError, parse_axis

    out: dict[str, list[Any]] = {}
    for spec in specs:
        key, values = parse_axis(spec)
        if key in out:
            raise SweepError(f"axis {key!r} is given twice", key)
        out[key] = values
    return out


def _sweep(args: argparse.Namespace) -> int:
    """``tribo sweep``: runs the cases, prints the table and draws the asked charts; exit 3 when a case did
    not converge."""
    from tribo import sweep as sweeping

    if args.out.exists() and not args.out.is_dir():
        return _error(f"--out {args.out} exists and is not a directory")
    try:
        axes, zipped = _axes(args.axes), _axes(args.zipped)
        if not axes and not zipped:
            return _error("a sweep needs at least one axis: --set KEY=V1,V2,… or --zip KEY=V1,V2,…")
        df = sweeping.sweep(args.scene, axes, zipped=zipped, out=args.out, client=args.scheduler,
                            workers=args.workers, threads=args.threads, files=args.files, plots=args.plots,
                            progress=not args.quiet)
    except TriboError as e:
        context = "; ".join([type(e).__name__, *getattr(e, "__notes__", [])])
        return _error(f"{e} ({context})")
    except OSError as e:
        return _error(f"cannot write the sweep into {args.out}: {e.strerror or e} ({e.filename or args.out})")
    names = [*axes, *zipped]
    shown = [*names, "status", "iterations", "normal_force", "tangential_force", "contact_extent", "stick_extent",
             "kkt_max", "seconds"]
    print(df[shown].to_string(index=False))
    counts = df["status"].value_counts()
    print(f"{len(df)} cases: " + ", ".join(f"{n} {status}" for status, n in counts.items()))
    files = [args.out / "results.parquet", args.out / "results.csv"]
    for column in args.plot:
        if column not in df.columns or column in names:
            return _error(f"--plot {column}: not an output column (columns: {', '.join(sweeping.COLUMNS)})")
        files += _sweep_plot(df, names, column, args.out)
    print(f"wrote {', '.join(str(f) for f in files)} and the cases under {args.out / 'cases'}")
    return 0 if bool((df["status"] == "converged").all()) else 3


def _sweep_plot(df: Any, names: Sequence[str], column: str, out: Path) -> list[Path]:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        from tribo import plot
    except ImportError:
        log.warning("matplotlib is not installed: no plots (pip install 'tribo[plot]')")
        return []
    fig = plot.sweep_figure(df, names, column)
    path = out / f"sweep_{column}.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return [path]


def build_parser() -> argparse.ArgumentParser:
    """The ``tribo`` command line (the documentation site renders its help from it)."""
    parser = argparse.ArgumentParser(prog="tribo", description="2D frictional contact, stabilized multipliers.")
    parser.add_argument("--version", action="version", version=f"tribo {__version__}")
    parser.add_argument("-q", "--quiet", action="store_true", help="no progress log on stderr")
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="solve a TOML scene and write its results")
    run.add_argument("scene", type=Path, help="scene file (TOML)")
    run.add_argument("--out", type=Path, required=True, help="output directory")
    run.add_argument("--no-plots", action="store_true", help="skip the PNG plots")
    sw = sub.add_parser("sweep", help="run a scene over axes of parameters on Dask (pip install 'tribo[sweep]')")
    sw.add_argument("scene", type=Path, help="scene file (TOML)")
    sw.add_argument("--set", dest="axes", action="append", default=[], metavar="KEY=V1,V2,…",
                    help="an axis: a scene key and its values (repeat; the cases are the product of the axes)")
    sw.add_argument("--zip", dest="zipped", action="append", default=[], metavar="KEY=V1,V2,…",
                    help="an axis that moves together with the other --zip axes (equal lengths)")
    sw.add_argument("--out", type=Path, required=True, help="output directory (results.parquet/csv, cases/)")
    sw.add_argument("--scheduler", metavar="ADDRESS", help="a running Dask scheduler (tcp://host:port)")
    sw.add_argument("--workers", type=int, help="workers of the local cluster (default: cores // --threads)")
    sw.add_argument("--threads", type=int, default=1, help="threads per solve (default 1)")
    sw.add_argument("--files", action="store_true", help="write each case's CSV and VTU files")
    sw.add_argument("--plots", action="store_true", help="with --files, each case's plots too")
    sw.add_argument("--plot", action="append", default=[], metavar="COLUMN",
                    help="draw COLUMN over the axes into sweep_COLUMN.png (repeat)")
    demo = sub.add_parser("demo", help="run the built-in demo scene")
    demo.add_argument("--out", type=Path, default=Path("tribo-demo-out"), help="output directory (tribo-demo-out)")
    demo.add_argument("--no-plots", action="store_true", help="skip the PNG plots")
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``tribo`` script; returns the exit code."""
    args = build_parser().parse_args(argv)
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(logging.Formatter("[tribo %(relativeCreated)7.0f ms] %(message)s"))
    log.handlers[:] = [handler]
    log.setLevel(logging.WARNING if args.quiet else logging.INFO)
    log.propagate = False
    scene = demo_scene_path() if args.command == "demo" else args.scene
    try:
        if args.command == "sweep":
            return _sweep(args)
        return _run(scene, args.out, not args.no_plots)
    except KeyboardInterrupt:
        print("tribo: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        # The reader of stdout went away (``tribo run … | head``): stop quietly, as a shell tool does.
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 141
    except (SystemExit, GeneratorExit):
        raise
    except BaseException as e:  # noqa: BLE001 - pyo3's PanicException is not an Exception: a bug either way
        print(f"tribo: internal error: {type(e).__name__}: {_one_line(str(e))} (please report it)", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
