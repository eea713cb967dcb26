"""Study 23 — axisymmetric bodies: a sphere on a flat, a flat punch and a shrink fit against their closed forms.

Issue 41 asks for axisymmetry measured against 3D Hertz (a sphere on a flat within 1 % in a, p₀ and P), a flat
cylindrical punch against Boussinesq's pressure away from its edge, and a shaft pressed into a hub and pushed
out at μ p 2π r L within 1 % of the Lamé pressure. Each family is refined and measured per mesh: the sphere
(a rigid sphere R = 1 pushed δ = 0.01 into a cylinder of radius and height 20, graded toward (0, 0.15) at growth
0.05; contact radius a = 0.1) by the relative L²(Γ_C, 2π r dr) error of λ_n against 3D Hertz's pressure of the
computed force, the centre pressure p₀ against 3P/(2πa²) and the force against 4/3 E* R^½ δ^{3/2}; the punch
(radius a = 0.125 pushed 1e-3 into a cylinder of 512 a) by the L² error over r ≤ 0.8 a against P/(2πa√(a² − r²))
and the force against 2aE*δ; the hub (radii 0.5–1, length 0.5, ends on rollers, shrunk on a rigid shaft with
interference 1e-3, uniform meshes) by the largest deviation of λ_n from the plane-strain Lamé pressure, and,
pushed 0.01 along the shaft with μ = 0.2, by the push-out force against μ p 2π a L. On the finest meshes: the
sphere 0.58 % (p₀ +0.30 %, P +0.37 %; 65k unknowns), the punch 0.32 % (P +0.53 %; 20k), the hub's push-out
within 1e-6 of μ p 2π a L (its pressure within ±0.08 % of Lamé node by node; 33k).

    python scripts/study_axisymmetric.py            # docs/axisymmetric.{csv,md,png}
    python scripts/study_axisymmetric.py --smoke --out /tmp/x

What is left out: the sphere's and the punch's forces include the finite body's share (the punch's force is
+1.10 % on a body of 128 a, +0.63 % on 512 a at the same mesh); the punch's pressure is singular at its edge,
which P1 multipliers cannot follow, hence r ≤ 0.8 a; the hub's pressure alternates node by node with the mesh's
alternating diagonals (the deviation is that amplitude), its mean is Lamé's to 1e-5.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import numpy.typing as npt

sys.path.insert(0, str(Path(__file__).resolve().parent))
import studylib as sl  # noqa: E402

import tribo  # noqa: E402

Floats = npt.NDArray[np.float64]
E, NU = 200.0, 0.3
E_STAR = E / (1 - NU**2)


def l2(problem: tribo.Problem, solution: tribo.Solution, exact: Floats, r: Floats) -> float:
    """The relative L²(2π r dr) distance of λ_n from ``exact`` on the fine grid ``r`` (trapezoids)."""
    lam = problem.evaluate_multiplier(solution.lambda_n, r)
    return math.sqrt(float(np.trapezoid(r * (lam - exact) ** 2, r) / np.trapezoid(r * exact**2, r)))


def sphere(h_min: float) -> tuple[tribo.Problem, tribo.Solution, float, list[float]]:
    mesh = tribo.Mesh.graded_rectangle((0.0, 20.0), (-20.0, 0.0), side="top", segment=(0.0, 0.15), h_min=h_min,
                                       h_max=5.0, growth=0.05)
    problem = tribo.Problem(mesh, young=E, poisson=NU, contact="top", clamped="bottom", model="axisymmetric",
                            obstacle=tribo.Obstacle.circle(center=0.0, radius=1.0), approach=0.01)
    solution, seconds = sl.timed(problem.solve)
    force = solution.normal_force
    a = (3 * force / (4 * E_STAR)) ** (1 / 3)
    p0 = 3 * force / (2 * math.pi * a * a)
    r = np.linspace(0.0, 1.5 * a, 200_001)
    exact = p0 * np.sqrt(np.clip(1 - (r / a) ** 2, 0.0, None))
    centre = float(problem.evaluate_multiplier(solution.lambda_n, np.array([0.0]))[0])
    measures = [l2(problem, solution, exact, r), centre / p0 - 1, force / (4 / 3 * E_STAR * 0.01**1.5) - 1]
    return problem, solution, seconds, measures


def punch(h_min: float, a: float = 0.125, delta: float = 1e-3) -> tuple[tribo.Problem, tribo.Solution, float,
                                                                        list[float]]:
    size = 512 * a
    mesh = tribo.Mesh.graded_rectangle((0.0, size), (-size, 0.0), side="top", segment=(0.0, a), h_min=h_min,
                                       h_max=size / 8, growth=0.1)
    points = np.asarray(mesh.points)
    top = np.asarray(mesh.edge_sets["top"])
    under = top[points[top].max(axis=1)[:, 0] <= a * (1 + 1e-12)]
    sets = {name: np.asarray(e) for name, e in mesh.edge_sets.items() if name != "top"} | {"punch": under}
    mesh = tribo.Mesh(points, np.asarray(mesh.triangles), sets)
    problem = tribo.Problem(mesh, young=E, poisson=NU, contact="punch", clamped="bottom", model="axisymmetric",
                            approach=delta)
    solution, seconds = sl.timed(problem.solve)
    force = solution.normal_force
    r = np.linspace(0.0, 0.8 * a, 200_001)
    exact = force / (2 * math.pi * a * np.sqrt(a * a - r * r))
    return problem, solution, seconds, [l2(problem, solution, exact, r), force / (2 * a * E_STAR * delta) - 1]


def lame(a: float = 0.5, b: float = 1.0, delta: float = 1e-3) -> float:
    lam, mu = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
    big_a = delta / (a + (lam + mu) * b * b / (mu * a))
    return 2 * (lam + mu) * big_a * (b * b / (a * a) - 1)


def hub(n: int, mu: float = 0.2) -> tuple[tribo.Problem, tribo.Solution, float, list[float]]:
    mesh = tribo.Mesh.rectangle((0.5, 1.0), (0.0, 0.5), n, n, diagonal="alternating")
    common = dict(young=E, poisson=NU, contact="left", model="axisymmetric", approach=1e-3,
                  supports=[tribo.Support.roller("bottom"), tribo.Support.roller("top")])
    fit = tribo.Problem(mesh, **common)
    solution, seconds = sl.timed(fit.solve)
    p = lame()
    force = p * 2 * math.pi * 0.5 * 0.5
    pushed = tribo.Problem(mesh, **common, shift=0.01).solve(mu=mu)
    assert pushed.report.status == "converged" and {tribo.STATE_NAMES[s] for s in pushed.states} == {"slip"}, pushed.states
    return fit, solution, seconds, [float(np.max(np.abs(solution.lambda_n / p - 1))),
                                    solution.normal_force / force - 1, abs(pushed.tangential_force) / (mu * force) - 1]


def run(smoke: bool, out: Path) -> list[list[object]]:
    families = {
        "sphere": (sphere, [0.005, 0.0025] if smoke else [0.005, 0.0025, 0.00125, 0.000625, 0.0003125]),
        "punch": (punch, [0.125 / 16, 0.125 / 32] if smoke else [0.125 / n for n in (16, 32, 64, 128, 256)]),
        "hub": (hub, [8, 16] if smoke else [8, 16, 32, 64, 128]),
    }
    rows: list[list[object]] = []
    for name, (build, levels) in families.items():
        for level in levels:
            problem, solution, seconds, m = build(level)  # type: ignore[operator]
            assert solution.report.status == "converged", (name, level, solution.report.status)
            m = m + [math.nan] * (3 - len(m))
            rows.append([name, level, problem.n_free, solution.normal_force, *m,
                         solution.report.estimate["traction_relative"], seconds])
            print(f"{name} {level}: {problem.n_free} unknowns, " + ", ".join(f"{v:+.4%}" for v in m))
    headers = ["case", "level", "unknowns", "P", "pressure_error", "second", "third", "traction_estimate", "seconds"]
    out.mkdir(parents=True, exist_ok=True)
    sl.write_csv(out / "axisymmetric.csv", headers, rows)
    labels = {
        "sphere": ("λ_n vs 3D Hertz (L²)", "p₀", "P for δ"),
        "punch": ("λ_n vs Boussinesq (L², r ≤ 0.8a)", "P for δ", None),
        "hub": ("λ_n vs Lamé (largest)", "P vs Lamé", "push-out vs μ p 2πaL"),
    }
    plt = sl.pyplot()
    fig, axes = plt.subplots(1, 3, figsize=(12.0, 4.0), sharey=True)
    for ax, (name, label) in zip(axes, labels.items()):
        mine = [r for r in rows if r[0] == name]
        n = [float(r[2]) for r in mine]  # type: ignore[arg-type]
        for k, what in enumerate(label):
            values = [abs(float(r[4 + k])) * 100 for r in mine]  # type: ignore[arg-type]
            if what is not None and all(v > 0 for v in values):
                ax.loglog(n, values, ["o-", "s-", "x--"][k], label=what)
        ax.axhline(1.0, color="grey", ls="--", lw=0.8, label="1 % (issue 41)")
        ax.set_xlabel("unknowns")
        ax.set_title(name, fontsize=10)
        ax.legend(fontsize=7)
    axes[0].set_ylabel("relative error (%)")
    fig.suptitle("Axisymmetric bodies against closed forms", fontsize=10)
    fig.tight_layout()
    fig.savefig(out / "axisymmetric.png", dpi=110)
    plt.close(fig)
    finest = {name: [r for r in rows if r[0] == name][-1] for name in families}
    pct = lambda v: f"{100 * float(v):+.2f} %"  # noqa: E731
    s, p, h = finest["sphere"], finest["punch"], finest["hub"]
    found = "\n".join([
        f"* sphere on a flat, {s[2]} unknowns: λ_n {100 * float(s[4]):.2f} % from 3D Hertz in L², p₀ {pct(s[5])}, "
        f"P {pct(s[6])}, the traction estimate {100 * float(s[7]):.1f} %",  # type: ignore[arg-type]
        f"* flat punch, {p[2]} unknowns: λ_n {100 * float(p[4]):.2f} % from Boussinesq in L²(r ≤ 0.8a), "
        f"P {pct(p[5])}",  # type: ignore[arg-type]
        f"* hub, {h[2]} unknowns: λ_n within {100 * float(h[4]):.2f} % of Lamé node by node, P {pct(h[5])}, the "
        f"push-out force {pct(h[6])} from μ p 2π a L",  # type: ignore[arg-type]
    ])
    table = sl.markdown_table(
        ["case", "h_min or cells", "unknowns", "P", "λ_n error", "second", "third", "estimate", "seconds"],
        [[r[0], r[1], r[2], f"{float(r[3]):.6g}", f"{100 * float(r[4]):.3f} %", pct(r[5]),  # type: ignore[arg-type]
          "" if math.isnan(float(r[6])) else pct(r[6]), f"{100 * float(r[7]):.2f} %",  # type: ignore[arg-type]
          f"{float(r[8]):.2f}"] for r in rows])  # type: ignore[arg-type]
    legend = ("The columns *second* and *third* are, for the sphere, p₀ against 3P/(2πa²) and P against "
              "4/3 E* R^½ δ^{3/2}; for the punch, P against 2aE*δ; for the hub, P against p 2π a L and the push-out "
              "force against μ p 2π a L. *estimate* is the solve's traction estimate (the bound, `traction_relative`).")
    text = "\n\n".join(["On the finest meshes:", found, "![axisymmetric](axisymmetric.png)", legend, table])
    sl.write_page(out / "axisymmetric.md", "Study 23: axisymmetric bodies", __doc__ or "",
                  sl.commands_block(__doc__ or ""), text)
    return rows


def main(argv: list[str] | None = None) -> list[list[object]]:
    return sl.cli(run, __doc__, argv)  # type: ignore[no-any-return]


if __name__ == "__main__":
    main()
