"""Study 8b — two-body Hertz against a converged two-body reference: the mesh's error apart from the model's.

Study 8 measures λ_n against plane-strain Hertz, whose half-spaces the finite blocks only approximate
(the upper block is 1 thick, the contact half-width about 0.075); its error levels off near 0.8 %. Here the
same two-body problems (study 8's blocks and supports, frictionless, graded at growth 0.15 toward
[−0.15, 0.15] with h_min from 0.02 to 0.000625) are also measured against a converged solution of the
*same* finite blocks: both bodies graded toward [−0.1, 0.1] at growth 0.03 with h_max 0.05 and h_min
0.0003125 (studylib.REFERENCE, the one-body studies' reference, on each body). Per pair (equal:
E 200, ν 0.3 on both; dissimilar: E 200, ν 0.3 under E 70, ν 0.33):

* ``reference_l2``: relative L2 error of λ_n against the reference's λ_n (the discretization error);
* ``hertz_l2``: against the Hertz pressure of the computed force (discretization and model);
* the reference's own distance to Hertz (the model error of the finite blocks, to the reference's error).

    python scripts/study_two_body_reference.py            # docs/two_body_reference.{md,csv}
    python scripts/study_two_body_reference.py --smoke --out /tmp/x
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import studylib as sl  # noqa: E402

import tribo  # noqa: E402

LOWER = (200.0, 0.3)
PAIRS = {"equal": (200.0, 0.3), "dissimilar": (70.0, 0.33)}
DELTA = 0.01
MESHES = [0.02, 0.01, 0.005, 0.0025, 0.00125, 0.000625]
STUDY = dict(half=0.15, h_max=0.5, growth=0.15)


def pair_problem(upper: tuple[float, float], h_min: float, half: float, h_max: float, growth: float) -> tribo.Problem:
    """Study 8's two-body Hertz (``tribo_testkit::two_body_hertz``, hold_top false) on the given grading."""
    def mesh(y: tuple[float, float], side: str) -> tribo.Mesh:
        return tribo.Mesh.graded_rectangle((-2.0, 2.0), y, side=side, segment=(-half, half), h_max=h_max,
                                           h_min=h_min, growth=growth)

    lower = tribo.Body("lower", mesh((-2.0, 0.0), "top"), *LOWER, clamped="bottom")
    upper_body = tribo.Body("upper", mesh((0.0, 1.0), "bottom"), *upper,
                            supports=[tribo.Support.displacement("top", y=-DELTA),
                                      tribo.Support.displacement("left", x=0.0)])
    return tribo.Problem.two_bodies(lower, upper_body, secondary="lower.top", primary="upper.bottom",
                                    gap=tribo.Obstacle.parabola(1.0))


def combined_modulus(upper: tuple[float, float]) -> float:
    return 1.0 / sum((1.0 - nu**2) / e for e, nu in (LOWER, upper))


def l2(lam: np.ndarray, ref: np.ndarray, w: np.ndarray) -> float:
    """Relative L2 distance of ``lam`` to ``ref`` by the quadrature weights ``w``."""
    return float(np.sqrt(np.sum(w * (lam - ref) ** 2) / np.sum(w * ref**2)))


def quadrature(p: tribo.Problem, ref: tribo.Problem, a: float) -> tuple[np.ndarray, np.ndarray]:
    """Gauss points and weights on the union of both T_H and the Hertz edges ±a (P1 λ is linear between)."""
    breaks = np.unique(np.concatenate([p.multiplier_mesh, ref.multiplier_mesh, [-a, a]]))
    return sl._gauss_points(breaks)


def hertz(force: float, e_star: float) -> tuple[Any, float]:
    a = math.sqrt(4.0 * force * 1.0 / (math.pi * e_star))
    p0 = 2.0 * force / (math.pi * a)
    return (lambda x: p0 * np.sqrt(np.clip(1.0 - (x / a) ** 2, 0.0, None))), a


def run(smoke: bool, out: Path) -> list[dict[str, Any]]:
    spec = sl.SMOKE_REFERENCE if smoke else sl.REFERENCE
    meshes = [0.04, 0.02] if smoke else MESHES
    rows: list[dict[str, Any]] = []
    for pair, upper in PAIRS.items():
        clock = time.perf_counter()
        ref = pair_problem(upper, spec["h_min"], spec["half"], spec["h_max"], spec["growth"])
        ref_sol = ref.solve()
        ref_seconds = time.perf_counter() - clock
        assert ref_sol.report.status == "converged", ref_sol.report.status
        pressure, a = hertz(ref_sol.normal_force, combined_modulus(upper))
        x, w = quadrature(ref, ref, a)
        ref_lam = ref.evaluate_multiplier(ref_sol.lambda_n, x)
        ref_hertz = l2(ref_lam, pressure(x), w)
        rows.append(dict(pair=pair, h_min=spec["h_min"], n_free=ref.n_free, force=ref_sol.normal_force,
                         reference_l2=0.0, hertz_l2=ref_hertz, seconds=ref_seconds, reference=True))
        for h_min in meshes:
            p = pair_problem(upper, h_min, **STUDY)  # type: ignore[arg-type]
            sol = p.solve()
            pressure, a = hertz(sol.normal_force, combined_modulus(upper))
            x, w = quadrature(p, ref, a)
            lam = p.evaluate_multiplier(sol.lambda_n, x)
            rows.append(dict(pair=pair, h_min=h_min, n_free=p.n_free, force=sol.normal_force,
                             reference_l2=l2(lam, ref.evaluate_multiplier(ref_sol.lambda_n, x), w),
                             hertz_l2=l2(lam, pressure(x), w), seconds=math.nan, reference=False))
    write(rows, out)
    return rows


def write(rows: list[dict[str, Any]], out: Path) -> None:
    headers = ["pair", "reference", "h_min", "n_free", "force", "reference_l2", "hertz_l2", "seconds"]
    table = [[r[k] for k in headers] for r in rows]
    out.mkdir(parents=True, exist_ok=True)
    sl.write_csv(out / "two_body_reference.csv", headers, table)
    lines = ["# Two-body Hertz against a converged two-body reference", "",
             "Written by `python scripts/study_two_body_reference.py` (see its docstring). The first row of each pair",
             "is the reference itself: its `hertz_l2` is the model error of the finite blocks (to its own error).", "",
             sl.markdown_table(headers, table), ""]
    for pair in PAIRS:
        rs = [r for r in rows if r["pair"] == pair and not r["reference"]]
        rate = sl.fitted_rate([r["h_min"] for r in rs], [r["reference_l2"] for r in rs])
        model = next(r["hertz_l2"] for r in rows if r["pair"] == pair and r["reference"])
        lines.append(f"* {pair}: against the reference, λ_n converges like h_min^{rate:.2f} "
                     f"({100 * rs[0]['reference_l2']:.2f} % → {100 * rs[-1]['reference_l2']:.2f} %); "
                     f"the reference is {100 * model:.2f} % off Hertz.")
    (out / "two_body_reference.md").write_text("\n".join(lines) + "\n", encoding="utf-8")


def main(argv: list[str] | None = None) -> list[dict[str, Any]]:
    return sl.cli(run, __doc__, argv)  # type: ignore[no-any-return]


if __name__ == "__main__":
    main()
