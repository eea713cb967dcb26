"""Parameter sweeps of a scene on Dask: one call (or ``tribo sweep``) from a laptop to a cluster.

A sweep is a scene and some **axes**: scene keys with lists of values (``friction.mu = [0, 0.2, 0.4]``).
The cases are the product of the axes; axes given as ``zipped`` move together (equal lengths) and make one
factor of that product. Every case is checked against the scene schema before anything runs, so a typo is
one ``SceneError`` naming the key, not a hundred failed cases.

Each case runs ``tribo.run.run_scene`` (what ``tribo run`` runs) on a Dask worker and becomes one row of a
table: the axes, then status, failure reason, iterations, forces, the extents of the contact and stick
zones, the largest KKT residual, unknowns, seconds, the estimated errors (see ``COLUMNS``): of the solve,
of the last step of a ``[history]`` scene, of the last level of an ``[adapt]`` one, as ``tribo run``'s
``summary.json`` reports them. The table is
written to ``DIR/results.parquet`` and ``DIR/results.csv`` and returned as a pandas DataFrame;
``df.set_index(axes).to_xarray()`` gives the grid.

* **Where it runs.** By default on a ``LocalCluster`` of worker processes sized to the machine: workers ×
  threads per solve ≤ cores, and each worker caps the threads of its solves (``RAYON_NUM_THREADS``, which
  faer's parallel factorizations use). ``client=`` (or ``tribo sweep --scheduler tcp://host:port``) runs on
  an existing cluster instead: ``dask scheduler`` and ``dask worker`` on the machines, or dask-jobqueue on
  Slurm/PBS. The workers need tribo installed, and, for per-case files (``files=True``), ``DIR`` on a
  filesystem they share with the client; the table and the cache are written by the client either way.
* **Cache.** A case is named by a hash of its checked scene (the mesh files it reads included) and the
  tribo version; its outputs live in ``DIR/cases/<hash>/`` (``summary.json``; the VTU files and plots
  with ``files=True``), and ``row.json`` there marks it done. A rerun skips the cases whose ``row.json``
  exists, so an interrupted sweep resumes where it stopped.
* **Faults.** A case whose solve fails is a row with its status and reason, never the end of the sweep
  (it is cached: it would fail again). A worker that dies mid-case (killed, out of memory) has its case
  retried on another worker by Dask; a case that kills ``distributed.scheduler.allowed-failures`` + 1
  workers (4 by default) is a row with status ``killed_worker`` and is not cached, so a rerun tries it
  again. The ``attempts`` column counts the workers that started a case (on a shared filesystem).
  Ctrl-C cancels what is left and writes the table of what is done before it re-raises.
* **Batches.** Cases go to Dask in batches of about 8 per worker (one case per batch for small sweeps),
  so that Dask's cost per task is paid per batch. A worker that dies retries its whole batch (its
  finished cases count a second attempt); a batch that kills workers repeatedly is split into single
  cases, so that only the case that kills them ends ``killed_worker``. Dask counts a worker's death
  against every case the worker held, queued ones too: a case that never started runs again (at most 3
  more times; without a shared filesystem no start is recorded, so a case that kills workers is then
  tried that often before it is marked).

Needs the ``sweep`` extra: ``pip install "tribo[sweep]"`` (dask, distributed, pandas, pyarrow, xarray).
"""

from __future__ import annotations

import contextlib
import hashlib
import importlib.util
import io
import itertools
import json
import logging
import math
import os
import socket
import time
import tomllib
from collections.abc import Callable, Iterator, Mapping, Sequence
from copy import deepcopy
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from tribo._tribo import __version__
from tribo.errors import TriboError
from tribo.io import write_text_atomic
from tribo.run import run_scene
from tribo.scene import SceneError, parse_scene, read_scene_data

if TYPE_CHECKING:  # pragma: no cover - types only
    import pandas as pd
    from distributed import Client

__all__ = ["sweep", "cases", "parse_axis", "Case", "SweepError", "COLUMNS", "MAX_CASES"]

log = logging.getLogger("tribo")

#: The most cases one sweep may have (checked before the cases are enumerated).
MAX_CASES = 100_000

#: The columns of the table after the axes, each with what it holds.
COLUMNS: dict[str, str] = {
    "case": "the case's hash: its outputs are in DIR/cases/<case>/",
    "status": "the solve's status (converged, max_iterations, qp_failed, …); error: the scene could not be "
    "built or solved (failure says why); killed_worker: the case killed every worker that tried it",
    "adapt_stop": "why the adaptive loop stopped (tolerance, exact, max_unknowns, …); empty without [adapt]",
    "adapt_handed_back": "whether the adaptive loop handed back the answer enriched for its last level's estimate; "
                         "False without [adapt]",
    "failure": "why a case did not converge or failed (empty when it converged)",
    "friction": "the friction law the solve used",
    "formulation": "what the body was solved with: displacement (P1) or mixed (displacement–pressure; auto's choice)",
    "iterations": "iterations of the Coulomb method: fixed-point iterations or Newton steps (of the last step of a "
                  "history)",
    "coulomb_method": "the Coulomb method that answered (fixed_point or newton; empty without Coulomb friction)",
    "coulomb_check": "with [solver] coulomb_check: agree, differ (two answers: λ not unique) or undecided; else empty",
    "normal_force": "the normal resultant of the contact pressure",
    "tangential_force": "the tangential resultant",
    "contact_extent": "the length of Γ_C between the first and last multiplier dof in contact (stick or slip; on a "
                      "closed side, the shortest arc that holds them)",
    "stick_extent": "the same for the dofs that stick",
    "kkt_max": "the largest KKT residual of (3.1)",
    "lambda_n_oscillation": "TV(λ_n) over the multiplier dofs / (2 max λ_n): 1 for one smooth hump, larger when the "
    "pressure oscillates (the checkerboard of γ0 = 0 with T_H finer than the FE edges)",
    "unknowns": "free displacement dofs",
    "multipliers": "multiplier dofs",
    "traction_estimate": "the relative a posteriori estimate of the error in the contact tractions (the bound)",
    "traction_hierarchical": "the hierarchical one, where an adaptive loop computed it (handed back: half its change)",
    "energy_estimate": "the relative a posteriori estimate of the energy error",
    "seconds": "wall time of the case on its worker (build, solve and outputs)",
    "warnings": "the scene warnings of the run (tribo.checks), joined by ' | '",
    "attempts": "how many workers started the case in this run (more than 1: Dask retried it after a worker "
    "died; counted on a filesystem the workers share with the client, else 1)",
}


class SweepError(TriboError):
    """A sweep that cannot start: bad axes, too many cases, a missing ``sweep`` extra, an unusable DIR."""

    def __init__(self, message: str, key: str | None = None) -> None:
        super().__init__(message)
        self.kind = "SweepError"
        self.details: dict[str, Any] = {"key": key} if key is not None else {}


@dataclass(frozen=True)
class Case:
    """One case of a sweep: its axis values, its scene (as TOML data, the axes set) and its hash."""

    index: int
    values: dict[str, Any]
    data: dict[str, Any]
    key: str


# ----- axes -----
def _split_top_level(text: str) -> list[str]:
    """Splits ``text`` at the commas that are outside brackets and quotes: ``0,[1,2],"a,b"`` has 3 items."""
    items, depth, quote, start = [], 0, "", 0
    for i, c in enumerate(text):
        if quote:
            quote = "" if c == quote else quote
        elif c in "\"'":
            quote = c
        elif c in "[{":
            depth += 1
        elif c in "]}":
            depth -= 1
        elif c == "," and depth == 0:
            items.append(text[start:i])
            start = i + 1
    items.append(text[start:])
    return [s.strip() for s in items]


def _value(text: str) -> Any:
    """A value as TOML reads it (``0.2``, ``[1, 2]``, ``"P1"``, ``true``); a bare word is a string."""
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except (tomllib.TOMLDecodeError, RecursionError):  # nested too deeply to read: a string the schema refuses
        return text


def parse_axis(spec: str) -> tuple[str, list[Any]]:
    """``"friction.mu=0,0.2,0.4"`` → ``("friction.mu", [0, 0.2, 0.4])``: a scene key and its values, each
    read as a TOML value (arrays in brackets may hold commas; a bare word is a string)."""
    key, sep, values = spec.partition("=")
    key = key.strip()
    if not sep or not key or not values.strip():
        raise SweepError(f"an axis is KEY=V1,V2,… (a scene key and its values), got {spec!r}", key or None)
    items = _split_top_level(values)
    if any(not s for s in items):
        raise SweepError(f"axis {key!r} has an empty value in {values!r}", key)
    return key, [_value(s) for s in items]


def _path(key: str) -> list[str | int]:
    """``"bodies[1].material.young"`` or ``"bodies.1.material.young"`` → ``["bodies", 1, "material", "young"]``."""
    parts: list[str | int] = []
    for part in key.replace("[", ".").replace("]", "").split("."):
        if not part:
            raise SweepError(f"axis key {key!r} is not a dotted scene key (section.key)", key)
        parts.append(int(part) if part.isdigit() else part)
    if len(parts) < 2 and parts[0] not in ("title", "description"):
        raise SweepError(f"axis key {key!r} names a table, not a key: give section.key", key)
    return parts


def set_key(data: dict[str, Any], key: str, value: Any) -> None:
    """Sets the scene key ``key`` (dotted, list entries by index) of the TOML data ``data`` to ``value``,
    making the tables on the way; the schema checks the result."""
    parts = _path(key)
    node: Any = data
    for i, part in enumerate(parts[:-1]):
        nxt = parts[i + 1]
        if isinstance(part, int):
            if not isinstance(node, list) or part >= len(node):
                have = len(node) if isinstance(node, list) else 0
                raise SceneError(f"scene key {key!r}: entry {part} does not exist (the scene has {have})", key)
            node = node[part]
        else:
            if not isinstance(node, dict):
                raise SceneError(f"scene key {key!r}: {'.'.join(map(str, parts[:i]))} is not a table", key)
            if part not in node:
                node[part] = [] if isinstance(nxt, int) else {}
            node = node[part]
    last = parts[-1]
    if not isinstance(node, dict):
        raise SceneError(f"scene key {key!r}: {'.'.join(map(str, parts[:-1]))} is not a table", key)
    if isinstance(last, int):
        raise SceneError(f"scene key {key!r} does not name a value of a table", key)
    node[last] = value


# ----- cases -----
def _grid(axes: Mapping[str, Sequence[Any]], zipped: Mapping[str, Sequence[Any]]) -> tuple[int, list[str]]:
    """Checks the axes; returns the number of cases and the axis names in table order."""
    names = list(axes) + list(zipped)
    for name, values in [*axes.items(), *zipped.items()]:
        if isinstance(values, (str, bytes)) or not isinstance(values, Sequence):
            raise SweepError(f"axis {name!r} must be a list of values, got {values!r}", name)
        if len(values) == 0:
            raise SweepError(f"axis {name!r} has no values", name)
    if set(axes) & set(zipped):
        both = sorted(set(axes) & set(zipped))[0]
        raise SweepError(f"axis {both!r} is given both as a product axis and as a zipped one", both)
    lengths = {name: len(v) for name, v in zipped.items()}
    if len(set(lengths.values())) > 1:
        raise SweepError(f"zipped axes must have equal lengths, got {lengths}", next(iter(zipped)))
    n = math.prod(len(v) for v in axes.values()) * (next(iter(lengths.values())) if lengths else 1)
    if n > MAX_CASES:
        raise SweepError(f"the sweep has {n} cases, more than the limit of {MAX_CASES}")
    return n, names


def _combinations(axes: Mapping[str, Sequence[Any]], zipped: Mapping[str, Sequence[Any]]) -> Iterator[dict[str, Any]]:
    """The axis values of every case: the product of ``axes`` and of the zipped group (last, fastest)."""
    factors: list[list[dict[str, Any]]] = [[{name: v} for v in values] for name, values in axes.items()]
    if zipped:
        columns = list(zipped.items())
        factors.append([{name: values[i] for name, values in columns} for i in range(len(columns[0][1]))])
    for combo in itertools.product(*factors):
        values: dict[str, Any] = {}
        for part in combo:
            values.update(part)
        yield values


def _file_digests(data: Mapping[str, Any], base_dir: Path) -> dict[str, str]:
    """The sha256 of every mesh file the scene reads (``body.mesh``, ``bodies[k].mesh``)."""
    bodies = [data.get("body", {})] + list(data.get("bodies", []) if isinstance(data.get("bodies"), list) else [])
    out = {}
    for body in bodies:
        name = body.get("mesh") if isinstance(body, dict) else None
        if isinstance(name, str):
            path = base_dir / name
            try:
                out[name] = hashlib.sha256(path.read_bytes()).hexdigest()
            except OSError as e:
                raise SceneError(f"cannot read the mesh file {path}: {e.strerror}", "body.mesh") from e
    return out


def case_key(data: Mapping[str, Any], base_dir: Path) -> str:
    """The hash that names a case: its checked scene (title and description left out, defaults and number
    spellings normalized by the schema), the digests of the mesh files it reads, and the tribo version."""
    scene = parse_scene(data, base_dir=base_dir).to_dict()
    scene.pop("title", None)
    scene.pop("description", None)
    canonical = json.dumps(
        {"scene": scene, "files": _file_digests(data, base_dir), "tribo": __version__}, sort_keys=True, default=str
    )
    return hashlib.sha256(canonical.encode()).hexdigest()[:16]


def cases(
    data: Mapping[str, Any],
    axes: Mapping[str, Sequence[Any]],
    zipped: Mapping[str, Sequence[Any]] | None = None,
    base_dir: Path | None = None,
) -> list[Case]:
    """Every distinct case of a sweep of the scene ``data`` (TOML data), each checked by the scene schema: a
    bad key or value raises ``SceneError`` naming the key (and the case) before anything runs. Values that
    make one checked scene (``0.1``, ``1e-1``, ``0.10``) are one case, run once (defect D33)."""
    zipped = dict(zipped or {})
    base_dir = base_dir if base_dir is not None else Path.cwd()
    _grid(axes, zipped)
    out: list[Case] = []
    seen: set[str] = set()
    for values in _combinations(axes, zipped):
        case = deepcopy(dict(data))
        for key, value in values.items():
            set_key(case, key, value)
        try:
            key = case_key(case, base_dir)
        except SceneError as e:
            e.add_note("in the sweep case " + ", ".join(f"{k} = {v!r}" for k, v in values.items()))
            raise
        if key not in seen:
            seen.add(key)
            out.append(Case(len(out), values, case, key))
    return out


# ----- one case, on a worker -----
def _oscillation(solution: Any) -> float:
    """TV(λ_n) over the multiplier dofs in abscissa order / (2 max λ_n): 1 for a single smooth hump, more for a
    pressure that oscillates (a checkerboard); NaN when nothing presses; the largest of the contact pairs'."""
    parts = [solution.pair(k) for k in range(max(len(solution.pairs), 1))]
    lams = [part.lambda_n[np.argsort(part.multiplier_abscissae)] for part in parts]
    values = [float(np.abs(np.diff(lam)).sum() / (2.0 * lam.max())) for lam in lams if len(lam) and lam.max() > 0.0]
    return max(values, default=math.nan)


def _row(summary: Mapping[str, Any], solution: Any) -> dict[str, Any]:
    """The row of a run from its summary and solution."""
    est = summary["estimate"]
    failure = summary["failure"]["reason"] if summary["failure"] else ""
    states = solution.states
    return {
        "status": summary["status"],
        "adapt_stop": summary.get("adapt_stop") or "",
        "adapt_handed_back": bool(summary.get("adapt_handed_back")),
        "failure": failure,
        "friction": summary["friction"],
        "formulation": summary["formulation"],
        "iterations": summary["iterations"],
        "coulomb_method": summary["coulomb_method"] or "",
        "coulomb_check": (summary.get("coulomb_check") or {}).get("agreement", ""),
        "normal_force": summary["normal_force"],
        "tangential_force": summary["tangential_force"],
        "contact_extent": solution.extent(states != 0),
        "stick_extent": solution.extent(states == 1),
        "kkt_max": summary["kkt_max"],
        "lambda_n_oscillation": _oscillation(solution),
        "unknowns": summary["n_free"],
        "multipliers": summary["n_multipliers"],
        "traction_estimate": est.get("traction_relative"),
        "traction_hierarchical": est.get("traction_hierarchical_relative"),
        "energy_estimate": est.get("energy_relative"),
        "warnings": " | ".join(summary["warnings"]),
    }


def run_case(
    data: dict[str, Any], base_dir: str, case_dir: str, files: bool = False, plots: bool = False, threads: int = 1
) -> dict[str, Any]:
    """Runs one case (on a worker): ``run_scene`` into ``case_dir`` (``summary.json``; the fields and plots
    with ``files``). Returns ``{"row": …, "summary": …}``; a failure is a row with status ``error``."""
    # faer's parallel factorizations use rayon's global pool, sized from this on the first solve of the process.
    os.environ.setdefault("RAYON_NUM_THREADS", str(threads))

    out = Path(case_dir)
    clock = time.perf_counter()
    try:
        out.mkdir(parents=True, exist_ok=True)
        with (out / "attempts").open("a", encoding="utf-8") as f:
            f.write(f"{socket.gethostname()} {os.getpid()}\n")
    except OSError:
        pass  # no shared filesystem: the attempts are not counted
    try:
        scene = parse_scene(data, base_dir=Path(base_dir))
        with contextlib.redirect_stderr(io.StringIO()):  # the run's warnings go into its row, not the terminal
            _, solution, _ = run_scene(scene, out, plots=plots, fields=files)
        summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
        row = _row(summary, solution)
    except TriboError as e:
        summary = None
        notes = "; ".join(getattr(e, "__notes__", []))
        row = {"status": "error", "failure": f"{type(e).__name__}: {e}" + (f" ({notes})" if notes else "")}
    except OSError as e:
        summary = None
        row = {"status": "error", "failure": f"cannot write the case's outputs into {out}: {e}"}
    row["seconds"] = time.perf_counter() - clock
    return {"row": row, "summary": summary}


def run_cases(cases_args: list[tuple[Any, ...]]) -> list[dict[str, Any]]:
    """Runs a batch of cases (on one worker, one after the other): ``run_case`` of each argument tuple."""
    return [run_case(*args) for args in cases_args]


def _batches(cases_: list[Case], workers: int) -> list[list[Case]]:
    """The cases in batches, one Dask task each: about 8 per worker, so that Dask's cost per task (about 2 ms)
    is paid once per batch and the load stays balanced; one case per batch when there are few cases."""
    size = max(1, math.ceil(len(cases_) / (8 * workers)))
    return [cases_[i : i + size] for i in range(0, len(cases_), size)]


# ----- the sweep -----
def _scene_data(scene: str | Path | Mapping[str, Any], base_dir: Path | None) -> tuple[dict[str, Any], Path]:
    if isinstance(scene, Mapping):
        return deepcopy(dict(scene)), (base_dir if base_dir is not None else Path.cwd())
    path = Path(scene)
    data = read_scene_data(path)
    return data, path.resolve().parent


def _imports() -> Any:
    try:
        import distributed
        import pandas  # noqa: F401
        import pyarrow  # noqa: F401
    except ImportError as e:
        raise SweepError(
            f"sweeps need the 'sweep' extra ({e.name} is not installed): pip install \"tribo[sweep]\""
        ) from e
    return distributed


def _cores() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1


def _cell(value: Any) -> Any:
    """An axis value as a table cell: numbers, strings and booleans as they are, anything else as JSON."""
    return value if isinstance(value, (int, float, str, bool)) else json.dumps(value)


def _table(done: Mapping[int, dict[str, Any]], all_cases: Sequence[Case], names: Sequence[str]) -> pd.DataFrame:
    import pandas as pd

    rows = []
    for case in all_cases:
        if case.index in done:
            rows.append({**{k: _cell(case.values[k]) for k in names}, "case": case.key, **done[case.index]})
    columns = [*names, *COLUMNS]
    return pd.DataFrame(rows, columns=columns)


def _write_table(out: Path, df: pd.DataFrame) -> None:
    df.to_parquet(out / "results.parquet", index=False)
    df.to_csv(out / "results.csv", index=False)


def _attempts_recorded(case_dir: Path) -> int:
    """The starts of a case recorded in this run (0 when none, or without a shared filesystem)."""
    try:
        return len((case_dir / "attempts").read_text(encoding="utf-8").splitlines())
    except OSError:
        return 0


def _finish(case_dir: Path, result: Mapping[str, Any]) -> dict[str, Any]:
    """Writes a finished case's cache marker (and its summary, when the worker's filesystem is not ours)."""
    row = dict(result["row"])
    row["attempts"] = max(1, _attempts_recorded(case_dir))
    case_dir.mkdir(parents=True, exist_ok=True)
    if result["summary"] is not None and not (case_dir / "summary.json").exists():
        write_text_atomic(case_dir / "summary.json", json.dumps(result["summary"], indent=2) + "\n")
    if row["status"] not in ("killed_worker", "internal_error"):  # these may not happen again: not cached
        write_text_atomic(case_dir / "row.json", json.dumps(row, default=str) + "\n")
    return row


def sweep(
    scene: str | Path | Mapping[str, Any],
    axes: Mapping[str, Sequence[Any]] | None = None,
    *,
    out: str | Path,
    zipped: Mapping[str, Sequence[Any]] | None = None,
    client: Client | str | None = None,
    workers: int | None = None,
    threads: int = 1,
    files: bool = False,
    plots: bool = False,
    base_dir: Path | None = None,
    progress: bool | Callable[[int, int], object] = True,
) -> pd.DataFrame:
    """Runs every case of a sweep of ``scene`` (a TOML file, or its data as a dict) over ``axes`` (scene key
    → values; the product) and ``zipped`` (axes that move together) on Dask; returns the table (one row
    per case, in case order) and writes it to ``out/results.parquet`` and ``out/results.csv``.

    ``client``: a ``distributed.Client`` or a scheduler address (``"tcp://host:port"``); by default a
    ``LocalCluster`` of ``workers`` processes (cores // threads) is started and closed. ``threads``: threads
    per solve. ``files``: write each case's CSV and VTU files (and, with ``plots``, its PNGs) beside its
    summary. ``progress``: a bar over cases (True), none (False), or a callback ``(done, total)``. Cases
    whose ``out/cases/<hash>/row.json`` exists are not run again."""
    distributed = _imports()
    if not (isinstance(threads, int) and threads >= 1):
        raise SweepError(f"threads per solve must be a positive integer, got {threads!r}", "threads")
    if workers is not None and not (isinstance(workers, int) and workers >= 1):
        raise SweepError(f"workers must be a positive integer, got {workers!r}", "workers")
    data, base = _scene_data(scene, base_dir)
    axes, zipped = dict(axes or {}), dict(zipped or {})
    _, names = _grid(axes, zipped)
    all_cases = cases(data, axes, zipped, base)
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise SweepError(f"out {out} exists and is not a directory", "out")
    (out / "cases").mkdir(parents=True, exist_ok=True)
    done: dict[int, dict[str, Any]] = {}
    for case in all_cases:
        cached = out / "cases" / case.key / "row.json"
        if cached.is_file():
            try:
                done[case.index] = json.loads(cached.read_text(encoding="utf-8"))
            except (OSError, ValueError):
                pass  # a damaged marker: run the case again
    todo = [c for c in all_cases if c.index not in done]
    log.info("sweep: %d cases, %d cached, %d to run", len(all_cases), len(done), len(todo))
    try:
        if todo:
            _run(distributed, todo, done, len(all_cases), out, base, client, workers, threads, files, plots, progress)
    finally:  # also on Ctrl-C: the table of what is done
        df = _table(done, all_cases, names)
        _write_table(out, df)
    return df


def _run(
    distributed: Any, todo: Sequence[Case], done: dict[int, dict[str, Any]], total: int, out: Path, base: Path,
    client: Any, workers: int | None, threads: int, files: bool, plots: bool,
    progress: bool | Callable[[int, int], object],
) -> None:
    """Runs ``todo`` on Dask, filling ``done``; on Ctrl-C, writes nothing more and re-raises."""
    from tqdm import tqdm

    cluster = None
    own_client = not isinstance(client, distributed.Client)
    if client is None:
        n = workers if workers is not None else max(1, _cores() // threads)
        cluster = distributed.LocalCluster(
            n_workers=n, threads_per_worker=1, processes=True, dashboard_address=":0",
            silence_logs=logging.ERROR, env={"RAYON_NUM_THREADS": str(threads)},
        )
        client = distributed.Client(cluster)
    elif isinstance(client, str):
        try:
            client = distributed.Client(client, timeout="10s")
        except (OSError, TimeoutError) as e:
            raise SweepError(f"cannot reach the Dask scheduler at {client}: {e}", "scheduler") from e
    try:
        link = getattr(client, "dashboard_link", None)
        # A local cluster serves its dashboard only where bokeh is installed; a remote one says for itself.
        if link and (cluster is None or importlib.util.find_spec("bokeh") is not None):
            log.info("Dask dashboard: %s", link)
        for case in todo:
            (out / "cases" / case.key / "attempts").unlink(missing_ok=True)  # count this run's starts only
        n_workers = max(1, len(client.scheduler_info().get("workers", {})))
        ac = distributed.as_completed()
        futures: dict[Any, list[Case]] = {}
        innocent: dict[int, int] = {}
        serial = itertools.count()

        def submit(batch: list[Case]) -> None:
            # A key of its own per submission: Dask would hand back the erred task of a reused key.
            args = [(c.data, str(base), str((out / "cases" / c.key).resolve()), files, plots, threads) for c in batch]
            key = f"tribo-cases-{batch[0].key}-{len(batch)}-{next(serial)}"
            future = client.submit(run_cases, args, key=key, pure=False)
            futures[future] = batch
            ac.add(future)

        for batch in _batches(list(todo), n_workers):
            submit(batch)
        bar = tqdm(total=total, initial=total - len(todo), desc="cases", unit="case",
                   disable=progress is not True)
        try:
            for future in ac:
                # Released once read: Dask recomputes the results it still holds on a worker that dies.
                batch = futures.pop(future)
                try:
                    results = future.result()
                except distributed.KilledWorker as e:
                    if len(batch) > 1:  # one of them kills workers: run each alone, so that only it is marked
                        for case in batch:
                            submit([case])
                        continue
                    # Dask counts a death against every task the worker held, started or queued: a case that
                    # never started (no attempt recorded) only waited behind the one that kills workers, and
                    # runs again (a few times at most: without a shared filesystem no start is recorded).
                    case = batch[0]
                    innocent[case.index] = innocent.get(case.index, 0) + 1
                    if _attempts_recorded(out / "cases" / case.key) == 0 and innocent[case.index] <= 3:
                        submit([case])
                        continue
                    results = [{"row": {"status": "killed_worker", "failure": f"the case killed every worker that "
                                        f"tried it ({e})", "seconds": math.nan}, "summary": None}]
                except Exception as e:  # noqa: BLE001 - a bug in one case must not end the sweep
                    results = [{"row": {"status": "internal_error", "failure": f"{type(e).__name__}: {e}",
                                        "seconds": math.nan}, "summary": None}] * len(batch)
                future.release()
                for case, result in zip(batch, results):
                    done[case.index] = _finish(out / "cases" / case.key, result)
                bar.update(len(batch))
                if callable(progress):
                    progress(len(done), total)
        except KeyboardInterrupt:
            client.cancel(list(futures))
            raise
        finally:
            bar.close()
    finally:
        if own_client:
            client.close()
        if cluster is not None:
            cluster.close()
