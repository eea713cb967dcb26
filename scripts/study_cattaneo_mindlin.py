"""Study 4 — loading histories against Cattaneo–Mindlin: partial slip, the fretting loop, path dependence.

The Hertz cylinder (R = 1, E = 200) is pressed δ = 0.01 into the block, then moved tangentially in steps
(``Problem.solve_history``, Coulomb μ = 0.3). For an elastic body on a rigid cylinder with no coupling of
normal and tangential response (Dundurs β = (1 − 2ν) / (2(1 − ν)) = 0), the 2D Cattaneo–Mindlin solution
of monotone loading to Q < μP has a central stick zone of half-width

    c = a √(1 − Q/(μP)),   q(x) = μ p₀ √(1 − x²/a²) − μ p₀ (c/a) √(1 − x²/c²) in |x| < c,  μ p(x) beyond,

with a, p₀ = 2P/(πa) the Hertz values of the computed P. Measured per mesh (graded, h_min from 0.02 to
0.0025) and per ν (0.40: β = 0.167; 0.45: β = 0.091; the part of the error due to β ≠ 0 is estimated by
extrapolating the finest mesh's error linearly in β to β = 0; ν closer to 1/2 locks P1 triangles, whose
stresses then oscillate in the stick zone):

* **c/a**: the stick half-width (half the extent of the stick dofs) over the contact half-width, against
  √(1 − Q/μP) at the computed Q, P; the largest error over the steps with 0.1 ≤ Q/μP ≤ 0.9;
* **traction**: relative L2 error of λ_t against q(x) at the step nearest Q/μP = 0.6;
* **fretting loop**: two cycles ±s*; the energy dissipated in the second, W = −∮ Q ds (the obstacle's
  work), against the 2D Mindlin–Deresiewicz-type value. In 2D the stick zone moves rigidly by
  δ(Q) = C Q + (μP/(πE*)) (1 − r) ln(1 − r), r = Q/(μP), E* = E/(1 − ν²), C depending on the body (it
  cancels in the loop); Masing's rule gives the unloading branch δ(Q*) − 2δ((Q* − Q)/2), and W is the
  area between the branches (computed by quadrature);
* **path dependence** (ν = 0.3): the same final position reached in one step from rest, in 20 steps
  after the press, and after overshooting to twice the distance; and **gross sliding**: dragged past μP,
  every contact dof slips and Q/μP = 1.

    python scripts/study_cattaneo_mindlin.py            # docs/cattaneo_mindlin.{md,csv,png}
    python scripts/study_cattaneo_mindlin.py --smoke --out /tmp/x
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

MU = 0.3
APPROACH = 0.01
S_MAX = 0.0045  # Q/μP ≈ 0.9 on the finest meshes


def beta(nu: float) -> float:
    """Dundurs' β of an elastic body on a rigid one (plane strain)."""
    return (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu))


def hertz_values(force: float, nu: float) -> tuple[float, float]:
    """Half-width a and peak pressure p₀ of the plane-strain Hertz contact under force P per length."""
    e_star = sl.YOUNG / (1.0 - nu**2)
    a = math.sqrt(4.0 * force * sl.RADIUS / (math.pi * e_star))
    return a, 2.0 * force / (math.pi * a)


def cm_traction(x: np.ndarray, a: float, p0: float, c: float) -> np.ndarray:
    """The Cattaneo–Mindlin tangential traction (magnitude, along the drag) of monotone loading."""
    outer = MU * p0 * np.sqrt(np.clip(1.0 - (x / a) ** 2, 0.0, None))
    inner = MU * p0 * (c / a) * np.sqrt(np.clip(1.0 - (x / c) ** 2, 0.0, None)) if c > 0 else 0.0 * x
    return outer - inner


def dissipation(q_star: float, force: float, nu: float) -> float:
    """Energy per cycle of ±Q* from the 2D Mindlin–Deresiewicz-type compliance (Masing's rule)."""
    e_star = sl.YOUNG / (1.0 - nu**2)
    mu_p = MU * force

    def nonlinear(q: np.ndarray) -> np.ndarray:
        r = q / mu_p
        return (mu_p / (math.pi * e_star)) * (1.0 - r) * np.log1p(-r)

    q = np.linspace(-q_star, q_star, 4001)
    down = nonlinear(np.array(q_star)) - 2.0 * nonlinear((q_star - q) / 2.0)
    up = -nonlinear(np.array(q_star)) + 2.0 * nonlinear((q_star + q) / 2.0)
    width = down - up
    return float(np.sum(0.5 * (width[1:] + width[:-1]) * np.diff(q)))


def problem_for(h_min: float, nu: float) -> tribo.Problem:
    return sl.hertz_problem(sl.graded_mesh(h_min), approach=APPROACH, poisson=nu)


def stick_ratio(h: tribo.History) -> tuple[np.ndarray, np.ndarray, float]:
    """Per step Q/μP and c/a (half the stick extent over half the contact extent), and the largest error
    of c/a against √(1 − Q/μP) over the steps with 0.1 ≤ Q/μP ≤ 0.9 (nan if none)."""
    half = lambda z: 0.5 * (z[:, 1] - z[:, 0])  # noqa: E731
    with np.errstate(invalid="ignore", divide="ignore"):  # steps where nothing touches: nan
        r = np.abs(h.tangential_force) / (MU * h.normal_force)
        ca = half(h.stick_zone) / half(h.contact_zone)
    keep = (r >= 0.1) & (r <= 0.9) & np.isfinite(ca)
    return r, ca, float(np.max(np.abs(ca[keep] - np.sqrt(1.0 - r[keep])))) if keep.any() else math.nan


def partial_slip(h_min: float, nu: float, steps: int) -> dict[str, Any]:
    """Press, then drag monotonically to S_MAX: c/a and the traction against Cattaneo–Mindlin."""
    problem = problem_for(h_min, nu)
    shift = np.linspace(0.0, S_MAX, steps + 1)
    h = problem.solve_history(APPROACH, shift, mu=MU)
    assert h.converged, h.status
    p = h.normal_force
    r, ca, err_c = stick_ratio(h)
    k = int(np.argmin(np.abs(r - 0.6)))
    sol = h.solutions[k]
    a, p0 = hertz_values(float(p[k]), nu)
    c = a * math.sqrt(max(0.0, 1.0 - r[k]))
    centre = 0.5 * (h.contact_zone[k, 0] + h.contact_zone[k, 1])
    x = sol.multiplier_abscissae
    ref = cm_traction(x - centre, a, p0, c)
    lt = np.abs(sol.lambda_t)
    err_t = float(np.sqrt(np.trapezoid((lt - ref) ** 2, x) / np.trapezoid(ref**2, x)))
    return {
        "h_min": h_min, "nu": nu, "beta": beta(nu), "dofs_in_contact": int(np.sum(sol.states != 0)),
        "ca_error": err_c, "traction_error": err_t, "r": r, "ca": ca, "step": k, "x": x - centre,
        "lambda_t": lt, "reference": ref, "a": a, "seconds_per_step": float(np.mean(h.step_seconds[1:])),
        "setup_seconds": h.setup_seconds,
    }


def fretting(h_min: float, nu: float, n: int) -> dict[str, Any]:
    """Two cycles ±S_MAX after the press; the work of the second against the prediction."""
    problem = problem_for(h_min, nu)
    up = np.linspace(0.0, S_MAX, n + 1)
    cycle = np.concatenate([np.linspace(S_MAX, -S_MAX, 2 * n + 1)[1:], np.linspace(-S_MAX, S_MAX, 2 * n + 1)[1:]])
    s = np.concatenate([up, cycle, cycle])
    h = problem.solve_history(APPROACH, s, mu=MU)
    assert h.converged, h.status
    q = h.tangential_force
    last = slice(len(s) - len(cycle) - 1, len(s))
    work = float(-np.sum(0.5 * (q[last][1:] + q[last][:-1]) * np.diff(s[last])))
    force = float(h.normal_force[-1])
    q_star = float(np.max(np.abs(q[last])))
    predicted = dissipation(q_star, force, nu)
    # Static solve of the last position (same problem, factorization reused) for the cost comparison.
    static_clock = sl.timed(lambda: problem.solve(mu=MU))[1]
    return {
        "h_min": h_min, "nu": nu, "work": work, "predicted": predicted, "q_star_ratio": q_star / (MU * force),
        "s": s, "q": q, "mu_p": MU * force, "cycle_start": last.start,
        "seconds_per_step": float(np.mean(h.step_seconds[1:])), "static_seconds": static_clock,
    }


def path_dependence(h_min: float, n: int) -> dict[str, Any]:
    """ν = 0.3: one step from rest, press + n steps, press + overshoot to 2s and back; and gross sliding."""
    nu, last = 0.3, 0.003
    problem = problem_for(h_min, nu)
    direct = problem.solve_history(APPROACH, [last], mu=MU).solutions[0]
    stepped = problem.solve_history(APPROACH, np.linspace(0.0, last, n + 1), mu=MU).solutions[-1]
    over_path = np.concatenate([np.linspace(0.0, 2 * last, n // 2 + 1), np.linspace(2 * last, last, n // 2 + 1)[1:]])
    over = problem.solve_history(APPROACH, over_path, mu=MU).solutions[-1]
    slide = problem.solve_history(APPROACH, np.linspace(0.0, 0.03, 7), mu=MU)
    end = slide.solutions[-1]
    return {
        "x": direct.multiplier_abscissae,
        "profiles": {
            "one step from rest": direct.lambda_t,
            f"press, then {n} steps": stepped.lambda_t,
            "press, overshoot to 2s, back": over.lambda_t,
        },
        "bound": direct.friction_threshold,
        "slide_ratio": float(abs(end.tangential_force) / (MU * end.normal_force)),
        "slide_all_slip": bool(np.all(end.states[end.states != 0] == 2)),
        "slide_status": slide.status,
    }


def run(smoke: bool, out: Path) -> dict[str, Any]:
    meshes = [0.02, 0.01] if smoke else [0.02, 0.01, 0.005, 0.0025]
    steps = 8 if smoke else 32
    nus = [0.4, 0.45]
    slips = [partial_slip(h, nu, steps) for nu in nus for h in meshes]
    loops = [fretting(h, nu, steps // 2) for nu in nus for h in meshes]
    path = path_dependence(meshes[-1], 8 if smoke else 20)
    # Per ν: the change of the c/a error over the last refinement is what the mesh still contributes; the
    # level it settles at, the rest, is the coupling β ≠ 0 (it scales with β).
    split = {}
    for nu in nus:
        errs = [s["ca_error"] for s in slips if s["nu"] == nu]
        split[nu] = (abs(errs[-1] - errs[-2]), errs[-1] - abs(errs[-1] - errs[-2]))
    write(slips, loops, path, out, split)
    return {"slips": slips, "loops": loops, "path": path, "split": split}


def write(
    slips: list[dict[str, Any]],
    loops: list[dict[str, Any]],
    path: dict[str, Any],
    out: Path,
    split: dict[float, tuple[float, float]],
) -> None:
    headers = ["nu", "beta", "h_min", "dofs_in_contact", "ca_error", "traction_error", "work", "predicted_work",
               "work_error", "q_star_over_mu_p", "seconds_per_step", "static_solve_seconds"]
    rows = []
    for s, lp in zip(slips, loops, strict=True):
        rows.append([s["nu"], s["beta"], s["h_min"], s["dofs_in_contact"], s["ca_error"], s["traction_error"],
                     lp["work"], lp["predicted"], lp["work"] / lp["predicted"] - 1.0, lp["q_star_ratio"],
                     lp["seconds_per_step"], lp["static_seconds"]])
    out.mkdir(parents=True, exist_ok=True)
    sl.write_csv(out / "cattaneo_mindlin.csv", headers, rows)
    text = [
        "# Loading histories against Cattaneo–Mindlin",
        "",
        "Written by `python scripts/study_cattaneo_mindlin.py` (see its docstring for the set-up). Hertz cylinder,",
        f"δ = {APPROACH}, μ = {MU}, dragged monotonically to s = {S_MAX} and cycled ±{S_MAX} twice.",
        "`ca_error`: largest |c/a − √(1 − Q/μP)| over the steps with 0.1 ≤ Q/μP ≤ 0.9; `traction_error`: relative",
        "L2 error of λ_t against the Cattaneo–Mindlin traction at Q/μP ≈ 0.6; `work`: energy dissipated in the",
        "second fretting cycle, against the 2D Mindlin–Deresiewicz-type value; `seconds_per_step` against one",
        "static Coulomb solve on the reused factorization.",
        "",
        sl.markdown_table(headers, rows),
        "",
        "c/a error at the finest mesh, split: the change over the last refinement (what the mesh still",
        "contributes) and the level it settles at (the coupling β ≠ 0): "
        + "; ".join(f"ν = {nu}: {m:.3f} + {b:.3f} (β = {beta(nu):.3f})" for nu, (m, b) in split.items())
        + ".",
        "",
        f"Gross sliding (ν = 0.3, dragged to 0.03): status {path['slide_status']}, Q/μP = {path['slide_ratio']:.12f},",
        f"every contact dof slips: {path['slide_all_slip']}.",
        "",
    ]
    (out / "cattaneo_mindlin.md").write_text("\n".join(text), encoding="utf-8")
    plt = sl.pyplot()
    fig, axes = plt.subplots(2, 2, figsize=(12.0, 8.5), layout="constrained")
    ax = axes[0, 0]
    rr = np.linspace(0.0, 1.0, 200)
    ax.plot(rr, np.sqrt(1.0 - rr), "k-", lw=1.5, label="Cattaneo–Mindlin √(1 − Q/μP)")
    for s in slips:
        if s["h_min"] == min(x["h_min"] for x in slips):
            ax.plot(s["r"], s["ca"], "o", ms=4, label=f"tribo, ν = {s['nu']} (β = {s['beta']:.3f}), h_min = {s['h_min']}")
    ax.set_xlabel("Q/μP")
    ax.set_ylabel("stick half-width c/a")
    ax.set_title("Stick zone under monotone tangential loading")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax = axes[0, 1]
    finest = [s for s in slips if s["h_min"] == min(x["h_min"] for x in slips)]
    s = finest[0]
    a = s["a"]
    ax.plot(s["x"] / a, s["reference"], "k-", lw=1.5, label="Cattaneo–Mindlin")
    for s in finest:
        ax.plot(s["x"] / s["a"], s["lambda_t"], ".-", ms=3, lw=0.8, label=f"|λ_t|, ν = {s['nu']}")
    ax.set_xlim(-1.5, 1.5)
    ax.set_xlabel("x / a")
    ax.set_ylabel("tangential traction")
    ax.set_title(f"Traction at Q/μP ≈ {finest[0]['r'][finest[0]['step']]:.2f}")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax = axes[1, 0]
    for lp in loops:
        if lp["h_min"] == min(x["h_min"] for x in loops):
            i = lp["cycle_start"]
            ax.plot(lp["s"][i:], lp["q"][i:] / lp["mu_p"], "-", lw=1.2,
                    label=f"ν = {lp['nu']}: W = {lp['work']:.3e} (predicted {lp['predicted']:.3e})")
    ax.set_xlabel("obstacle tangential position s (along t)")
    ax.set_ylabel("Q/μP (along t)")
    ax.set_title("Fretting loop (second cycle)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax = axes[1, 1]
    x = path["x"]
    for name, lt in path["profiles"].items():
        ax.plot(x, lt, ".-", ms=3, lw=1.0, label=name)
    ax.plot(x, path["bound"], "k:", lw=0.8, label="±μλ_n")
    ax.plot(x, -path["bound"], "k:", lw=0.8)
    zone = x[path["bound"] > 0]
    if len(zone):
        pad = 0.3 * (zone.max() - zone.min())
        ax.set_xlim(zone.min() - pad, zone.max() + pad)
    ax.set_xlabel("abscissa along Γ_C (along t)")
    ax.set_ylabel("λ_t (along t)")
    ax.set_title("Same final position, three paths (ν = 0.3)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.savefig(out / "cattaneo_mindlin.png", dpi=100)
    plt.close(fig)


def main(argv: list[str] | None = None) -> dict[str, Any]:
    return sl.cli(run, __doc__, argv)


if __name__ == "__main__":
    main()
