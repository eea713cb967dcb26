"""Study 10 — studies as sweeps, and what a sweep costs on Dask.

1. Two studies ported to ``tribo sweep``: the Coulomb fixed point over μ × ν × (ω, qp_tol) (study 1c,
   ``scenes/coulomb_map.toml``) and the checkerboard map over H/h × γ0 × space (study 1a,
   ``scenes/checkerboard.toml``). Each is one scene and the one command written at the top of that scene
   file, which this script reads and runs as it stands (``--smoke``: the first two values of each axis).
   Their tables are compared, case by case, with the studies' own CSV files (``docs/coulomb_fixed_point.csv``,
   ``docs/checkerboard.csv``), which call ``Problem.solve`` in a loop.
2. Overhead: sweeps of N cases of the Hertz scene (μ varies) on a fresh 2-worker ``LocalCluster``, against
   the sum of the same cases' times run one after the other in this process (``run_scene``, summary only).
   Reported: the sweep's wall time (cluster start and stop included) over that sum, and the same for the
   core-seconds (wall × workers) the sweep held.

    python scripts/study_sweeps.py          # docs/sweep.{md,csv}, docs/sweep_coulomb_map.png, docs/sweep_checkerboard.png
    python scripts/study_sweeps.py --smoke --out /tmp/x
"""

from __future__ import annotations

import contextlib
import io
import logging
import shlex
import shutil
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import studylib as sl  # noqa: E402

from tribo.cli import main as tribo_main  # noqa: E402
from tribo.run import run_scene  # noqa: E402
from tribo.scene import parse_scene, read_scene_data, scene_path  # noqa: E402
from tribo.sweep import cases, sweep  # noqa: E402

# Sizes of the overhead study: (h_min of the Hertz scene, number of cases).
OVERHEAD = [(0.04, 100), (0.01, 100), (0.0025, 40)]
SMOKE_OVERHEAD = [(0.04, 6)]


def documented_command(scene: Path) -> list[str]:
    """The ``tribo sweep`` command written in the comment at the top of a scene file, as arguments."""
    lines, on = [], False
    for line in scene.read_text(encoding="utf-8").splitlines():
        text = line.lstrip("#").strip()
        if text.startswith("tribo sweep"):
            on = True
        if on:
            lines.append(text.rstrip("\\").strip())
            if not text.endswith("\\"):
                break
    args = shlex.split(" ".join(lines))
    assert args[:2] == ["tribo", "sweep"], f"no tribo sweep command in {scene}"
    return args[2:]


def smoke_args(args: list[str]) -> list[str]:
    """The command with the first two values of each axis."""
    out = []
    for a in args:
        if "=" in a and not a.startswith("-"):
            key, values = a.split("=", 1)
            a = key + "=" + ",".join(values.split(",")[:2])
        out.append(a)
    return out


def run_ported(name: str, smoke: bool, work: Path) -> Any:
    import pandas as pd

    scene = scene_path(name)
    args = documented_command(scene)
    args = smoke_args(args) if smoke else args
    out_at = args.index("--out") + 1
    args[out_at] = str(work / args[out_at])
    args[0] = str(scene)
    clock = time.perf_counter()
    code = tribo_main(["-q", "sweep", *args])
    seconds = time.perf_counter() - clock
    print(f"{name}: exit {code}, {seconds:.1f} s")
    return pd.read_parquet(Path(args[out_at]) / "results.parquet"), Path(args[out_at]), seconds


def compare_coulomb(df: Any) -> dict[str, Any]:
    """Case by case against docs/coulomb_fixed_point.csv (its h_min = 0.01 grid, by the default QP method)."""
    import pandas as pd

    ref = pd.read_csv(sl.DOCS / "coulomb_fixed_point.csv")
    ref = ref[(ref["h_min"] == 0.01) & (ref["qp_method"] == "auto")]
    keys = ["friction.mu", "material.poisson", "solver.fp_relaxation", "solver.qp_tol"]
    ref = ref.rename(columns={"mu": keys[0], "nu": keys[1], "omega": keys[2], "qp_tol": keys[3]})
    both = df.merge(ref, on=keys, suffixes=("", "_study"))
    rel = np.abs(both["normal_force"] - both["force"]) / both["force"]
    return dict(matched=len(both), cases=len(df), same_status=int((both["status"] == both["status_study"]).sum()),
                same_iterations=int((both["iterations"] == both["iterations_study"]).sum()),
                force_rel_max=float(rel.max()) if len(both) else float("nan"))


def compare_checkerboard(df: Any) -> dict[str, Any]:
    """Case by case against docs/checkerboard.csv."""
    import pandas as pd

    ref = pd.read_csv(sl.DOCS / "checkerboard.csv").rename(columns={
        "space": "discretization.space", "H/h": "discretization.multiplier_ratio",
        "theta": "discretization.gamma0_fraction"})
    keys = ["discretization.space", "discretization.multiplier_ratio", "discretization.gamma0_fraction"]
    both = df.merge(ref, on=keys, suffixes=("", "_study"))
    force = np.abs(both["normal_force"] - both["force"]) / both["force"]
    est = np.abs(both["traction_estimate"] - both["estimate"]) / both["estimate"]
    return dict(matched=len(both), cases=len(df), same_status=int((both["status"] == both["status_study"]).sum()),
                force_rel_max=float(force.max()) if len(both) else float("nan"),
                estimate_rel_max=float(est.max()) if len(both) else float("nan"))


def overhead(h_min: float, n: int, work: Path) -> dict[str, Any]:
    """N Hertz cases (μ from 0.01 to 0.5, Coulomb, shift 0.004): serial sum, then one sweep on a fresh
    2-worker LocalCluster."""
    data = read_scene_data(scene_path("hertz"))
    data["discretization"]["h_min"] = h_min
    data["obstacle"]["shift"] = 0.004
    axes = {"friction.mu": [float(m) for m in np.round(np.linspace(0.01, 0.5, n), 6)]}
    serial = 0.0
    for case in cases(data, axes):
        clock = time.perf_counter()
        with contextlib.redirect_stderr(io.StringIO()):  # its scene warnings: the coarse meshes have few dofs
            run_scene(parse_scene(case.data), work / "serial", fields=False)
        serial += time.perf_counter() - clock
    clock = time.perf_counter()
    df = sweep(data, axes, out=work / f"overhead_{h_min}_{n}", workers=2, progress=False)
    wall = time.perf_counter() - clock
    # The same sweep on a cluster that is already running (a second sweep of a session).
    import distributed

    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0",
                                  silence_logs=logging.ERROR, env={"RAYON_NUM_THREADS": "1"}) as cluster, \
            distributed.Client(cluster) as client:
        client.run(lambda: __import__("tribo.cli"))  # what a worker has loaded after its first sweep
        clock = time.perf_counter()
        sweep(data, axes, out=work / f"overhead_running_{h_min}_{n}", client=client, progress=False)
        running = time.perf_counter() - clock
    row = dict(h_min=h_min, cases=n, unknowns=int(df["unknowns"].iloc[0]), converged=int((df["status"] == "converged").sum()),
               serial_seconds=serial, per_case_ms=1e3 * serial / n, sweep_seconds=wall,
               on_worker_seconds=float(df["seconds"].sum()), wall_over_serial=wall / serial,
               core_seconds_over_serial=2 * wall / serial, running_seconds=running,
               running_over_serial=running / serial)
    print({k: (round(v, 3) if isinstance(v, float) else v) for k, v in row.items()})
    return row


def run(smoke: bool, out: Path) -> dict[str, Any]:
    out.mkdir(parents=True, exist_ok=True)
    logging.getLogger("distributed").setLevel(logging.ERROR)
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        coulomb, coulomb_dir, coulomb_s = run_ported("coulomb_map", smoke, work)
        board, board_dir, board_s = run_ported("checkerboard", smoke, work)
        shutil.copy(coulomb_dir / "sweep_iterations.png", out / "sweep_coulomb_map.png")
        shutil.copy(board_dir / "sweep_lambda_n_oscillation.png", out / "sweep_checkerboard.png")
        rows = [overhead(h, n, work) for h, n in (SMOKE_OVERHEAD if smoke else OVERHEAD)]
    cmp_c, cmp_b = compare_coulomb(coulomb), compare_checkerboard(board)
    headers = list(rows[0])
    sl.write_csv(out / "sweep.csv", headers, [[r[h] for h in headers] for r in rows])
    text = [
        "# Study 10: studies as sweeps, and what a sweep costs",
        "",
        "Regenerate with `python scripts/study_sweeps.py`. Wall times on the 2-core machine.",
        "",
        "## Two studies, one scene and one command each",
        "",
        "The commands are those written at the top of the scene files, run as they stand.",
        "",
        "| study | scene | cases | sweep seconds | compared with | matched | same status | same iterations |"
        " largest relative difference |",
        "|---|---|---|---|---|---|---|---|---|",
        f"| 1c Coulomb fixed point | `scenes/coulomb_map.toml` | {len(coulomb)} | {coulomb_s:.1f} | "
        f"`coulomb_fixed_point.csv` | {cmp_c['matched']} | {cmp_c['same_status']} | {cmp_c['same_iterations']} | "
        f"normal force {cmp_c['force_rel_max']:.1e} |",
        f"| 1a checkerboard | `scenes/checkerboard.toml` | {len(board)} | {board_s:.1f} | `checkerboard.csv` | "
        f"{cmp_b['matched']} | {cmp_b['same_status']} | – | normal force {cmp_b['force_rel_max']:.1e}, "
        f"traction estimate {cmp_b['estimate_rel_max']:.1e} |",
        "",
        "![iterations of the Coulomb fixed point over μ × ν](sweep_coulomb_map.png)",
        "",
        "![oscillation of λ_n over H/h × γ0](sweep_checkerboard.png)",
        "",
        "The oscillation column of a sweep is TV(λ_n) / (2 max λ_n) (1: one smooth hump); study 1a divides by",
        "the Hertz p_max instead, so its checkerboards read larger (22.6 there for 5.4 here: the checkerboard's",
        "own maximum is about four times p_max).",
        "",
        "## Overhead on a local cluster",
        "",
        "N cases of the Hertz scene (Coulomb, μ from 0.01 to 0.5, shift 0.004), run one after the other in one",
        "process (`run_scene`, summary only: the serial sum), then as one sweep on a fresh `LocalCluster` of 2",
        "worker processes (its start and stop included), and on a cluster that is already running (a second sweep",
        "of a session: workers started, tribo imported).",
        "",
        sl.markdown_table(
            ["h_min", "cases", "unknowns", "converged", "ms per case", "serial s", "sweep s", "sweep / serial",
             "core-s / serial", "running cluster s", "running / serial"],
            [[r["h_min"], r["cases"], r["unknowns"], r["converged"], r["per_case_ms"], r["serial_seconds"],
              r["sweep_seconds"], r["wall_over_serial"], r["core_seconds_over_serial"], r["running_seconds"],
              r["running_over_serial"]] for r in rows],
        ),
        "",
    ]
    (out / "sweep.md").write_text("\n".join(text), encoding="utf-8")
    return dict(coulomb=coulomb, board=board, compare_coulomb=cmp_c, compare_board=cmp_b, overhead=rows)


def main(argv: list[str] | None = None) -> Any:
    return sl.cli(run, __doc__, argv)


if __name__ == "__main__":
    main()
