"""Study 18 — the memory of long loading histories, measured against the estimate their budget is checked on.

Issue 37 (D21) asked that a long history cost what its data costs and that the estimate the memory budget is
checked against (``tribo::History::estimated_bytes``: the solutions kept, and per step its record, its step
and the series a reader takes) lie within 1.5 times the measured peak. A cylinder (R = 1, δ = 0.01) is
pressed into a 16 × 8 block (1 × 0.5, E = 1, ν = 0.3: 272 unknowns, 17 multiplier dofs) and dragged by
Coulomb friction (μ = 0.3) through N shift steps from 0 to 0.002, keeping every 1000th solution
(``keep_every``). Each N runs in a process of its own; the peak is the growth of the resident memory
(Linux's VmHWM) over its value before the history, the history's arrays handed to Python included. The
estimate is read, in another process, from the memory-budget refusal of the same history under a 1 MiB budget.

    python scripts/study_history_memory.py            # N = 10k, 30k, 100k, 300k: docs/history_memory.{md,csv}
    python scripts/study_history_memory.py --smoke --out /tmp/x
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
import studylib as sl  # noqa: E402

HEADERS = ["steps", "unknowns", "multipliers", "status", "seconds", "before_mb", "peak_mb", "growth_mb",
           "estimate_mb", "growth_per_step_bytes", "estimate_per_step_bytes", "growth_over_estimate"]
KEEP_EVERY = 1000

CHILD = """
import json, sys, time
import numpy as np
import tribo

def mb(key):
    with open("/proc/self/status") as f:
        return next(int(l.split()[1]) / 1024 for l in f if l.startswith(key))

n, keep = int(sys.argv[1]), int(sys.argv[2])
mesh = tribo.Mesh.rectangle((0.0, 1.0), (0.0, 0.5), 16, 8)
problem = tribo.Problem(mesh, young=1.0, poisson=0.3, clamped="bottom", contact="top",
                        obstacle=tribo.Obstacle.circle(1.0, center=0.5), approach=0.01)
shift = np.linspace(0.0, 0.002, n)
if sys.argv[3] == "estimate":
    try:
        problem.solve_history(shift=shift, mu=0.3, keep_every=keep, memory_budget=1 << 20)
        raise SystemExit("the history fitted a 1 MiB budget")
    except tribo.TriboError as e:
        print(json.dumps(dict(estimate_mb=e.details["needed"] / 2**20)))
        raise SystemExit(0)
problem.solve(mu=0.3)  # the factorization, made before the peak is read, as the history reuses it
before = mb("VmHWM")
t = time.perf_counter()
h = problem.solve_history(shift=shift, mu=0.3, keep_every=keep)
seconds = time.perf_counter() - t
print(json.dumps(dict(steps=n, unknowns=problem.n_free, multipliers=problem.n_multipliers, status=h.status,
                      seconds=seconds, before_mb=before, peak_mb=mb("VmHWM"))))
"""


def child(n: int, what: str) -> dict[str, Any]:
    out = subprocess.run([sys.executable, "-c", CHILD, str(n), str(KEEP_EVERY), what], check=True,
                         capture_output=True, text=True).stdout
    row: dict[str, Any] = json.loads(out.strip().splitlines()[-1])
    return row


def one(n: int) -> dict[str, Any]:
    """The history of n steps measured in one process, its estimate read in another."""
    r = {**child(n, "run"), **child(n, "estimate")}
    r["growth_mb"] = r["peak_mb"] - r["before_mb"]
    r["growth_per_step_bytes"] = r["growth_mb"] * 2**20 / n
    r["estimate_per_step_bytes"] = r["estimate_mb"] * 2**20 / n
    r["growth_over_estimate"] = r["growth_mb"] / r["estimate_mb"]
    return r


def run(smoke: bool, out: Path) -> list[dict[str, Any]]:
    rows = [one(n) for n in ([4000, 8000] if smoke else [10_000, 30_000, 100_000, 300_000])]
    out.mkdir(parents=True, exist_ok=True)
    sl.write_csv(out / "history_memory.csv", HEADERS, [[r[h] for h in HEADERS] for r in rows])
    table = sl.markdown_table(
        ["steps", "status", "seconds", "memory before (MB)", "peak (MB)", "growth (MB)", "estimate (MB)",
         "growth per step (B)", "estimate per step (B)", "growth / estimate"],
        [[r["steps"], r["status"], r["seconds"], r["before_mb"], r["peak_mb"], r["growth_mb"], r["estimate_mb"],
          r["growth_per_step_bytes"], r["estimate_per_step_bytes"], r["growth_over_estimate"]] for r in rows])
    ratios = [r["growth_over_estimate"] for r in rows]
    sl.write_page(
        out / "history_memory.md", "Study 18: the memory of long loading histories", __doc__,
        f"Regenerate with `python scripts/study_history_memory.py` ({rows[0]['unknowns']} unknowns, "
        f"{rows[0]['multipliers']} multipliers, keep_every = {KEEP_EVERY}; one run each). The measured growth is "
        f"{min(ratios):.2f}–{max(ratios):.2f} times the estimate.", table)
    return rows


def main(argv: list[str] | None = None) -> Any:
    return sl.cli(run, __doc__, argv)


if __name__ == "__main__":
    main()
