"""Shared pieces of the studies in scripts/: the Hertz scene, the error measures and the output helpers.

The scene is `tribo/scenes/hertz.toml`, the one the Rust and Python tests read: a rigid cylinder R = 1
pushed `approach` into the block (−2, 2) × (−2, 0), clamped at the bottom, contact on the top, E = 200,
ν = 0.3. The error measures mirror the Rust tests:

* ``lambda_l2_error``: relative L2 error of λ_n against the plane-strain Hertz pressure of the computed
  force (a² = 4PR(1−ν²)/(πE), p_max = 2P/(πa)), 8-point Gauss on every segment of the union of T_H, the
  FE nodes of Γ_C and ±a (so the square-root edge of the pressure sits on a breakpoint);
* ``oscillation``: total variation of the λ_n dof values over that of the Hertz pressure (2 p_max);
* ``energy_error``: ‖u_ref − I u_h‖_K / ‖u_ref‖_K on a fine reference mesh, I the P1 interpolation of the
  coarse displacement at the fine nodes (matplotlib.tri.LinearTriInterpolator), the norm the core's
  (``Problem.energy_norm``).
"""

from __future__ import annotations

import argparse
import csv
import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

import tribo
from tribo.scene import load_scene, scene_path

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
HERTZ = load_scene(scene_path("hertz"))
YOUNG, POISSON = float(HERTZ.get("material", "young")), float(HERTZ.get("material", "poisson"))
RADIUS = float(HERTZ.get("obstacle", "radius"))
BOX = (tuple(HERTZ.get("body", "x")), tuple(HERTZ.get("body", "y")))
SEGMENT = tuple(HERTZ.get("discretization", "grading"))

# Gauss–Legendre, 8 points on [−1, 1].
GAUSS_X, GAUSS_W = np.polynomial.legendre.leggauss(8)


def uniform_mesh(nx: int) -> tribo.Mesh:
    """Rectangle nx × nx/2 on (−2, 2) × (−2, 0): square cells of side h = 4/nx, right diagonals."""
    return tribo.Mesh.rectangle(*BOX, nx, nx // 2)


def graded_mesh(h_min: float, h_max: float = 0.5, growth: float = 0.3) -> tribo.Mesh:
    """Mesh graded toward the scene's segment of the top side ([−0.3, 0.3])."""
    return tribo.Mesh.graded_rectangle(*BOX, side="top", segment=SEGMENT, h_min=h_min, h_max=h_max, growth=growth)


# A converged reference mesh of the Hertz scene: graded toward [c − 0.1, c + 0.1] around the cylinder's centre
# c (the contact zone, a ≈ 0.07, with room for a shift), at growth 0.03, whose own bias is far below the
# errors measured (175k unknowns; halving h_min at growth 0.02, 466k unknowns, moves λ_n by 0.05 %). A
# growth-0.3 reference would carry that grading's 1.4 % bias in λ_n into every error (study 6).
REFERENCE = dict(h_min=0.0003125, h_max=0.05, growth=0.03, half=0.1)
SMOKE_REFERENCE = dict(h_min=0.005, h_max=0.1, growth=0.3, half=0.1)


def reference_mesh(center: float = 0.0, spec: dict[str, float] = REFERENCE) -> tribo.Mesh:
    """The reference mesh (``REFERENCE``) for the cylinder at x = `center`."""
    return tribo.Mesh.graded_rectangle(*BOX, side="top", segment=(center - spec["half"], center + spec["half"]),
                                       h_min=spec["h_min"], h_max=spec["h_max"], growth=spec["growth"])


def hertz_problem(
    mesh: tribo.Mesh,
    *,
    approach: float = 0.01,
    shift: float = 0.0,
    space: str = "P1",
    ratio: float = 1.0,
    poisson: float = POISSON,
) -> tribo.Problem:
    """The Hertz problem on `mesh`; T_H has size ratio × the FE edge size (H/h = ratio)."""
    return tribo.Problem(
        mesh,
        young=YOUNG,
        poisson=poisson,
        clamped="bottom",
        contact="top",
        obstacle=tribo.Obstacle.circle(RADIUS),
        approach=approach,
        shift=shift,
        space=space,  # type: ignore[arg-type]
        multiplier_ratio=ratio,
    )


def hertz_pressure(force: float, poisson: float = POISSON) -> tuple[Callable[[np.ndarray], np.ndarray], float, float]:
    """Plane-strain Hertz pressure p(x) of total force `force` per unit depth, its half-width a and p_max."""
    a = math.sqrt(4.0 * force * RADIUS * (1.0 - poisson**2) / (math.pi * YOUNG))
    pmax = 2.0 * force / (math.pi * a)

    def p(x: np.ndarray) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        return np.where(np.abs(x) < a, pmax * np.sqrt(np.clip(1.0 - (x / a) ** 2, 0.0, None)), 0.0)

    return p, a, pmax


def _gauss_points(breaks: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Gauss points and weights of the 8-point rule on every segment between sorted unique breakpoints."""
    b = np.unique(breaks)
    h, m = 0.5 * np.diff(b), 0.5 * (b[1:] + b[:-1])
    x = (m[:, None] + h[:, None] * GAUSS_X[None, :]).ravel()
    w = (h[:, None] * GAUSS_W[None, :]).ravel()
    return x, w


def contact_breaks(problem: tribo.Problem) -> np.ndarray:
    """T_H points, multiplier dof positions and FE nodes of Γ_C."""
    return np.concatenate([problem.multiplier_mesh, problem.multiplier_abscissae, problem.node_abscissae])


def lambda_l2_error(problem: tribo.Problem, sol: tribo.Solution, poisson: float = POISSON) -> float:
    """Relative L2 error of λ_n against the Hertz pressure of the computed force (nan if no force)."""
    if sol.normal_force <= 0.0:
        return math.nan
    p, a, _ = hertz_pressure(sol.normal_force, poisson)
    x, w = _gauss_points(np.concatenate([contact_breaks(problem), [-a, a]]))
    lam = problem.evaluate_multiplier(sol.lambda_n, x)
    ref = p(x)
    return float(np.sqrt(np.sum(w * (lam - ref) ** 2) / np.sum(w * ref**2)))


def sigma_pieces(problem: tribo.Problem, sol: tribo.Solution) -> tuple[np.ndarray, np.ndarray]:
    """Breakpoints (sorted FE nodes of Γ_C) and the contact pressure −σ_n(u_h), constant on each edge."""
    nodes = np.sort(problem.node_abscissae)
    order = np.argsort(sol.edge_abscissae)
    mids = np.asarray(sol.edge_abscissae)[order]
    if len(nodes) != len(mids) + 1 or not np.all((mids > nodes[:-1]) & (mids < nodes[1:])):
        raise RuntimeError("contact edges are not the segments between consecutive contact nodes")
    return nodes, -np.asarray(sol.sigma_n)[order]


def sigma_l2_error(problem: tribo.Problem, sol: tribo.Solution, poisson: float = POISSON) -> float:
    """Relative L2 error of −σ_n(u_h) (piecewise constant on the FE edges) against the Hertz pressure."""
    if sol.normal_force <= 0.0:
        return math.nan
    p, a, _ = hertz_pressure(sol.normal_force, poisson)
    nodes, values = sigma_pieces(problem, sol)
    x, w = _gauss_points(np.concatenate([nodes, [-a, a]]))
    s = values[np.clip(np.searchsorted(nodes, x) - 1, 0, len(values) - 1)]
    ref = p(x)
    return float(np.sqrt(np.sum(w * (s - ref) ** 2) / np.sum(w * ref**2)))


def oscillation(sol: tribo.Solution, poisson: float = POISSON) -> float:
    """TV(λ_n dofs) / (2 p_max): about 1 for a smooth single-peaked pressure, much more for a checkerboard."""
    if sol.normal_force <= 0.0:
        return math.nan
    _, _, pmax = hertz_pressure(sol.normal_force, poisson)
    order = np.argsort(sol.multiplier_abscissae)
    return float(np.sum(np.abs(np.diff(np.asarray(sol.lambda_n)[order]))) / (2.0 * pmax))


@dataclass
class Reference:
    """A fine solution with what the error measures need."""

    problem: tribo.Problem
    solution: tribo.Solution
    energy: float  # ‖u_ref‖_K

    def lambda_n_error(self, problem: tribo.Problem, sol: tribo.Solution) -> float:
        """Relative L2 error of λ_n against the reference λ_n."""
        x, w = _gauss_points(np.concatenate([contact_breaks(problem), contact_breaks(self.problem)]))
        mine = problem.evaluate_multiplier(sol.lambda_n, x)
        ref = self.problem.evaluate_multiplier(self.solution.lambda_n, x)
        return float(np.sqrt(np.sum(w * (mine - ref) ** 2) / np.sum(w * ref**2)))

    def sigma_n_error(self, problem: tribo.Problem, sol: tribo.Solution) -> float:
        """Relative L2 error of −σ_n(u_h) against the reference λ_n."""
        nodes, values = sigma_pieces(problem, sol)
        x, w = _gauss_points(np.concatenate([nodes, contact_breaks(self.problem)]))
        x, w = x[(x > nodes[0]) & (x < nodes[-1])], w[(x > nodes[0]) & (x < nodes[-1])]
        s = values[np.clip(np.searchsorted(nodes, x) - 1, 0, len(values) - 1)]
        ref = self.problem.evaluate_multiplier(self.solution.lambda_n, x)
        return float(np.sqrt(np.sum(w * (s - ref) ** 2) / np.sum(w * ref**2)))

    def energy_error(self, problem: tribo.Problem, sol: tribo.Solution) -> float:
        """‖u_ref − I u_h‖_K / ‖u_ref‖_K on the reference mesh."""
        iu = interpolate(problem.mesh, np.asarray(sol.displacement), self.problem.mesh.points)
        diff = np.asarray(self.solution.displacement) - iu
        return self.problem.energy_norm(diff) / self.energy


def make_reference(problem: tribo.Problem, **solve: Any) -> Reference:
    sol = problem.solve(**solve)
    if sol.report.status != "converged":
        raise RuntimeError(f"the reference solve did not converge: {sol.report.status}")
    return Reference(problem, sol, problem.energy_norm(sol.displacement))


def interpolate(mesh: tribo.Mesh, u: np.ndarray, points: np.ndarray) -> np.ndarray:
    """P1 interpolation of the nodal field u of `mesh` at `points`."""
    import matplotlib.tri as mtri

    tri = mtri.Triangulation(mesh.points[:, 0], mesh.points[:, 1], mesh.triangles)
    out = np.empty((len(points), 2))
    for k in range(2):
        vals = mtri.LinearTriInterpolator(tri, u[:, k])(points[:, 0], points[:, 1])
        if np.ma.is_masked(vals) and np.any(np.ma.getmaskarray(vals)):
            raise RuntimeError("a point lies outside the coarse mesh")
        out[:, k] = np.asarray(vals)
    return out


def timed(fn: Callable[[], Any]) -> tuple[Any, float]:
    """(fn(), wall seconds)."""
    t = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t


def fitted_rate(x: Sequence[float], y: Sequence[float]) -> float:
    """Least-squares slope of log y against log x."""
    return float(np.polyfit(np.log(np.asarray(x, float)), np.log(np.asarray(y, float)), 1)[0])


def markdown_table(headers: Sequence[str], rows: Sequence[Sequence[Any]]) -> str:
    """A GitHub markdown table; floats printed with 3 significant digits."""

    def fmt(v: Any) -> str:
        if isinstance(v, float):
            return "nan" if math.isnan(v) else f"{v:.3g}"
        return str(v)

    lines = ["| " + " | ".join(headers) + " |", "|" + "|".join("---" for _ in headers) + "|"]
    lines += ["| " + " | ".join(fmt(v) for v in row) + " |" for row in rows]
    return "\n".join(lines) + "\n"


def effectivity_summary(effectivity: Sequence[float], in_contact: Sequence[int]) -> str:
    """One paragraph on effectivity indices over levels: their range, max/min and drift from the first to the
    last, over every level with a finite index and over those whose contact zone holds at least
    ``tribo.checks.MIN_CONTACT_DOFS`` multiplier dofs (below it every solve warns that the zone is barely
    resolved)."""
    from tribo.checks import MIN_CONTACT_DOFS

    def line(what: str, e: list[float]) -> str:
        if not e:
            return f"{what}: none.\n"
        return (f"{what}: energy effectivity from {min(e):.3g} to {max(e):.3g} (max/min {max(e) / min(e):.3g}, "
                f"first to last {e[-1] / e[0] - 1:+.0%}).\n")

    finite = [(e, c) for e, c in zip(effectivity, in_contact, strict=True) if math.isfinite(e)]
    resolved = [e for e, c in finite if c >= MIN_CONTACT_DOFS]
    return ("\n" + line(f"Over {len(finite)} levels", [e for e, _ in finite]) + "\n"
            + line(f"Over the {len(resolved)} levels with at least {MIN_CONTACT_DOFS} multiplier dofs in contact",
                   resolved))


def write_csv(path: Path, headers: Sequence[str], rows: Sequence[Sequence[Any]]) -> None:
    """Floats to 6 significant digits; a value holding a comma is quoted (the csv module's dialect)."""
    with open(path, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(headers)
        w.writerows([f"{v:.6g}" if isinstance(v, float) else str(v) for v in r] for r in rows)


def write_page(path: Path, title: str, doc: str, regenerate: str, table: str) -> None:
    """A study's Markdown page: its title, what it measures (the second paragraph of its docstring), how to
    regenerate it and what it found, then its table."""
    path.write_text("\n\n".join([f"# {title}", doc.split("\n\n")[1], regenerate, table]) + "\n")


def pyplot() -> Any:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def csv_study_args(doc: str | None, folder: str, argv: list[str] | None = None) -> argparse.Namespace:
    """The command line of a study drawn from the CSV files of a Rust example: ``--csv-dir`` (default
    ``docs/<folder>``) and ``--out`` (default docs/)."""
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--csv-dir", type=Path, default=DOCS / folder, help=f"input (default docs/{folder})")
    ap.add_argument("--out", type=Path, default=DOCS, help="output directory (default docs/)")
    return ap.parse_args(argv)


def effectivity_axes(ax: Any, band: tuple[float, float]) -> None:
    """An axis of effectivities (estimate over true error) against unknowns: both logarithmic, the band shaded,
    ticks at 1, 1.5, 2 and 3."""
    plt = pyplot()
    ax.axhspan(*band, color="0.9", zorder=0)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_yticks([1, 1.5, 2, 3], ["1", "1.5", "2", "3"])
    ax.yaxis.set_minor_formatter(plt.NullFormatter())
    ax.set_xlabel("unknowns")


def read_csv_rows(path: Path) -> list[dict[str, str]]:
    """The rows of a CSV file as dicts by its header; a row cut short (a run killed while writing) or too long is
    an error naming the file and the line."""
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        rows = []
        for r in reader:
            if None in r or None in r.values():
                raise ValueError(f"{path.name}, line {reader.line_num}: not as many fields as the header")
            rows.append(r)
    return rows


def smaller(a: float, b: float) -> float:
    """The smaller of two estimates as the adaptive stop takes it (Rust's ``f64::min``): a NaN one (not computed)
    gives way to the other."""
    return b if math.isnan(a) else a if math.isnan(b) else min(a, b)


def commands_block(doc: str) -> str:
    """The third paragraph of a study's docstring (its indented commands) as a bash code block."""
    return "```bash\n" + doc.split("\n\n")[2].replace("    ", "", 1).replace("\n    ", "\n").strip() + "\n```"


def cli(run: Callable[[bool, Path], Any], doc: str | None, argv: list[str] | None = None) -> Any:
    """The command line every study shares: ``--smoke`` (tiny configuration) and ``--out DIR``."""
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--smoke", action="store_true", help="tiny configuration (seconds)")
    ap.add_argument("--out", type=Path, default=DOCS, help="output directory (default docs/)")
    args = ap.parse_args(argv)
    return run(args.smoke, args.out)
