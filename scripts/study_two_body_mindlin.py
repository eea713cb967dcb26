"""Study 9 — Cattaneo–Mindlin between two elastic bodies: partial slip against the half-space solution.

The two-body Hertz scene of study 8: a block (−2, 2) × (−2, 0) clamped at its bottom (the secondary side,
its top carries T_H) under a block (−2, 2) × (0, 1) whose top is held by a prescribed displacement, with a
parabolic gap of radius 1 between them; both graded toward [−0.15, 0.15] at growth 0.15 down to h_min. A
loading history (``Problem.solve_history(displacements=…)``) presses the upper top down to δ = 0.01 in
four steps, then moves it along x in ``steps`` steps (Coulomb, μ = 0.3) until Q/μP passes 0.9.

For two half-spaces whose Dundurs' β vanishes (equal materials, or μ₂(1 − 2ν₁) = μ₁(1 − 2ν₂)), normal and
tangential responses uncouple: the pressure stays Hertz's of the combined modulus 1/E* = Σ(1 − ν_i²)/E_i
while the bodies are sheared, and the stick zone and the traction are Cattaneo–Mindlin's,

    c = a √(1 − Q/(μP)),   q(x) = μ p₀ √(1 − x²/a²) − μ p₀ (c/a) √(1 − x²/c²) in |x| < c,  μ p(x) beyond,

with a and p₀ = 2P/(πa) the Hertz values of the computed P. Pairs: ``equal`` (E = 200, ν = 0.3 on both,
β = 0), ``beta0`` (E = 200, ν = 0.3 under E = 107.69, ν = 0.4: β = 0 with unequal materials) and
``stiff`` (E = 200, ν = 0.3 under E = 2000, ν = 0.3: β = −0.23, where the theory does not hold and the
departure is measured). Per pair and mesh:

* **c/a**: half the stick extent over half the contact extent, against √(1 − Q/μP), the largest error over
  the steps with 0.1 ≤ Q/μP ≤ 0.9 (the extents are read on the multiplier dofs, so each is off by up to
  one spacing h_min: the resolution is about 2 h_min/a);
* **traction**: relative L2 error of λ_t against q(x) at the step nearest Q/μP = 0.6;
* **P change**: how much the normal force moves while the bodies are sheared (0 when β = 0).

    python scripts/study_two_body_mindlin.py            # docs/two_body_mindlin.{md,csv,png}
    python scripts/study_two_body_mindlin.py --smoke --out /tmp/x
"""

from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import studylib as sl  # noqa: E402
from study_cattaneo_mindlin import cm_traction  # noqa: E402

import tribo  # noqa: E402

MU = 0.3
DELTA = 0.01
X_MAX = 0.004  # the upper top's last x: Q/μP ≈ 0.94
LOWER = (200.0, 0.3)
PAIRS = {"equal": (200.0, 0.3), "beta0": (107.69230769230769, 0.4), "stiff": (2000.0, 0.3)}


def shear_modulus(e: float, nu: float) -> float:
    return e / (2.0 * (1.0 + nu))


def dundurs_beta(first: tuple[float, float], second: tuple[float, float]) -> float:
    """Dundurs' β of two plane-strain bodies."""
    (m1, n1), (m2, n2) = (shear_modulus(*first), first[1]), (shear_modulus(*second), second[1])
    return (m1 * (1 - 2 * n2) - m2 * (1 - 2 * n1)) / (2 * (m1 * (1 - n2) + m2 * (1 - n1)))


def combined_modulus(first: tuple[float, float], second: tuple[float, float]) -> float:
    return 1.0 / sum((1.0 - nu**2) / e for e, nu in (first, second))


def problem_for(h_min: float, upper: tuple[float, float]) -> tribo.Problem:
    def mesh(y: tuple[float, float], side: str) -> tribo.Mesh:
        return tribo.Mesh.graded_rectangle((-2.0, 2.0), y, side=side, segment=(-0.15, 0.15), h_max=0.5,
                                           h_min=h_min, growth=0.15)

    lower_body = tribo.Body("lower", mesh((-2.0, 0.0), "top"), *LOWER, clamped="bottom")
    upper_body = tribo.Body("upper", mesh((0.0, 1.0), "bottom"), *upper,
                            supports=tribo.Support.displacement("top", x=0.0, y=0.0))
    return tribo.Problem.two_bodies(lower_body, upper_body, secondary="lower.top", primary="upper.bottom",
                                    gap=tribo.Obstacle.parabola(1.0))


def partial_slip(h_min: float, pair: str, steps: int) -> dict[str, Any]:
    upper = PAIRS[pair]
    problem = problem_for(h_min, upper)
    press = np.linspace(0.0, -DELTA, 5)[1:]
    x = np.concatenate([np.zeros(4), np.linspace(0.0, X_MAX, steps + 1)[1:]])
    y = np.concatenate([press, np.full(steps, -DELTA)])
    h, seconds = sl.timed(lambda: problem.solve_history(displacements={"upper.top.x": x, "upper.top.y": y}, mu=MU))
    assert h.converged, h.status
    half = lambda z: 0.5 * (z[:, 1] - z[:, 0])  # noqa: E731
    with np.errstate(invalid="ignore", divide="ignore"):
        r = np.abs(h.tangential_force) / (MU * h.normal_force)
        ca = half(h.stick_zone) / half(h.contact_zone)
    keep = (r >= 0.1) & (r <= 0.9) & np.isfinite(ca)
    ca_error = float(np.max(np.abs(ca[keep] - np.sqrt(1.0 - r[keep]))))
    k = int(np.argmin(np.abs(r - 0.6)))
    sol = h.solutions[k]
    e_star = combined_modulus(LOWER, upper)
    force = float(h.normal_force[k])
    a = math.sqrt(4.0 * force * 1.0 / (math.pi * e_star))
    p0 = 2.0 * force / (math.pi * a)
    c = a * math.sqrt(max(0.0, 1.0 - r[k]))
    xs = sol.multiplier_abscissae
    centre = 0.5 * (h.contact_zone[k, 0] + h.contact_zone[k, 1])
    ref = cm_traction(xs - centre, a, p0, c)
    lt = np.abs(sol.lambda_t)
    traction_error = float(np.sqrt(np.trapezoid((lt - ref) ** 2, xs) / np.trapezoid(ref**2, xs)))
    pressed = float(h.normal_force[3])
    return {
        "pair": pair, "beta": dundurs_beta(LOWER, upper), "h_min": h_min, "n_free": problem.n_free,
        "a": a, "resolution": 2.0 * h_min / a, "ca_error": ca_error, "traction_error": traction_error,
        "p_change": float(np.max(np.abs(h.normal_force[3:] - pressed)) / pressed), "r_last": float(r[-1]),
        "seconds": seconds, "steps": len(x), "r": r, "ca": ca, "x": xs - centre, "lambda_t": lt, "reference": ref,
    }


def run(smoke: bool, out: Path) -> list[dict[str, Any]]:
    meshes = [0.02, 0.01] if smoke else [0.02, 0.01, 0.005, 0.0025, 0.00125]
    steps = 8 if smoke else 24
    rows = [partial_slip(h, pair, steps) for pair in PAIRS for h in meshes]
    write(rows, out)
    return rows


def write(rows: list[dict[str, Any]], out: Path) -> None:
    headers = ["pair", "beta", "h_min", "n_free", "a", "resolution", "ca_error", "traction_error", "p_change",
               "r_last", "seconds", "steps"]
    table = [[r[k] for k in headers] for r in rows]
    out.mkdir(parents=True, exist_ok=True)
    sl.write_csv(out / "two_body_mindlin.csv", headers, table)
    rates = {
        pair: sl.fitted_rate([r["h_min"] for r in rows if r["pair"] == pair],
                             [r["traction_error"] for r in rows if r["pair"] == pair])
        for pair in PAIRS
    }
    text = [
        "# Cattaneo–Mindlin between two elastic bodies",
        "",
        "Written by `python scripts/study_two_body_mindlin.py` (see its docstring for the set-up): the upper",
        f"block's top pressed down δ = {DELTA} in 4 steps, then moved along x to {X_MAX} (Coulomb, μ = {MU}).",
        "`ca_error`: largest |c/a − √(1 − Q/μP)| over the steps with 0.1 ≤ Q/μP ≤ 0.9, beside the resolution",
        "2 h_min/a of the extents; `traction_error`: relative L2 error of λ_t against the Cattaneo–Mindlin",
        "traction at Q/μP ≈ 0.6; `p_change`: largest relative change of the normal force while sheared;",
        "`seconds`: the whole history.",
        "",
        sl.markdown_table(headers, table),
        "",
        "Rate of the traction error against h_min: "
        + ", ".join(f"{pair} {rate:.2f}" for pair, rate in rates.items()) + ".",
        "",
    ]
    (out / "two_body_mindlin.md").write_text("\n".join(text), encoding="utf-8")
    plt = sl.pyplot()
    if plt is None:
        return
    fig, axes = plt.subplots(1, 3, figsize=(15.0, 4.2), layout="constrained")
    for pair, marker in zip(PAIRS, "osd", strict=True):
        rs = [r for r in rows if r["pair"] == pair]
        axes[0].loglog([r["h_min"] for r in rs], [r["traction_error"] for r in rs], marker + "-",
                       label=f"{pair} (β = {rs[0]['beta']:.2f}), traction")
        axes[0].loglog([r["h_min"] for r in rs], [r["ca_error"] for r in rs], marker + ":",
                       label=f"{pair}, c/a")
        finest = rs[-1]
        keep = finest["r"] > 0
        axes[1].plot(finest["r"][keep], finest["ca"][keep], marker, label=f"{pair}, h_min {finest['h_min']}")
        if pair != "beta0":
            axes[2].plot(finest["x"], finest["lambda_t"], marker, ms=3, label=f"{pair}: |λ_t|")
    rs = [r for r in rows if r["pair"] == "equal"]
    axes[0].loglog([r["h_min"] for r in rs], [r["resolution"] for r in rs], "k--", label="2 h_min / a")
    axes[0].set(xlabel="h_min", ylabel="error", title="error against mesh size")
    q = np.linspace(0.0, 1.0, 200)
    axes[1].plot(q, np.sqrt(1.0 - q), "k-", label="√(1 − Q/μP)")
    axes[1].set(xlabel="Q / μP", ylabel="c / a", title="stick zone")
    finest = rs[-1]
    axes[2].plot(finest["x"], finest["reference"], "k-", label="Cattaneo–Mindlin (β = 0)")
    axes[2].set(xlabel="x − centre", ylabel="tangential traction", xlim=(-1.5 * finest["a"], 1.5 * finest["a"]),
                title="traction at Q/μP ≈ 0.6")
    for ax in axes:
        ax.legend(fontsize=7)
    fig.savefig(out / "two_body_mindlin.png", dpi=120)
    plt.close(fig)


def main(argv: list[str] | None = None) -> list[dict[str, Any]]:
    return sl.cli(run, __doc__, argv)  # type: ignore[no-any-return]


if __name__ == "__main__":
    main()
