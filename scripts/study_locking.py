"""Study 25 — locking: Hertz as ν → ½, P1 displacements against the mixed displacement–pressure formulation.

Issue 41 asks for a locking-free option: λ_n within 2 % of Hertz at ν = 0.499 and 0.4999 on the meshes where P1
displacements are within 0.7 % at ν = 0.3, its rate under refinement and its cost at most 2.5 times the P1 solve
of the same mesh. The Hertz scene (a rigid cylinder R = 1 pushed δ = 0.01 into the block (−2, 2) × (−2, 0),
clamped at the bottom, frictionless, E = 200) is solved on meshes graded toward [−0.3, 0.3] at growth 0.05
(h_max = 0.1) for h_min = 0.01 … 0.000625, at ν from 0.3 to 0.4999, with `formulation="displacement"` (P1) and
`formulation="mixed"` (`tribo::fem::mixed`: P1 displacements and pressures, MINI's bubble condensed). Each
solve's λ_n is measured against the plane-strain Hertz pressure of its own force (E* = E / (1 − ν²)), in
relative L², and timed (the solve: the factorization and the QPs; building the problem apart; each the fastest
of five runs on a fresh problem, each after an untimed one, in five passes over all cases so that a slow spell
of this shared machine does not fall on every run of one case).

    python scripts/study_locking.py            # docs/locking.{csv,md,png}
    python scripts/study_locking.py --smoke --out /tmp/x
    python scripts/study_locking.py --page-from docs/locking.csv --out /tmp/x   # the page and chart alone
    python scripts/study_locking.py --memory   # docs/locking_memory.csv: peak RSS, finest mesh, ν = 0.4999

What is left out: the finite block's share of the force (the same for both formulations); memory (the mixed
factor holds about 1.5 times the unknowns, measured apart with --memory); axisymmetry and two bodies (their
mixed formulation is measured in crates/tribo/tests/integration/axisymmetric_mixed.rs and mixed.rs).
"""

from __future__ import annotations

import math
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import studylib as sl  # noqa: E402

import tribo  # noqa: E402

POISSONS = [0.3, 0.4, 0.45, 0.47, 0.49, 0.499, 0.4999]
H_MINS = [0.01, 0.005, 0.0025, 0.00125, 0.000625]
FORMULATIONS = ("displacement", "mixed")
PASSES = 5


def mesh(h_min: float) -> tribo.Mesh:
    return sl.graded_mesh(h_min, h_max=0.1, growth=0.05)


def build(m: tribo.Mesh, nu: float, formulation: str) -> tribo.Problem:
    return tribo.Problem(m, young=sl.YOUNG, poisson=nu, clamped="bottom", contact="top",
                         obstacle=tribo.Obstacle.circle(sl.RADIUS), approach=0.01, formulation=formulation)


def solve(m: tribo.Mesh, nu: float, formulation: str) -> tuple[tribo.Problem, tribo.Solution, float, float]:
    """The problem built and solved afresh (no factorization kept), each timed, after one untimed build and solve
    of the same case: the first solve of a larger case in a process pays for the memory the process grows by
    (twice the time of the next, measured on the mixed formulation at h_min = 0.0025)."""
    build(m, nu, formulation).solve()
    problem, build_seconds = sl.timed(lambda: build(m, nu, formulation))
    solution, seconds = sl.timed(problem.solve)
    assert solution.report.status == "converged", (nu, formulation, solution.report.status)
    return problem, solution, build_seconds, seconds


def run(smoke: bool, out: Path) -> list[list[object]]:
    poissons = [0.3, 0.4999] if smoke else POISSONS
    h_mins = [0.02, 0.01] if smoke else H_MINS
    meshes = {h_min: mesh(h_min) for h_min in h_mins}
    cases = [(h_min, nu, formulation) for h_min in h_mins for nu in poissons for formulation in FORMULATIONS]
    rows: list[list[object]] = []
    for h_min, nu, formulation in cases:
        problem, solution, build_seconds, seconds = solve(meshes[h_min], nu, formulation)
        error = sl.lambda_l2_error(problem, solution, poisson=nu)
        rows.append([h_min, nu, formulation, problem.n_free, solution.normal_force, error, build_seconds, seconds])
        print(f"h_min {h_min} ν {nu} {formulation}: {problem.n_free} unknowns, λ_n {100 * error:.3f} % "
              f"off Hertz, {seconds:.3f} s")
    # The timings: the fastest of PASSES runs, each pass over every case in turn, so that a slow spell of this
    # shared machine (one run of a case can take twice its usual time) does not fall on every run of one case.
    for _ in range(0 if smoke else PASSES - 1):
        for row, (h_min, nu, formulation) in zip(rows, cases):
            _, _, build_seconds, seconds = solve(meshes[h_min], nu, formulation)
            row[6], row[7] = min(float(row[6]), build_seconds), min(float(row[7]), seconds)  # type: ignore[arg-type]
    headers = ["h_min", "poisson", "formulation", "unknowns", "P", "error", "build_seconds", "solve_seconds"]
    out.mkdir(parents=True, exist_ok=True)
    sl.write_csv(out / "locking.csv", headers, rows)
    return page(rows, out)


def pick(rows: list[list[object]], h_min: float, nu: float, formulation: str) -> list[object]:
    return next(r for r in rows if r[0] == h_min and r[1] == nu and r[2] == formulation)


def page(rows: list[list[object]], out: Path) -> list[list[object]]:
    h_mins = sorted({float(r[0]) for r in rows}, reverse=True)  # type: ignore[arg-type]
    poissons = sorted({float(r[1]) for r in rows})  # type: ignore[arg-type]
    finest = h_mins[-1]
    plt = sl.pyplot()
    fig, axes = plt.subplots(1, 3, figsize=(13.0, 4.0))
    for formulation, style in (("displacement", "o-"), ("mixed", "s-")):
        errors = [100 * float(pick(rows, finest, nu, formulation)[5]) for nu in poissons]  # type: ignore[arg-type]
        axes[0].semilogy([1 - 2 * nu for nu in poissons], errors, style, label=formulation)
    axes[0].invert_xaxis()
    axes[0].set_xscale("log")
    axes[0].set_xlabel("1 − 2ν")
    axes[0].set_ylabel("λ_n against Hertz, relative L² (%)")
    axes[0].set_title(f"at h_min = {finest}", fontsize=10)
    axes[0].axhline(2.0, color="grey", ls="--", lw=0.8, label="2 % (issue 41)")
    axes[0].legend(fontsize=7)
    series = [("displacement", poissons[0]), ("displacement", poissons[-1]), ("mixed", poissons[0]),
              ("mixed", poissons[-1])]
    for formulation, nu in series:
        mine = [pick(rows, h, nu, formulation) for h in h_mins]
        axes[1].loglog([float(r[3]) for r in mine], [100 * float(r[5]) for r in mine],  # type: ignore[arg-type]
                       "o-" if formulation == "displacement" else "s--", label=f"{formulation}, ν = {nu}")
        axes[2].semilogx([float(r[3]) for r in mine],  # type: ignore[arg-type]
                         [float(r[7]) / float(pick(rows, r[0], nu, "displacement")[7])  # type: ignore[arg-type]
                          for r in mine], "o-" if formulation == "displacement" else "s--",
                         label=f"{formulation}, ν = {nu}")
    axes[1].set_xlabel("unknowns")
    axes[1].set_title("under refinement", fontsize=10)
    axes[1].legend(fontsize=7)
    axes[2].axhline(2.5, color="grey", ls="--", lw=0.8, label="2.5 (issue 41)")
    axes[2].set_xlabel("unknowns")
    axes[2].set_ylabel("solve time / P1's on the same mesh and ν")
    axes[2].legend(fontsize=7)
    fig.suptitle("Hertz as ν → ½: P1 displacements lock, the mixed formulation does not", fontsize=10)
    fig.tight_layout()
    fig.savefig(out / "locking.png", dpi=110)
    plt.close(fig)
    nu_hi = poissons[-1]
    p1, mixed = pick(rows, finest, poissons[0], "displacement"), pick(rows, finest, nu_hi, "mixed")
    locked = pick(rows, finest, nu_hi, "displacement")
    ratios = [float(pick(rows, r[0], r[1], "mixed")[7]) / float(r[7])  # type: ignore[arg-type]
              for r in rows if r[2] == "displacement"]
    totals = [(float(pick(rows, r[0], r[1], "mixed")[7]) + float(pick(rows, r[0], r[1], "mixed")[6]))  # type: ignore[arg-type]
              / (float(r[7]) + float(r[6])) for r in rows if r[2] == "displacement"]  # type: ignore[arg-type]
    ratio = lambda nu: [float(pick(rows, h, nu, "displacement")[5]) / float(pick(rows, h, nu, "mixed")[5])  # type: ignore[arg-type]  # noqa: E731
                        for h in h_mins]
    at49, at45 = (ratio(0.49), ratio(0.45)) if 0.45 in poissons else ([math.nan], [math.nan])
    last = [pick(rows, h, nu_hi, "mixed") for h in h_mins[-2:]]
    rate = sl.fitted_rate([float(pick(rows, h, nu_hi, "mixed")[3]) for h in h_mins],  # type: ignore[arg-type]
                          [float(pick(rows, h, nu_hi, "mixed")[5]) for h in h_mins])  # type: ignore[arg-type]
    found = "\n".join([
        f"* at h_min = {finest} ({p1[3]} P1 unknowns, {mixed[3]} mixed): P1 at ν = {poissons[0]} is "
        f"{100 * float(p1[5]):.2f} % off Hertz; at ν = {nu_hi} P1 is {100 * float(locked[5]):.1f} % off "  # type: ignore[arg-type]
        f"(force {float(locked[4]):.4g}), the mixed formulation {100 * float(mixed[5]):.2f} % "  # type: ignore[arg-type]
        f"(force {float(mixed[4]):.4g})",  # type: ignore[arg-type]
        f"* the mixed formulation's error at ν = {nu_hi} falls like N^{rate:.2f} over these meshes (a least-squares "
        f"fit; the last step {float(last[0][5]) * 100:.3f} → {float(last[1][5]) * 100:.3f} % reaches the floor of "  # type: ignore[arg-type]
        f"about 0.5 % that P1 displacements at ν = {poissons[0]} show too on this grading)",
        f"* its solve takes {min(ratios):.2f}–{max(ratios):.2f} times the P1 solve of the same mesh and ν "
        f"(median {statistics.median(ratios):.2f}); with the building of the problem, "
        f"{min(totals):.2f}–{max(totals):.2f} times (median {statistics.median(totals):.2f})",
        f"* at ν = 0.49 the P1 error is {min(at49):.1f}–{max(at49):.1f} times the mixed one on the same mesh, at "
        f"ν = 0.45 {min(at45):.1f}–{max(at45):.1f} times (the default formulation, 'auto', is mixed from ν = 0.49)",
    ])
    table = sl.markdown_table(
        ["h_min", "ν", "formulation", "unknowns", "P", "λ_n error", "build (s)", "solve (s)"],
        [[r[0], repr(r[1]), r[2], r[3], f"{float(r[4]):.5g}", f"{100 * float(r[5]):.3f} %",  # type: ignore[arg-type]
          f"{float(r[6]):.3f}", f"{float(r[7]):.3f}"] for r in rows])  # type: ignore[arg-type]
    text = "\n\n".join(["Found:", found, "![locking](locking.png)", table])
    sl.write_page(out / "locking.md", "Study 25: locking as ν → ½", __doc__ or "", sl.commands_block(__doc__ or ""),
                  text)
    return rows


def from_csv(path: Path) -> list[list[object]]:
    """The rows of a CSV this study wrote, typed as ``run`` makes them."""
    kinds = (float, float, str, int, float, float, float, float)
    return [[kind(r[h]) for kind, h in zip(kinds, r)] for r in sl.read_csv_rows(path)]


MEMORY = """
import resource, sys
sys.path.insert(0, {scripts!r})
import studylib as sl, tribo
m = sl.graded_mesh({h_min}, h_max=0.1, growth=0.05)
p = tribo.Problem(m, young=sl.YOUNG, poisson=0.4999, clamped="bottom", contact="top",
                  obstacle=tribo.Obstacle.circle(sl.RADIUS), approach=0.01, formulation={formulation!r})
s = p.solve()
assert s.report.status == "converged"
print(p.n_free, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024)
"""


def memory(h_min: float, out: Path) -> list[list[object]]:
    """The peak resident memory of a fresh process that builds and solves Hertz at ν = 0.4999 on the mesh of
    ``h_min``, in each formulation (the process's baseline, Python and the mesh, included)."""
    import subprocess

    rows: list[list[object]] = []
    for formulation in ("displacement", "mixed"):
        code = MEMORY.format(scripts=str(Path(__file__).resolve().parent), h_min=h_min, formulation=formulation)
        n, rss = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True).stdout.split()
        rows.append([h_min, formulation, int(n), int(rss)])
        print(f"h_min {h_min} {formulation}: {n} unknowns, peak RSS {int(rss) / 2**20:.0f} MiB")
    out.mkdir(parents=True, exist_ok=True)
    sl.write_csv(out / "locking_memory.csv", ["h_min", "formulation", "unknowns", "peak_rss_bytes"], rows)
    return rows


def main(argv: list[str] | None = None) -> list[list[object]]:
    args = list(argv if argv is not None else sys.argv[1:])
    if "--memory" in args:
        out = Path(args[args.index("--out") + 1]) if "--out" in args else sl.DOCS
        return memory(0.01 if "--smoke" in args else H_MINS[-1], out)
    if "--page-from" in args:
        at = args.index("--page-from")
        out = Path(args[args.index("--out") + 1]) if "--out" in args else sl.DOCS
        return page(from_csv(Path(args[at + 1])), out)
    return sl.cli(run, __doc__, args)  # type: ignore[no-any-return]


if __name__ == "__main__":
    main()
