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
* ``adapt.csv`` (and with ``--plots`` ``adapt.png``) for a scene with ``[adapt]`` (the outputs above are then the last
  level's, on its refined mesh; see ``tribo.adaptive``), and with ``write_levels = true`` the level series
  ``levels/level_NNN.vtu`` with ``adapt.pvd``;
* ``contact.csv`` (per multiplier dof), ``contact_nodes.csv``, ``contact_edges.csv``: the contact fields;
* ``result.vtu``, ``result_contact.vtu``, ``result_multipliers.vtu``: for ParaView; for two bodies also
  ``result.vtm``, a multiblock of one file per body (``result_<name>.vtu``), the contact fields on the
  secondary side;
* with ``--plots`` (when matplotlib is installed): ``contact_normal.png``, ``contact_tangential.png``,
  ``von_mises.png``, ``von_mises_contact.png`` and the charts of a history or an adaptive loop. Without it
  the run writes the data files only: a plot takes about a third of a second and matplotlib a second to load,
  more than many solves (``docs/output_cost.md``).

The run prints the status, the forces and the estimated error of the solve.

``tribo sweep SCENE.toml --set KEY=V1,V2,… [--zip KEY=…] --out DIR`` runs the scene over axes of values on
Dask (``tribo.sweep``): ``DIR/results.parquet``, ``DIR/results.csv``, ``DIR/cases/<hash>/`` per case and,
with ``--plot COLUMN``, ``DIR/sweep_COLUMN.png``; exit 0 when every case converged, 3 when one did not.

``tribo demo [--out DIR] [--no-plots]`` runs the built-in scene (``tribo/scenes/demo.toml``) into
``tribo-demo-out``, with its plots.

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
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from tribo._tribo import __version__
from tribo.errors import TriboError
from tribo.checks import actors, conventions
from tribo.run import log, run_scene
from tribo.scene import demo_scene_path, load_scene

__all__ = ["main", "run_scene"]


def _one_line(text: str) -> str:
    return " ".join(text.split())


def _error(message: str) -> int:
    print(f"tribo: error: {_one_line(message)}", file=sys.stderr)
    return 1


def _percent(x: float) -> str:
    """A relative estimate as people read it ('n/a' where it has no reference)."""
    return f"{100 * x:.2g} %" if math.isfinite(x) else "n/a"


# The quantities that carry error bars, as `tribo run` names them, and their Solution attributes.
_BARS = (("P", "normal_force"), ("Q", "tangential_force"), ("contact width", "contact_width"),
         ("stick width", "stick_width"))


def _run(scene_path: Path, out: Path, plots: bool, all_files: bool = False) -> int:
    if out.exists() and not out.is_dir():
        return _error(f"--out {out} exists and is not a directory")
    try:
        scene = load_scene(scene_path)
        problem, solution, files = run_scene(scene, out, plots=plots, all_files=all_files)
    except TriboError as e:
        context = "; ".join([type(e).__name__, *getattr(e, "__notes__", [])])
        return _error(f"{e} ({context})")
    except OSError as e:  # reading went through load_scene and read_mesh: this is writing the results
        return _error(f"cannot write the results into {out}: {e.strerror or e} ({e.filename or out})")
    r = solution.report
    print(f"{scene.title or scene_path}")
    steps = {"newton": "Newton steps", "fixed_point": "fixed-point iterations"}.get(str(r.coulomb_method), "iterations")
    fallback = " after Newton did not converge" if r.coulomb_fallback else ""
    other = "Newton" if r.coulomb_method == "fixed_point" else "the fixed point"
    undecided = (f"{other} ended {r.check_status}" if r.check_status not in (None, "converged") else
                 f"{other} was refused (see the log)" if r.check_status is None else "no contraction measured")
    fallback += {"agree": f"; {other} agrees", "undecided": f"; unchecked: {undecided}",
                 "differ": f"; {other} finds another answer: λ is not unique here"}.get(str(r.coulomb_check), "")
    print(
        f"  status {r.status} ({solution.friction}, {r.iterations} {steps}{fallback}), "
        f"normal force {solution.normal_force:.6g}, tangential force {solution.tangential_force:.6g}, "
        f"max KKT residual {solution.kkt_max:.2e}"
    )
    est = r.estimate
    bars = [(name, getattr(solution, key), est.get(f"{key}_error", math.nan)) for name, key in _BARS]
    with_bars = all(math.isfinite(bar) for _, _, bar in bars)
    if with_bars:
        shown = ", ".join(f"{name} = {value:.6g} ± {bar:.2g}" for name, value, bar in bars)
        print(f"  {shown} (error bars: 1.5 times the change under enrichment, sharp but not bounds)")
    elif not scene.has_history and not scene.get("estimate", "error_bars", False):
        print("  error bars of P, Q and the zone widths: set error_bars = true in [estimate] (one more solve, enriched "
              "everywhere and twice along the contact: 8-9 times the unknowns)")
    said_json = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    # An enriched answer handed back carries half its change from the level it enriched (unless solved again for its
    # bars).
    kind = "half its change from the level it enriched" if said_json["adapt_handed_back"] and not with_bars else \
        "hierarchical"
    sharp = est.get("traction_hierarchical_relative", math.nan)
    if not math.isfinite(sharp):
        # The level after an estimated one: the bound scaled by the two estimates' ratio measured there.
        sharp, kind = est.get("traction_calibrated_relative", math.nan), "the bound calibrated on the level before"
    traction = (f"{_percent(sharp)} in the contact tractions (L2 of Γ_C; {kind}, sharp but not a bound; "
                f"the bound: {_percent(est['traction_relative'])}), " if math.isfinite(sharp) else
                f"{_percent(est['traction_relative'])} in the contact tractions (L2 of Γ_C, a bound), ")
    print(
        f"  estimated error: {traction}"
        f"{_percent(est['energy_relative'])} in energy (η = {est['total']:.3g}: bulk {est['bulk']:.3g}, Γ_C "
        f"{est['gamma_c']:.3g}, contact {est['contact']:.3g}, friction {est['friction']:.3g})"
    )
    fx, fy = solution.contact_force
    said = conventions(problem, solution)
    on = " on ".join(actors(problem))
    print(f"  force of {on} (Fx, Fy) = ({fx:.6g}, {fy:.6g}) in global axes")
    print(f"  {said['n']}; {said['t']}; shift: {said['shift']}")
    states = solution.state_names
    print(
        "  multiplier dofs: "
        + ", ".join(f"{states.count(n)} {n}" for n in ("separation", "stick", "slip"))
    )
    if said_json["adapt_stop"] is not None:
        enriched = ", the answer enriched for the last level's estimate handed back" if said_json["adapt_handed_back"] \
            else ""
        print(f"  adaptive loop stopped on {said_json['adapt_stop']}{enriched}")
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
    run.add_argument("--plots", action=argparse.BooleanOptionalAction, default=False,
                     help="draw the PNG plots too (default: the data files only, for ParaView, pandas, JSON)")
    run.add_argument("--all-files", action="store_true",
                     help="write every level of an adaptive run (each but the last solved again, into levels/) and "
                          "every step of a history (default: the last level, and up to 200 steps)")
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
    demo.add_argument("--plots", action=argparse.BooleanOptionalAction, default=True,
                      help="draw the PNG plots (default: yes)")
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
        return _run(scene, args.out, args.plots, getattr(args, "all_files", False))
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
