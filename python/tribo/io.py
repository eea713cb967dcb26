"""Mesh input through meshio (Gmsh and any format meshio reads) and result output as VTU for ParaView.

Reading: triangles become the mesh (turned counter-clockwise where needed, nodes that no triangle uses
dropped), line cells become named edge sets: Gmsh physical groups (``gmsh:physical`` tags, named by
``field_data``; an unnamed group is called by its tag number), or else meshio's ``cell_sets``.

Writing: ``write_vtu("out/result.vtu", problem, solution)`` writes three files, all with z = 0:

* ``result.vtu``: the body, with point data ``displacement`` (3 components) and ``reaction``, and cell
  data ``stress`` (σ_xx, σ_yy, σ_xy), ``sigma_xx``, ``sigma_yy``, ``sigma_xy`` and ``von_mises``;
* ``result_contact.vtu``: Γ_C as line cells through its FE nodes, with point data ``u_n``, ``slip``,
  ``gap`` and cell data ``sigma_n``, ``sigma_t``;
* ``result_multipliers.vtu``: Γ_C as line cells through the points of T_H, with ``lambda_n``,
  ``lambda_t``, ``friction_threshold`` and ``state`` (0 separation, 1 stick, 2 slip) as point data (P1)
  or cell data (P0).
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from tribo._tribo import Mesh, MeshError, Problem, Solution

__all__ = ["mesh_from_meshio", "read_mesh", "write_vtu", "contact_tables", "write_contact_csv"]


def _line_sets(m: Any) -> dict[str, list[npt.NDArray[np.int64]]]:
    """Named sets of line cells of a meshio mesh, as lists of (E, 2) arrays."""
    sets: dict[str, list[npt.NDArray[np.int64]]] = {}
    physical = m.cell_data.get("gmsh:physical")
    if physical is not None:
        names = {
            int(tag_dim[0]): name
            for name, tag_dim in m.field_data.items()
            if len(tag_dim) >= 2 and int(tag_dim[1]) == 1
        }
        for block, tags in zip(m.cells, physical):
            if block.type != "line":
                continue
            tags = np.asarray(tags)
            for tag in np.unique(tags):
                name = names.get(int(tag), str(int(tag)))
                sets.setdefault(name, []).append(np.asarray(block.data[tags == tag], dtype=np.int64))
        return sets
    for name, per_block in getattr(m, "cell_sets", {}).items():
        for block, idx in zip(m.cells, per_block):
            if block.type == "line" and idx is not None and len(idx) > 0:
                sets.setdefault(name, []).append(np.asarray(block.data[np.asarray(idx)], dtype=np.int64))
    return sets


def mesh_from_meshio(m: Any, *, edge_sets: Mapping[str, str] | None = None) -> Mesh:
    """A tribo Mesh from a ``meshio.Mesh``.

    ``edge_sets`` optionally renames sets: {tribo name: name or tag in the file}.
    Raises MeshError if the mesh has no linear triangles or is not planar.
    """
    points = np.asarray(m.points, dtype=np.float64)
    if points.ndim != 2 or points.shape[1] < 2:
        raise MeshError(f"mesh points must have 2 or 3 coordinates, got shape {points.shape}")
    if points.shape[1] > 2:
        extent = float(np.ptp(points[:, :2], axis=0).max()) if len(points) else 0.0
        if np.any(np.abs(points[:, 2:]) > 1e-12 * max(extent, 1.0)):
            raise MeshError("the mesh is not planar: tribo solves 2D problems in the plane z = 0")
        points = points[:, :2]
    blocks = [np.asarray(b.data, dtype=np.int64) for b in m.cells if b.type == "triangle"]
    others = sorted({b.type for b in m.cells if b.type not in ("triangle", "line", "vertex")})
    if not blocks:
        raise MeshError(f"the mesh has no linear triangles (cell types: {others or 'none'})")
    if others:
        raise MeshError(f"only linear triangles (and line cells for edge sets) are supported, found {others}")
    triangles = np.concatenate(blocks)
    # Counter-clockwise order, as tribo requires.
    p = points[triangles]
    area = (p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1]) - (p[:, 2, 0] - p[:, 0, 0]) * (p[:, 1, 1] - p[:, 0, 1])
    flip = area < 0
    triangles[flip] = triangles[flip][:, [0, 2, 1]]
    # Drop nodes no triangle uses (geometry points, centres of arcs), renumbering the rest.
    used = np.zeros(len(points), dtype=bool)
    used[triangles.ravel()] = True
    renumber = np.cumsum(used) - 1
    sets = {}
    for name, parts in _line_sets(m).items():
        edges = np.concatenate(parts)
        if not used[edges.ravel()].all():
            raise MeshError(f"edge set '{name}' uses a node that belongs to no triangle")
        sets[name] = renumber[edges]
    if edge_sets is not None:
        missing = [src for src in edge_sets.values() if src not in sets]
        if missing:
            raise MeshError(f"the mesh file has no edge set {missing} (it has: {', '.join(sorted(sets))})")
        sets = {dst: sets[src] for dst, src in edge_sets.items()}
    return Mesh(points[used], renumber[triangles], sets)


def read_mesh(path: str | Path, *, edge_sets: Mapping[str, str] | None = None) -> Mesh:
    """Reads any mesh meshio can read (Gmsh .msh, VTK, XDMF, MED…) into a tribo Mesh."""
    import meshio

    try:
        m = meshio.read(str(path))
    except Exception as e:  # meshio raises a variety of errors for unreadable files
        raise MeshError(f"cannot read mesh file {path}: {e}") from e
    return mesh_from_meshio(m, edge_sets=edge_sets)


def _xyz(p: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    return np.column_stack([p, np.zeros(len(p))])


def write_vtu(path: str | Path, problem: Problem, solution: Solution) -> list[Path]:
    """Writes the body, Γ_C and the multiplier fields as three VTU files; returns their paths."""
    import meshio

    path = Path(path)
    stem = path.with_suffix("")
    mesh = problem.mesh
    stress = solution.stress
    body = meshio.Mesh(
        _xyz(mesh.points),
        [("triangle", mesh.triangles)],
        point_data={"displacement": _xyz(solution.displacement), "reaction": _xyz(solution.reactions)},
        cell_data={
            "stress": [stress],
            "sigma_xx": [stress[:, 0]],
            "sigma_yy": [stress[:, 1]],
            "sigma_xy": [stress[:, 2]],
            "von_mises": [solution.von_mises],
        },
    )
    n = len(solution.node_abscissae)
    lines = np.column_stack([np.arange(n - 1), np.arange(1, n)])
    contact = meshio.Mesh(
        _xyz(problem.contact_points(solution.node_abscissae)),
        [("line", lines)],
        point_data={"u_n": solution.u_n, "slip": solution.slip, "gap": solution.gap},
        cell_data={"sigma_n": [solution.sigma_n], "sigma_t": [solution.sigma_t]},
    )
    xi = problem.multiplier_mesh
    k = len(xi)
    fields = {
        "lambda_n": solution.lambda_n,
        "lambda_t": solution.lambda_t,
        "friction_threshold": solution.friction_threshold,
        "state": solution.states.astype(np.int32),
    }
    mlines = np.column_stack([np.arange(k - 1), np.arange(1, k)])
    if problem.space == "P1":
        multipliers = meshio.Mesh(_xyz(problem.contact_points(xi)), [("line", mlines)], point_data=fields)
    else:
        multipliers = meshio.Mesh(
            _xyz(problem.contact_points(xi)), [("line", mlines)], cell_data={k: [v] for k, v in fields.items()}
        )
    paths = [path, Path(f"{stem}_contact.vtu"), Path(f"{stem}_multipliers.vtu")]
    for p, m in zip(paths, [body, contact, multipliers]):
        p.parent.mkdir(parents=True, exist_ok=True)
        meshio.write(str(p), m, file_format="vtu")
    return paths


def contact_tables(problem: Problem, solution: Solution) -> dict[str, dict[str, npt.NDArray[Any]]]:
    """The contact fields as three tables (name -> column -> array), one per kind of place on Γ_C:
    ``multipliers`` (dofs of λ), ``nodes`` (FE nodes) and ``edges`` (FE edges)."""
    xm = solution.multiplier_abscissae
    pm = problem.contact_points(xm)
    xn = solution.node_abscissae
    pn = problem.contact_points(xn)
    xe = solution.edge_abscissae
    pe = problem.contact_points(xe)
    return {
        "multipliers": {
            "xi": xm,
            "x": pm[:, 0],
            "y": pm[:, 1],
            "lambda_n": solution.lambda_n,
            "lambda_t": solution.lambda_t,
            "friction_threshold": solution.friction_threshold,
            "state": np.asarray(solution.state_names),
        },
        "nodes": {"xi": xn, "x": pn[:, 0], "y": pn[:, 1], "u_n": solution.u_n, "slip": solution.slip, "gap": solution.gap},
        "edges": {"xi": xe, "x": pe[:, 0], "y": pe[:, 1], "sigma_n": solution.sigma_n, "sigma_t": solution.sigma_t},
    }


def write_contact_csv(directory: str | Path, problem: Problem, solution: Solution) -> list[Path]:
    """Writes ``contact.csv`` (per multiplier dof), ``contact_nodes.csv`` and ``contact_edges.csv``."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    names = {"multipliers": "contact.csv", "nodes": "contact_nodes.csv", "edges": "contact_edges.csv"}
    paths = []
    for key, table in contact_tables(problem, solution).items():
        path = directory / names[key]
        columns = list(table)
        with path.open("w", encoding="utf-8") as f:
            f.write(",".join(columns) + "\n")
            for row in zip(*(table[c] for c in columns)):
                f.write(",".join(v if isinstance(v, str) else repr(float(v)) for v in row) + "\n")
        paths.append(path)
    return paths
