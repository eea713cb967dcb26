"""Study 17 — the peak memory of one large solve from Python against the same solve from Rust.

Issue 37 asked that a Python solve of 1M unknowns peak within 1.1 times the Rust one. Both sides solve the
uniform Hertz block of the cost study (``python/tribo/scenes/hertz.toml``: (−2, 2) × (−2, 0), NX × NX/2 cells,
right diagonals, rigid cylinder R = 1 pushed δ = 0.01, Coulomb μ = 0.3 with an obstacle shift s = 0.004, P1
multipliers on the FE edges), each in a process of its own so that each peak resident memory (Linux's VmHWM)
is its own: Rust through ``cargo run --release -p tribo --example scale -- NX`` (the system allocator), Python
through ``tribo.Problem(...).solve(mu=0.3)``, once as ``import tribo`` sets mimalloc up and once for each other
purge delay in ``PURGE_DELAYS`` (``MIMALLOC_PURGE_DELAY`` set by hand: -1 never returns freed pages, which was
the setting before this study).

    python scripts/study_python_memory.py            # NX = 1000: docs/python_memory.{md,csv}
    python scripts/study_python_memory.py --smoke --out /tmp/x   # NX = 40, the Rust row only if its example is built
"""

from __future__ import annotations

import json
import math
import os
import re
import subprocess
import sys
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
import studylib as sl  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "target" / "release" / "examples" / "scale"
PURGE_DELAYS = ("-1", "0")  # besides the shipped setting: never purge (the former one), purge at once
HEADERS = ["run", "allocator", "unknowns", "status", "problem_seconds", "solve_seconds", "peak_mb",
           "kb_per_unknown", "peak_over_rust"]

# The Python side of one run: the same scene, phases and VmHWM as crates/tribo/examples/scale.rs.
CHILD = """
import json, sys, time
import tribo

def peak_mb():
    with open("/proc/self/status") as f:
        return next(int(l.split()[1]) / 1024 for l in f if l.startswith("VmHWM"))

nx = int(sys.argv[1])
mesh = tribo.Mesh.rectangle((-2.0, 2.0), (-2.0, 0.0), nx, nx // 2, diagonal="right")
t = time.perf_counter()
problem = tribo.Problem(mesh, young=200.0, poisson=0.3, clamped="bottom", contact="top",
                        obstacle=tribo.Obstacle.circle(1.0), approach=0.01, shift=0.004, multiplier_ratio=1.0)
t_problem = time.perf_counter() - t
t = time.perf_counter()
solution = problem.solve(mu=0.3)
t_solve = time.perf_counter() - t
print(json.dumps(dict(unknowns=problem.n_free, status=solution.report.status, problem_seconds=t_problem,
                      solve_seconds=t_solve, peak_mb=peak_mb())))
"""


def rust_run(nx: int, build: bool) -> dict[str, Any] | None:
    """The Rust example's numbers: `Problem::new` and solve times, the peak before its reference Cholesky.
    Without ``build`` (the smoke run), the example already built, or None (a release build takes minutes)."""
    if build:
        command = ["cargo", "run", "--release", "-q", "-p", "tribo", "--example", "scale", "--", str(nx)]
    elif EXAMPLE.is_file():
        command = [str(EXAMPLE), str(nx)]
    else:
        return None
    out = subprocess.run(command, cwd=ROOT, check=True, capture_output=True, text=True).stdout
    number = r"\s+([0-9.]+)"
    peak = re.search(r"peak ([0-9.]+) MB = ", out)
    unknowns = re.search(r"unknowns (\d+), multipliers \d+, status (\w+)", out)
    problem, solve = re.search(r"Problem::new" + number, out), re.search(r"\nsolve" + number, out)
    if not (peak and unknowns and problem and solve):
        raise RuntimeError(f"the scale example printed something this study does not read:\n{out}")
    return dict(run="Rust (crates/tribo/examples/scale.rs)", allocator="system", unknowns=int(unknowns[1]),
                status=unknowns[2], problem_seconds=float(problem[1]), solve_seconds=float(solve[1]),
                peak_mb=float(peak[1]))


def python_run(nx: int, purge_delay: str | None) -> dict[str, Any]:
    env = dict(os.environ)
    env.pop("MIMALLOC_PURGE_DELAY", None)
    if purge_delay is not None:
        env["MIMALLOC_PURGE_DELAY"] = purge_delay
    out = subprocess.run([sys.executable, "-c", CHILD, str(nx)], env=env, check=True, capture_output=True,
                         text=True).stdout
    row: dict[str, Any] = json.loads(out.strip().splitlines()[-1])
    shipped = purge_delay is None
    row["run"] = "Python, as shipped" if shipped else f"Python, MIMALLOC_PURGE_DELAY={purge_delay}"
    row["allocator"] = "mimalloc"
    return row


def shipped() -> tuple[str, float]:
    """The purge delay `import tribo` sets when the user has not set one, and the peak MB of that import."""
    env = {k: v for k, v in os.environ.items() if k != "MIMALLOC_PURGE_DELAY"}
    code = ("import os, tribo\nwith open('/proc/self/status') as f:\n"
            "    mb = next(int(l.split()[1]) / 1024 for l in f if l.startswith('VmHWM'))\n"
            "print(os.environ['MIMALLOC_PURGE_DELAY'], mb)")
    delay, mb = subprocess.run([sys.executable, "-c", code], env=env, check=True, capture_output=True,
                               text=True).stdout.split()
    return delay, float(mb)


def run(smoke: bool, out: Path) -> list[dict[str, Any]]:
    nx = 40 if smoke else 1000
    rust = rust_run(nx, build=not smoke)
    rows = ([rust] if rust else []) + [python_run(nx, None)] + [python_run(nx, d) for d in PURGE_DELAYS]
    for r in rows:
        r["kb_per_unknown"] = r["peak_mb"] * 1024 / r["unknowns"]
        r["peak_over_rust"] = r["peak_mb"] / rust["peak_mb"] if rust else math.nan
    delay, imported = shipped()
    out.mkdir(parents=True, exist_ok=True)
    sl.write_csv(out / "python_memory.csv", HEADERS, [[r[h] for h in HEADERS] for r in rows])
    table = sl.markdown_table(
        ["run", "allocator", "unknowns", "status", "Problem (s)", "solve (s)", "peak MB", "kB per unknown",
         "peak / Rust's"],
        [[r[h] for h in HEADERS] for r in rows])
    sl.write_page(
        out / "python_memory.md", "Study 17: the peak memory of a large solve, Python against Rust", __doc__,
        f"Regenerate with `python scripts/study_python_memory.py` (NX = {nx}; one run of each; `import tribo` "
        f"sets `MIMALLOC_PURGE_DELAY={delay}` unless the user set it). `import tribo` alone (the interpreter, "
        f"numpy and the module) peaks at {imported:.0f} MB.", table)
    return rows


def main(argv: list[str] | None = None) -> Any:
    return sl.cli(run, __doc__, argv)


if __name__ == "__main__":
    main()
