"""Study 1b — γ0 near and above its admissible bound.

Frictionless Hertz (approach 0.01) on graded meshes (h_min = 0.02, 0.01, 0.005), P1 multipliers, H = h. For
γ0 = f × the sufficient bound computed per contact triangle (f from 0.5 to 3, through the unchecked path
``solve(gamma0=..., check_gamma0=False)``): whether the Cholesky factorization of A = K − G is refused
(A indefinite), the relative L2 error of λ_n against Hertz and the oscillation indicator. The true bound
γ0* (the largest γ0 with A positive definite) is computed independently in numpy: with G = γ0 W Wᵀ
(W: √(h_T |E|) σ_n, σ_t of every contact triangle), γ0* = 1 / λ_max(Wᵀ K⁻¹ W), and the conditioning of
A relative to K is κ(K⁻¹ A) = 1 / (1 − γ0 / γ0*).

    python scripts/study_gamma0_bound.py            # docs/gamma0_bound.{md,csv,png}
    python scripts/study_gamma0_bound.py --smoke --out /tmp/x
"""

from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import studylib as sl  # noqa: E402

import tribo  # noqa: E402

FRACTIONS = [0.5, 0.75, 0.9, 1.0, 1.1, 1.25, 1.4, 1.5, 1.55, 1.58, 1.6, 1.7, 1.8, 1.9, 2.0, 2.5, 3.0]


def elasticity_matrix(young: float, poisson: float) -> np.ndarray:
    """Plane-strain C for (σ_xx, σ_yy, σ_xy) against (ε_xx, ε_yy, 2ε_xy), written here independently of the
    core (the point of this study's γ0*)."""
    c = young / ((1.0 + poisson) * (1.0 - 2.0 * poisson))
    return c * np.array([[1.0 - poisson, poisson, 0.0], [poisson, 1.0 - poisson, 0.0], [0.0, 0.0, 0.5 - poisson]])


def strain_operators(mesh: tribo.Mesh) -> tuple[np.ndarray, np.ndarray]:
    """Per triangle: B (3 × 6, interleaved x, y dofs) and the area."""
    p = mesh.points[mesh.triangles]  # (nt, 3, 2)
    x, y = p[:, :, 0], p[:, :, 1]
    b = np.stack([y[:, 1] - y[:, 2], y[:, 2] - y[:, 0], y[:, 0] - y[:, 1]], axis=1)
    c = np.stack([x[:, 2] - x[:, 1], x[:, 0] - x[:, 2], x[:, 1] - x[:, 0]], axis=1)
    area2 = (x[:, 1] - x[:, 0]) * (y[:, 2] - y[:, 0]) - (x[:, 2] - x[:, 0]) * (y[:, 1] - y[:, 0])
    bm = np.zeros((len(x), 3, 6))
    bm[:, 0, 0::2] = b / area2[:, None]
    bm[:, 1, 1::2] = c / area2[:, None]
    bm[:, 2, 0::2] = c / area2[:, None]
    bm[:, 2, 1::2] = b / area2[:, None]
    return bm, 0.5 * np.abs(area2)


def true_bound(problem: tribo.Problem) -> float:
    """Largest γ0 with K − G positive definite (dense numpy; K and G assembled here independently)."""
    mesh = problem.mesh
    bm, area = strain_operators(mesh)
    c = elasticity_matrix(problem.young, problem.poisson)
    ke = area[:, None, None] * np.einsum("tki,kl,tlj->tij", bm, c, bm)
    dofs = np.stack([2 * mesh.triangles, 2 * mesh.triangles + 1], axis=2).reshape(-1, 6)
    ndof = 2 * mesh.n_nodes
    k = np.zeros((ndof, ndof))
    np.add.at(k, (dofs[:, :, None], dofs[:, None, :]), ke)
    clamped = np.unique(mesh.edge_sets["bottom"])
    free = np.setdiff1d(np.arange(ndof), np.concatenate([2 * clamped, 2 * clamped + 1]))
    # Contact edges: the owner triangle, its diameter h_T and |E|; σ_n, σ_t rows a_n · C B, a_t · C B.
    n, t = np.array(problem.contact_normal), np.array(problem.contact_tangent)
    a_n = np.array([n[0] * n[0], n[1] * n[1], 2 * n[0] * n[1]])
    a_t = np.array([t[0] * n[0], t[1] * n[1], t[0] * n[1] + t[1] * n[0]])
    diam = mesh.diameters()
    tri_sets = [set(tr) for tr in mesh.triangles.tolist()]
    cols = []
    for a, b in mesh.edge_sets[problem.contact]:
        owner = next(i for i, s in enumerate(tri_sets) if a in s and b in s)
        length = float(np.linalg.norm(mesh.points[a] - mesh.points[b]))
        for vec in (a_n, a_t):
            col = np.zeros(ndof)
            col[dofs[owner]] = math.sqrt(diam[owner] * length) * (vec @ c @ bm[owner])
            cols.append(col)
    w = np.array(cols).T[free]
    kw = np.linalg.solve(k[np.ix_(free, free)], w)
    return float(1.0 / np.linalg.eigvalsh(w.T @ kw).max())


def run(smoke: bool, out: Path) -> dict[str, Any]:
    h_mins = [0.04] if smoke else [0.02, 0.01, 0.005]
    fractions = [0.5, 1.5, 2.0, 3.0] if smoke else FRACTIONS
    rows: list[dict[str, Any]] = []
    bounds: dict[float, tuple[float, float]] = {}
    for h_min in h_mins:
        problem = sl.hertz_problem(sl.graded_mesh(h_min))
        bound = problem.gamma0_bound
        star = true_bound(problem)
        bounds[h_min] = (bound, star)
        print(f"h_min {h_min}: sufficient bound {bound:.4e}, true bound {star:.4e} (ratio {star / bound:.3f})")
        for f in fractions:
            row: dict[str, Any] = dict(h_min=h_min, n_free=problem.n_free, fraction=f, gamma0=f * bound)
            row["kappa_rel"] = 1.0 / (1.0 - f * bound / star) if f * bound < star else math.inf
            try:
                sol = problem.solve(gamma0=f * bound, check_gamma0=False)
                row.update(outcome=sol.report.status, l2=sl.lambda_l2_error(problem, sol), tv=sl.oscillation(sol),
                           force=sol.normal_force)
            except tribo.SolverError as e:
                row.update(outcome=f"refused ({e.kind})", l2=math.nan, tv=math.nan, force=math.nan)
            rows.append(row)
            print(f"  f = {f:<5} {row['outcome']:>32}  L2 {row['l2']:.4f}  TV {row['tv']:.3f}  κ(K⁻¹A) {row['kappa_rel']:.3g}")
    write(rows, bounds, out)
    return dict(rows=rows, bounds=bounds)


def write(rows: list[dict[str, Any]], bounds: dict[float, tuple[float, float]], out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)
    keys = ["h_min", "n_free", "fraction", "gamma0", "outcome", "kappa_rel", "l2", "tv", "force"]
    sl.write_csv(out / "gamma0_bound.csv", keys, [[r[k] for k in keys] for r in rows])
    md = ["# Study 1b: γ0 near and above the admissible bound\n\n",
          "Frictionless Hertz, graded meshes, P1, H = h. f = γ0 / (sufficient bound computed per contact "
          "triangle); γ0* = true bound (largest γ0 with K − G positive definite, dense numpy). "
          "Regenerate with `python scripts/study_gamma0_bound.py`.\n\n"]
    md.append(sl.markdown_table(
        ["h_min", "sufficient bound", "true bound γ0*", "γ0* / sufficient", "largest f solved", "smallest f refused"],
        [[h, b, s, s / b,
          max((r["fraction"] for r in rows if r["h_min"] == h and not r["outcome"].startswith("refused")), default=math.nan),
          min((r["fraction"] for r in rows if r["h_min"] == h and r["outcome"].startswith("refused")), default=math.nan)]
         for h, (b, s) in bounds.items()]))
    md.append("\n")
    md.append(sl.markdown_table(["h_min", "f", "outcome", "κ(K⁻¹A)", "L2 error", "TV ratio"],
                                [[r["h_min"], r["fraction"], r["outcome"], r["kappa_rel"], r["l2"], r["tv"]] for r in rows]))
    (out / "gamma0_bound.md").write_text("".join(md))

    plt = sl.pyplot()
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.8))
    for h, c in zip(bounds, ["C0", "C1", "C2", "C3"]):
        rs = [r for r in rows if r["h_min"] == h]
        ok = [r for r in rs if not r["outcome"].startswith("refused")]
        bad = [r for r in rs if r["outcome"].startswith("refused")]
        star = bounds[h][1] / bounds[h][0]
        ax1.plot([r["fraction"] for r in ok], [r["l2"] for r in ok], "o-", color=c, label=f"h_min = {h:g}: L2 error")
        ax1.plot([r["fraction"] for r in ok], [r["tv"] - 1.0 for r in ok], "s--", color=c, ms=4, alpha=0.7,
                 label=f"h_min = {h:g}: TV ratio − 1")
        ax1.axvline(star, color=c, ls=":", lw=1.2)
        ax2.plot([r["fraction"] for r in ok], [r["kappa_rel"] for r in ok], "o-", color=c,
                 label=f"h_min = {h:g} (true bound at f = {star:.2f})")
        ax2.plot([r["fraction"] for r in bad], [1.0] * len(bad), "x", color=c, ms=9, mew=2,
                 label=f"h_min = {h:g}: Cholesky refused" if bad else None)
        ax2.axvline(star, color=c, ls=":", lw=1.2)
    for ax in (ax1, ax2):
        ax.axvline(1.0, color="k", lw=1.0)
        ax.set_xlabel("γ0 / sufficient bound (per-triangle eigenproblem)  [–]")
        ax.grid(True, which="both", alpha=0.3)
    ax1.set_yscale("log")
    ax1.set_ylabel("relative L2 error of λ_n; TV(λ_n)/(2 p_max) − 1  [–]")
    ax1.set_title("accuracy while A = K − G stays definite\n(dotted: true bound γ0*, solid: sufficient bound)")
    ax1.legend(fontsize=7)
    ax2.set_yscale("log")
    ax2.set_ylabel("κ(K⁻¹ A) = 1 / (1 − γ0/γ0*)  [–]")
    ax2.set_title("conditioning of A relative to K; × = factorization refused")
    ax2.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "gamma0_bound.png", dpi=90)
    plt.close(fig)


def main(argv: list[str] | None = None) -> dict[str, Any]:
    return sl.cli(run, __doc__, argv)


if __name__ == "__main__":
    main()
