"""Study 8 — two elastic bodies: two-body Hertz against the combined modulus, and what a two-body solve costs.

docs/two_bodies.csv is written by the Rust example `cargo run --release -p tribo --example two_bodies`
(see its documentation for the scene); this script draws the relative L2 error of λ_n against the Hertz
pressure of 1/E* = Σ (1 − ν_i²)/E_i and the solve time against the unknowns, fits the error's rate against
h_min, and compares the time per unknown of a two-body solve with that of the one-body problem on the
lower mesh alone (against the rigid parabola), writing docs/two_bodies.png and docs/two_bodies.md.

    cargo run --release -p tribo --example two_bodies && python scripts/plot_two_bodies.py
"""

from __future__ import annotations

import argparse
import csv
import sys
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
import studylib as sl  # noqa: E402


def load(path: Path) -> list[dict[str, Any]]:
    with open(path) as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k, v in r.items():
            if k not in ("pair", "coulomb_status"):
                r[k] = float(v)
    return rows


def run(csv_path: Path, out: Path) -> dict[str, Any]:
    rows = load(csv_path)
    out.mkdir(parents=True, exist_ok=True)
    pairs = list(dict.fromkeys(r["pair"] for r in rows))
    rates = {p: sl.fitted_rate([r["h_min"] for r in rows if r["pair"] == p],
                               [r["hertz_l2"] for r in rows if r["pair"] == p]) for p in pairs}
    # Time per unknown, two bodies over one body (frictionless and Coulomb), where the solves take ≥ 10 ms.
    ratio = {law: [(r[f"{law}_s"] / r["n_free"]) / (r[f"one_body_{law}_s"] / r["one_body_n"]) for r in rows
                   if r[f"one_body_{law}_s"] >= 0.01] for law in ("frictionless", "coulomb")}
    md = ["# Study 8: two elastic bodies\n\n",
          "Regenerate with `cargo run --release -p tribo --example two_bodies && python scripts/plot_two_bodies.py`"
          "; every number is in `two_bodies.csv`. Two-body Hertz: the Hertz block (E = 200, ν = 0.3) under an "
          "elastic block (−2, 2) × (0, 1), a parabolic gap of radius 1, the upper top pushed down by 0.01; both "
          "graded toward the contact at growth 0.15, non-matching where their sizes differ. The error is the "
          "relative L2 error of λ_n against the plane-strain Hertz pressure of the combined modulus for the "
          "computed force; the half-space model itself is off the finite blocks by a few tenths of a percent "
          "(0.38 % for one body against a rigid cylinder, study 6).\n\n"]
    table = [[r["pair"], r["h_min"], int(r["n_free"]), int(r["q"]), r["force"], r["hertz_l2"], r["frictionless_s"],
              r["coulomb_s"], r["coulomb_status"], int(r["one_body_n"]), r["one_body_frictionless_s"],
              r["one_body_coulomb_s"]] for r in rows]
    md.append(sl.markdown_table(["pair", "h_min", "unknowns", "q", "force", "λ_n error vs Hertz", "frictionless [s]",
                                 "Coulomb [s]", "Coulomb status", "one body: unknowns", "frictionless [s]",
                                 "Coulomb [s]"], table))
    md.append("\nRate of the λ_n error against h_min: " + ", ".join(f"{p} h^{rates[p]:.2f}" for p in pairs) + ".\n\n")
    for law, v in ratio.items():
        if v:
            md.append(f"Time per unknown of a two-body {law} solve over the one-body solve on the lower mesh: "
                      f"{min(v):.2f}–{max(v):.2f} (solves of 10 ms or more).\n\n")
    (out / "two_bodies.md").write_text("".join(md))

    plt = sl.pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    for p in pairs:
        rs = [r for r in rows if r["pair"] == p]
        axes[0].loglog([r["n_free"] for r in rs], [r["hertz_l2"] for r in rs], "o-", label=f"{p}: h^{rates[p]:.2f}")
        axes[1].loglog([r["n_free"] for r in rs], [r["coulomb_s"] for r in rs], "o-", label=f"{p}, Coulomb")
    one = [r for r in rows if r["pair"] == pairs[0]]
    axes[1].loglog([r["one_body_n"] for r in one], [r["one_body_coulomb_s"] for r in one], "k.--",
                   label="one body (lower mesh), Coulomb")
    axes[0].axhline(0.01, color="0.5", lw=0.8, ls=":")
    axes[0].set_ylabel("relative L2 error of λ_n vs two-body Hertz")
    axes[1].set_ylabel("wall time of a fresh solve [s]")
    for ax in axes:
        ax.set_xlabel("unknowns")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "two_bodies.png", dpi=85)
    plt.close(fig)
    return dict(rates=rates, ratio=ratio)


def main(argv: list[str] | None = None) -> dict[str, Any]:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--csv", type=Path, default=sl.DOCS / "two_bodies.csv")
    ap.add_argument("--out", type=Path, default=sl.DOCS)
    args = ap.parse_args(argv)
    return run(args.csv, args.out)


if __name__ == "__main__":
    main()
