"""Study 26 — conformal contact: an elastic pin pushed across a hole with clearance, against Persson's problem.

docs/persson_pin.csv, docs/persson_pin_pressure.csv and docs/persson_curve.csv are written by the Rust example
`persson_pin` (its documentation describes the scene: a pin of radius 1 − ΔR, ΔR = 10⁻³, in the hole of radius 1 of
a square plate of half-width 80, one material, E = 1, ν = 0.3 and at one δ also ν = 0 and 0.45, plane strain,
frictionless, the upper half by symmetry, the pin's small core moved across by δ, both meshes bisected 1 to 5 times
along the contact arc; times on two cores, with other work running). The reference is Persson's problem (the pin
and the plate of one material, the plate infinite) solved to 1e-9 at the load each answer carries
(`tribo_testkit::Persson`, whose documentation derives it); λ_n is compared as the force per radian λ_n r the two
rims share (r the radius of the rim that carries it). This script draws the load against the contact
half-angle (Persson's, Hertz's and tribo's), λ_n along the rim on the finest meshes, and the differences by
unknowns, and writes docs/persson_pin.{md,png}. Issue 39 asks for the contact half-angle and the pressure within 2 %.

    cargo run --release -p tribo --example persson_pin
    python scripts/plot_persson_pin.py
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
import studylib as sl  # noqa: E402

BAR = 0.02


def load(path: Path) -> list[dict[str, float]]:
    return [{k: float(v) for k, v in r.items()} for r in sl.read_csv_rows(path)]


def cases(rows: list[dict[str, float]]) -> dict[tuple[float, float], list[dict[str, float]]]:
    """The runs of each (δ, ν), by refinement."""
    out: dict[tuple[float, float], list[dict[str, float]]] = {}
    for r in rows:
        out.setdefault((r["approach"], r["poisson"]), []).append(r)
    return {k: sorted(v, key=lambda r: r["refinements"]) for k, v in out.items()}


def errors(r: dict[str, float]) -> tuple[float, float, float]:
    """The half-angle's relative error, λ_n's relative L² difference and its peak's, against Persson."""
    return r["alpha"] / r["alpha_persson"] - 1.0, r["l2_persson"], r["peak_persson"]


def findings(rows: list[dict[str, float]]) -> dict[str, Any]:
    """What the page states, read from the rows."""
    by_case = cases(rows)
    finest = {k: v[-1] for k, v in by_case.items()}
    worst = [max(abs(e) for e in errors(r)) for r in rows]
    within = [r for r, w in zip(rows, worst) if w < BAR]
    # the first refinement at which every case is within the bar, and stays within it
    levels = sorted({r["refinements"] for r in rows})
    first_all = next((lv for lv in levels
                      if all(max(abs(e) for e in errors(r)) < BAR for r in rows if r["refinements"] >= lv)), None)
    return {
        "cases": by_case,
        "finest": finest,
        "within": len(within),
        "runs": len(rows),
        "first_all": first_all,
        "finest_alpha": max(abs(errors(r)[0]) for r in finest.values()),
        "finest_l2": max(errors(r)[1] for r in finest.values()),
        "finest_peak": max(abs(errors(r)[2]) for r in finest.values()),
        "hertz": {k: r["alpha_hertz"] / r["alpha_persson"] - 1.0 for k, r in finest.items()},
        "falls": all(a["l2_persson"] > b["l2_persson"] for v in by_case.values() for a, b in zip(v, v[1:])),
        "rate": {k: sl.fitted_rate([r["unknowns"] for r in v], [r["l2_persson"] for r in v])
                 for k, v in by_case.items()},
        "last_step": {k: sl.fitted_rate([r["unknowns"] for r in v[-2:]], [r["l2_persson"] for r in v[-2:]])
                      for k, v in by_case.items()},
    }


def _pct(x: float) -> str:
    return f"{100 * x:.2f} %"


def _deg(x: float) -> str:
    return f"{math.degrees(x):.1f}°"


def run(csv_path: Path, profile_path: Path, curve_path: Path, out: Path) -> dict[str, Any]:
    rows = load(csv_path)
    out.mkdir(parents=True, exist_ok=True)
    f = findings(rows)
    finest = f["finest"]
    main = sorted((k for k in finest if k[1] == 0.3), key=lambda k: k[0])
    others = sorted(k for k in finest if k[1] != 0.3)
    span = f"{_deg(finest[main[0]]['alpha_persson'])} to {_deg(finest[main[-1]]['alpha_persson'])}" if main else ""
    first = (f"every run from {int(f['first_all'])} bisections on is within 2 % on all three" if f["first_all"]
             else "no refinement level has every run within 2 %")
    lines = [
        "# Study 26: conformal contact, a pin pushed across a hole (Persson)",
        __doc__.split("\n\n")[1].replace("\n", " "),
        sl.commands_block(__doc__),
        "## What it shows",
        f"* **Against Persson** (contact half-angles {span} at ν = 0.3): on the finest meshes "
        f"({int(max(r['unknowns'] for r in rows))} unknowns) the half-angle is within {_pct(f['finest_alpha'])}, "
        f"λ_n within {_pct(f['finest_l2'])} in L² and its peak within {_pct(f['finest_peak'])}; {f['within']} of "
        f"{f['runs']} runs are within 2 % on all three, and {first}. λ_n's difference falls "
        + ("at every refinement of every case" if f["falls"] else "with refinement, though not at every step")
        + ", like N^"
        + ", N^".join(f"{f['rate'][k]:.2f}" for k in main) + " (by half-angle, over all meshes); over the last step "
        "like N^" + ", N^".join(f"{f['last_step'][k]:.2f}" for k in main) + ", slower: the differences left ("
        + _pct(min(finest[k]["l2_persson"] for k in main)) + "–" + _pct(max(finest[k]["l2_persson"] for k in main))
        + ") approach what the scene models apart from Persson's problem (the pin's core stiffens its mode 2 by "
        "0.24 %, the plate's finite size the hole's by 0.07 %).",
        "* **Not Hertz**: at the same loads Hertz's semi-width `b = 2R √(P / π E* ΔR)` (the curvature ΔR / R², "
        "read as the arc R α) gives half-angles " + ", ".join(f"{100 * f['hertz'][k]:+.0f} %" for k in main)
        + " off Persson's: as the arc grows, the same load closes a smaller arc than the half-plane idealization says.",
        "* **E* alone**: at ν = " + " and ".join(f"{k[1]:g}" for k in others)
        + " the same δ gives half-angles within "
        + " and ".join(_pct(abs(errors(finest[k])[0])) for k in others)
        + " of Persson's at their loads and λ_n within " + " and ".join(_pct(errors(finest[k])[1]) for k in others)
        + ": for one material the two rims' opening depends on E* = E / 2(1 − ν²) only (the reference's "
        "derivation).",
        "## The runs",
        sl.markdown_table(["δ", "ν", "bisections", "unknowns", "time [s]", "P / E*ΔR", "α", "α (Persson)",
                           "α (Hertz)", "λ_n vs Persson (L²)", "peak vs Persson"],
                          [[r["approach"], r["poisson"], int(r["refinements"]), int(r["unknowns"]), r["seconds"],
                            f"{r['load']:.4g}", _deg(r["alpha"]), _deg(r["alpha_persson"]), _deg(r["alpha_hertz"]),
                            f"{r['l2_persson']:.2e}", f"{r['peak_persson']:+.2e}"] for r in rows]),
        "![pin in a hole](persson_pin.png)",
    ]
    (out / "persson_pin.md").write_text("\n\n".join(lines) + "\n")

    profile = [{k: float(v) for k, v in r.items()} for r in sl.read_csv_rows(profile_path)]
    curve = [{k: float(v) for k, v in r.items()} for r in sl.read_csv_rows(curve_path)]
    plt = sl.pyplot()
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
    ax = axes[0]
    ax.semilogy([math.degrees(r["alpha"]) for r in curve], [r["persson"] for r in curve], "-", label="Persson")
    ax.semilogy([math.degrees(r["alpha"]) for r in curve], [r["hertz"] for r in curve], "--", label="Hertz")
    for k, r in sorted(finest.items()):
        ax.semilogy(math.degrees(r["alpha"]), r["load"], "o" if k[1] == 0.3 else "s", color="k", ms=4)
    ax.plot([], [], "o", color="k", ms=4, label="tribo (finest meshes)")
    ax.set_xlabel("contact half-angle α [°]")
    ax.set_ylabel("P / (E* ΔR)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    ax = axes[1]
    for k in main:
        pts = sorted((r for r in profile if (r["approach"], r["poisson"]) == k), key=lambda r: r["angle"])
        line, = ax.plot([math.degrees(r["angle"]) for r in pts], [r["lambda_n"] for r in pts], lw=1.2)
        ax.plot([math.degrees(r["angle"]) for r in pts], [r["persson"] for r in pts], "k:", lw=0.8)
        line.set_label(f"δ = {k[0]:g}")
    ax.plot([], [], "k:", lw=0.8, label="Persson")
    ax.set_xlabel("angle θ [°]")
    ax.set_ylabel("λ_n / (E* ΔR / R) (finest meshes)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    ax = axes[2]
    for k, v in sorted(f["cases"].items()):
        ax.loglog([r["unknowns"] for r in v], [r["l2_persson"] for r in v], "o-" if k[1] == 0.3 else "s--", ms=3,
                  label=f"α = {_deg(v[-1]['alpha_persson'])}, ν = {k[1]:g}")
    ax.axhline(BAR, color="0.5", lw=0.8, ls=":")
    ax.set_xlabel("unknowns")
    ax.set_ylabel("relative L² difference of λ_n from Persson")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "persson_pin.png", dpi=85)
    plt.close(fig)
    return f


def main(argv: list[str] | None = None) -> dict[str, Any]:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--csv", type=Path, default=sl.DOCS / "persson_pin.csv")
    ap.add_argument("--profile", type=Path, default=sl.DOCS / "persson_pin_pressure.csv")
    ap.add_argument("--curve", type=Path, default=sl.DOCS / "persson_curve.csv")
    ap.add_argument("--out", type=Path, default=sl.DOCS)
    args = ap.parse_args(argv)
    return run(args.csv, args.profile, args.curve, args.out)


if __name__ == "__main__":
    main()
