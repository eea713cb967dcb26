"""Mesh input through meshio (Gmsh and any format meshio reads) and result output as VTU for ParaView.

Reading: triangles become the mesh (turned counter-clockwise where needed, nodes that no triangle uses
dropped), line cells become named edge sets: Gmsh physical groups (``gmsh:physical`` tags, named by
``field_data``; an unnamed group is called by its tag number), or else meshio's ``cell_sets``. Named sets of
triangles (physical surfaces) are read apart, as masks (``read_triangle_groups``): the regions of a body of
several materials.

Writing: ``write_vtu("out/result.vtu", problem, solution)`` writes three files, all with z = 0:

* ``result.vtu``: the body, with point data ``displacement`` (3 components), ``reaction``,
  ``stress_recovered`` (σ_xx, σ_yy, σ_xy per node: the area-weighted mean of the cell stresses around it,
  ``Solution.nodal_stress``), ``von_mises_recovered`` and, in the mixed formulation, ``pressure`` (p per
  node, σ = 2μ ε − p I), and cell
  data ``stress``, the full symmetric 3 × 3 stress tensor (9 components, which ParaView reads as a tensor:
  σ_xz = σ_yz = 0 and σ_zz = ν (σ_xx + σ_yy) in plane strain, 0 in plane stress, the hoop stress σ_θθ in
  axisymmetry, where x is r and y the axis, and ``sigma_hoop`` repeats it), its components ``sigma_xx``,
  ``sigma_yy``, ``sigma_xy``, ``sigma_zz``, ``von_mises``, ``error_indicator`` (the a posteriori η_K),
  ``traction_indicator`` (ζ_K, each triangle's part of the estimated error of the contact tractions) and
  ``body`` (0, or for two bodies the body's index in ``problem.bodies``) and ``material`` (each triangle's
  index into ``problem.materials``: its region); for two bodies, ``u_n`` and
  ``slip`` below are the jump between them and the gap is the initial one between the two lines;
* ``result_contact.vtu``: Γ_C as line cells through its FE nodes, with point data ``u_n``, ``slip``,
  ``gap`` (g = g0 − δ: where the obstacle is, along n), ``current_gap`` (g − u_n: 0 in contact) and
  ``obstacle`` (the obstacle's surface point facing the node, 3 components), and cell data ``sigma_n``,
  ``sigma_t``;
* ``result_multipliers.vtu``: Γ_C as line cells through the points of T_H, with ``lambda_n``,
  ``lambda_t``, ``friction_threshold`` and ``state`` (0 separation, 1 stick, 2 slip) as point data (P1)
  or cell data (P0);
* for two bodies, also ``result_<name>.vtu`` per body (its nodes and triangles with the fields above) and
  ``result.vtm``, the ParaView multiblock of them (``per_body=False`` skips these: the history series
  keep the joined mesh, whose cell data ``body`` tells the bodies apart).
"""

from __future__ import annotations

import contextlib
import io
import os
import threading
import zlib
from collections.abc import Iterator, Mapping, Sequence
from pathlib import Path
from typing import Any
from xml.sax.saxutils import quoteattr

import numpy as np
import numpy.typing as npt

from tribo._tribo import Mesh
from tribo.errors import MeshError
from tribo.checks import conventions, obstacle_points
from tribo.problem import Problem
from tribo.results import Solution, at_points

__all__ = [
    "mesh_from_meshio",
    "read_mesh",
    "read_triangle_groups",
    "triangle_groups",
    "write_vtu",
    "contact_tables",
    "write_contact_csv",
    "stress_tensor",
    "obstacle_points",
]


def write_text_atomic(path: Path, text: str) -> None:
    """Writes ``text`` (UTF-8) to ``path`` whole or not at all: into a temporary file beside it, then renamed
    over it, so that a reader never sees half a file (defect D33: one sweep case's copy read another's
    half-written ``summary.json``)."""
    tmp = path.with_name(f".{path.name}.{os.getpid()}.{threading.get_ident()}.tmp")
    tmp.write_text(text, encoding="utf-8")
    tmp.replace(path)


def _mesh_error(message: str, kind: str, **details: Any) -> MeshError:
    """A MeshError with the ``kind`` and ``details`` the core's errors carry, so callers can rely on them."""
    e = MeshError(message)
    e.kind = kind
    e.details = details
    return e


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
                sets.setdefault(name, []).append(_cells(block.data[tags == tag], 2, f"edge set '{name}'"))
        return sets
    for name, per_block in getattr(m, "cell_sets", {}).items():
        for block, idx in zip(m.cells, per_block):
            if block.type == "line" and idx is not None and len(idx) > 0:
                idx = np.asarray(idx)
                if not np.issubdtype(idx.dtype, np.integer) or idx.min() < 0 or idx.max() >= len(block.data):
                    raise _mesh_error(
                        f"cell set '{name}' refers to line cells outside 0…{len(block.data) - 1}",
                        "BadCellSet",
                        name=name,
                    )
                sets.setdefault(name, []).append(_cells(block.data[idx], 2, f"edge set '{name}'"))
    return sets


def _cells(data: Any, corners: int, what: str) -> npt.NDArray[np.int64]:
    """A block of cells as an (N, corners) int64 array; refuses other shapes and non-integer indices."""
    a = np.asarray(data)
    if a.ndim != 2 or a.shape[1] != corners or not (np.issubdtype(a.dtype, np.integer) or a.size == 0):
        raise _mesh_error(
            f"the cells of {what} must be an (N, {corners}) array of node indices, got shape {a.shape} of {a.dtype}",
            "BadInput",
        )
    return a.astype(np.int64)


def _check_indices(cells: npt.NDArray[np.int64], n_nodes: int, what: str) -> None:
    """Refuses a node index outside 0…n_nodes−1. Numpy would wrap −1 (what meshio's Gmsh reader writes for
    a node tag the file does not define) to the last node, and raise IndexError beyond the end.
    ``what`` names a cell, with ``{}`` for its number (counted from 0 in file order)."""
    bad = np.argwhere((cells < 0) | (cells >= n_nodes))
    if len(bad):
        row, col = (int(i) for i in bad[0])
        node = int(cells[row, col])
        hint = " (the file refers to a node it does not define)" if node < 0 else ""
        raise _mesh_error(
            f"{what.format(row)} uses node {node}, but the mesh has {n_nodes} nodes (0 to {n_nodes - 1}){hint}",
            "NodeIndexOutOfRange",
            element=row,
            node=node,
            n_nodes=n_nodes,
        )


def _check_no_overlap(points: npt.NDArray[np.float64], triangles: npt.NDArray[np.int64]) -> None:
    """Refuses overlapping triangles, which no later check can see once every triangle is turned
    counter-clockwise: two triangles that run along one edge in the same direction (one folded onto the
    other), or triangles that turn more than once around a node, or not exactly once around a node inside
    the mesh. A reader that maps two node tags to one node (meshio with a Gmsh node tag 0) makes such a mesh.
    Triangles are numbered from 0 in file order, nodes as in the file."""
    directed = triangles[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    _, first, inverse, count = np.unique(directed, axis=0, return_index=True, return_inverse=True, return_counts=True)
    inverse = inverse.reshape(-1)
    if (count > 1).any():
        edge = int(np.flatnonzero(count > 1)[0])
        a, b = (int(t) for t in np.flatnonzero(inverse == edge)[:2] // 3)
        i, j = (int(n) for n in directed[first[edge]])
        raise _mesh_error(
            f"triangles {a} and {b} overlap: both run from node {i} to node {j} once turned counter-clockwise",
            "OverlappingTriangles",
            triangles=[a, b],
            edge=[i, j],
        )
    p = points[triangles]
    u, v = np.roll(p, -1, axis=1) - p, np.roll(p, 1, axis=1) - p
    with np.errstate(all="ignore"):
        cross = u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]
        angle = np.arctan2(np.abs(cross), np.einsum("tck,tck->tc", u, v))
        # Each angle comes from coordinate differences that carry a relative error of eps · (scale / length).
        scale = float(np.abs(p).max()) if p.size else 0.0
        shortest = np.minimum(np.hypot(u[..., 0], u[..., 1]), np.hypot(v[..., 0], v[..., 1]))
        rounding = 8.0 * np.finfo(np.float64).eps * (1.0 + scale / shortest)
    n = len(points)
    turn = np.bincount(triangles.ravel(), weights=angle.ravel(), minlength=n)
    tol = np.bincount(triangles.ravel(), weights=rounding.ravel(), minlength=n)
    undirected = np.sort(directed, axis=1)
    _, edge_of, uses = np.unique(undirected, axis=0, return_inverse=True, return_counts=True)
    on_boundary = np.zeros(n, dtype=bool)
    on_boundary[undirected[uses[edge_of.reshape(-1)] == 1].ravel()] = True
    used = np.zeros(n, dtype=bool)
    used[triangles.ravel()] = True
    wrong = used & ((turn > 2.0 * np.pi + tol) | (~on_boundary & (np.abs(turn - 2.0 * np.pi) > tol)))
    if wrong.any():
        node = int(np.flatnonzero(wrong)[0])
        raise _mesh_error(
            f"the triangles around node {node} overlap: their angles there add up to {turn[node] / np.pi:.6g}π"
            f" instead of {'at most ' if on_boundary[node] else ''}2π",
            "OverlappingTriangles",
            node=node,
            angle=float(turn[node]),
        )


def mesh_from_meshio(m: Any, *, edge_sets: Mapping[str, str] | None = None) -> Mesh:
    """A tribo Mesh from a ``meshio.Mesh``.

    ``edge_sets`` optionally renames sets: {tribo name: name or tag in the file}.
    Raises MeshError if the mesh has no linear triangles or is not planar, if a cell refers to a node the
    mesh does not have, or if triangles overlap (the orientation fix below would otherwise hide it).
    """
    points = np.asarray(m.points, dtype=np.float64)
    if points.ndim != 2 or points.shape[1] < 2:
        raise _mesh_error(f"mesh points must have 2 or 3 coordinates, got shape {points.shape}", "BadInput")
    if points.shape[1] > 2:
        extent = float(np.ptp(points[:, :2], axis=0).max()) if len(points) else 0.0
        if np.any(np.abs(points[:, 2:]) > 1e-12 * max(extent, 1.0)):
            raise _mesh_error("the mesh is not planar: tribo solves 2D problems in the plane z = 0", "NotPlanar")
        points = points[:, :2]
    blocks = [_cells(b.data, 3, "the triangles") for b in m.cells if b.type == "triangle"]
    others = sorted({b.type for b in m.cells if b.type not in ("triangle", "line", "vertex")})
    if not blocks:
        raise _mesh_error(f"the mesh has no linear triangles (cell types: {others or 'none'})", "EmptyMesh")
    if others:
        raise _mesh_error(
            f"only linear triangles (and line cells for edge sets) are supported, found {others}", "UnsupportedCells"
        )
    triangles = np.concatenate(blocks)
    _check_indices(triangles, len(points), "triangle {}")
    # Counter-clockwise order, as tribo requires.
    p = points[triangles]
    area = (p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1]) - (p[:, 2, 0] - p[:, 0, 0]) * (p[:, 1, 1] - p[:, 0, 1])
    flip = area < 0
    triangles[flip] = triangles[flip][:, [0, 2, 1]]
    _check_no_overlap(points, triangles)
    # Drop nodes no triangle uses (geometry points, centres of arcs), renumbering the rest.
    used = np.zeros(len(points), dtype=bool)
    used[triangles.ravel()] = True
    renumber = np.cumsum(used) - 1
    sets = {}
    for name, parts in _line_sets(m).items():
        edges = np.concatenate(parts)
        _check_indices(edges, len(points), f"line {{}} of edge set '{name}'")
        if not used[edges.ravel()].all():
            raise _mesh_error(f"edge set '{name}' uses a node that belongs to no triangle", "NotABoundaryEdge", name=name)
        sets[name] = renumber[edges]
    if edge_sets is not None:
        missing = [src for src in edge_sets.values() if src not in sets]
        if missing:
            raise _mesh_error(
                f"the mesh file has no edge set {missing} (it has: {', '.join(sorted(sets))})",
                "UnknownEdgeSet",
                names=missing,
            )
        sets = {dst: sets[src] for dst, src in edge_sets.items()}
    return Mesh(points[used], renumber[triangles], sets)


def _blank(path: Path) -> bool:
    """Whether a file holds nothing but whitespace (read until its first other byte: one block for a mesh)."""
    with path.open("rb") as f:
        while block := f.read(1 << 16):
            if block.strip():
                return False
    return True


def _read_meshio(path: Path) -> Any:
    """The meshio mesh of a file; every failure to read is a MeshError naming the file (``read_mesh``)."""
    import meshio

    try:
        blank = path.is_file() and _blank(path)
    except OSError:
        blank = False  # meshio says why it cannot read the file
    if blank:
        raise _mesh_error(f"cannot read mesh file {path}: the file is empty", "UnreadableFile", path=str(path))
    said = io.StringIO()
    try:
        with contextlib.redirect_stdout(said), contextlib.redirect_stderr(said):
            return meshio.read(str(path))
    except (Exception, SystemExit) as e:
        output = " ".join(said.getvalue().split()).removeprefix("Error: ")
        reason = (str(e) if not isinstance(e, SystemExit) else "") or output or type(e).__name__
        raise _mesh_error(f"cannot read mesh file {path}: {reason}", "UnreadableFile", path=str(path)) from e


def read_mesh(path: str | Path, *, edge_sets: Mapping[str, str] | None = None) -> Mesh:
    """Reads any mesh meshio can read (Gmsh .msh, VTK, XDMF, MED…) into a tribo Mesh.

    Every failure to read is a MeshError naming the file. meshio raises many exception types, prints to
    stdout and stderr, calls ``sys.exit`` when no reader accepts a file, and loops forever on a TetGen
    file that is empty or blank: a blank file is refused first, the rest is caught and meshio's output kept
    for the message.
    """
    path = Path(path)
    m = _read_meshio(path)
    try:
        return mesh_from_meshio(m, edge_sets=edge_sets)
    except MeshError as e:
        e.add_note(f"in mesh file {path}")
        raise


def triangle_groups(m: Any) -> dict[str, npt.NDArray[np.bool_]]:
    """The named sets of triangles of a ``meshio.Mesh``, each as a mask over the triangles of the tribo Mesh
    that ``mesh_from_meshio`` makes of it (the triangle blocks in file order): Gmsh physical surfaces
    (``gmsh:physical`` tags of triangles, named by ``field_data``; an unnamed group by its tag number), or
    else meshio's ``cell_sets``. For a body of several materials: ``regions[groups["coating"]] = 1``."""
    blocks = [k for k, b in enumerate(m.cells) if b.type == "triangle"]
    offsets = np.cumsum([0] + [len(m.cells[k].data) for k in blocks])
    groups: dict[str, npt.NDArray[np.bool_]] = {}
    physical = m.cell_data.get("gmsh:physical")
    if physical is not None:
        names = {int(td[0]): name for name, td in m.field_data.items() if len(td) >= 2 and int(td[1]) == 2}
        tags = np.concatenate([np.asarray(physical[k]).reshape(-1) for k in blocks] or [np.zeros(0, np.int64)])
        for tag in np.unique(tags):
            groups[names.get(int(tag), str(int(tag)))] = tags == tag
        return groups
    for name, per_block in getattr(m, "cell_sets", {}).items():
        mask = np.zeros(int(offsets[-1]), dtype=bool)
        for k, start in zip(blocks, offsets[:-1]):
            idx = per_block[k]
            if idx is not None and len(idx) > 0:
                idx = np.asarray(idx)
                if not np.issubdtype(idx.dtype, np.integer) or idx.min() < 0 or idx.max() >= len(m.cells[k].data):
                    raise _mesh_error(f"cell set '{name}' refers to triangles outside its block", "BadCellSet", name=name)
                mask[start + idx] = True
        if mask.any():
            groups[name] = mask
    return groups


def read_triangle_groups(path: str | Path) -> dict[str, npt.NDArray[np.bool_]]:
    """``triangle_groups`` of a mesh file, over the triangles of ``read_mesh(path)``."""
    return triangle_groups(_read_meshio(Path(path)))


# meshio's VTU writer compresses each array with the ``zlib`` module at zlib's default level (6) and has no
# setting for it; the compression is most of the writing (study 19, docs/output_cost.md). tribo's writers
# compress with zlib's run-length strategy instead (``Z_RLE``: a standard deflate stream that any zlib reads):
# measured on the demo's body file, 3.8 times as fast as level 6 (2.4 times level 1) for files 7 % larger. The
# module meshio reads is replaced by a stand-in that does so only in a thread inside ``_fast_compression()``
# (tribo writing) and compresses as zlib does everywhere else: a program that imports tribo writes its own
# files unchanged.
_FAST = threading.local()


def _compress_fast(data: bytes) -> bytes:
    """``data`` deflated with zlib's run-length strategy (level 1, the default window and memory)."""
    c = zlib.compressobj(1, zlib.DEFLATED, zlib.MAX_WBITS, zlib.DEF_MEM_LEVEL, zlib.Z_RLE)
    return c.compress(data) + c.flush()


class _Zlib:
    """Stands in for the ``zlib`` module in meshio's VTU writer (see ``_fast_compression``)."""

    @staticmethod
    def compress(data: bytes, /, level: int = zlib.Z_DEFAULT_COMPRESSION, **kw: Any) -> bytes:
        if getattr(_FAST, "on", False) and level == zlib.Z_DEFAULT_COMPRESSION and not kw:
            return _compress_fast(data)
        return zlib.compress(data, level, **kw)

    def __getattr__(self, name: str) -> Any:
        return getattr(zlib, name)


@contextlib.contextmanager
def _fast_compression() -> Iterator[None]:
    """Within it, meshio's VTU writer compresses with ``_compress_fast`` in this thread. Where meshio's writer
    no longer reads a module-level ``zlib`` (another meshio), it is left alone and writes as it does."""
    from meshio.vtu import _vtu

    if getattr(_vtu, "zlib", None) is zlib:
        _vtu.zlib = _Zlib()
    before = getattr(_FAST, "on", False)
    _FAST.on = True
    try:
        yield
    finally:
        _FAST.on = before


def _xyz(p: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    return np.column_stack([p, np.zeros(len(p))])


def write_vtu(path: str | Path, problem: Problem, solution: Solution, *, per_body: bool = True) -> list[Path]:
    """Writes the body, Γ_C and the multiplier fields as three VTU files; returns their paths. For two
    bodies (and ``per_body``), also one VTU file per body (``<stem>_<name>.vtu``, its own nodes and
    triangles with their fields) and a ParaView multiblock ``<stem>.vtm`` of them."""
    import meshio

    path = Path(path)
    stem = path.with_suffix("")
    mesh = problem.mesh
    stress = solution.stress
    tensor = stress_tensor(solution)
    body = meshio.Mesh(
        _xyz(mesh.points),
        [("triangle", mesh.triangles)],
        point_data={
            "displacement": _xyz(solution.displacement),
            "reaction": _xyz(solution.reactions),
            "stress_recovered": solution.nodal_stress,
            "von_mises_recovered": solution.nodal_von_mises,
            **({"pressure": solution.pressure} if len(solution.pressure) else {}),
        },
        cell_data={
            "stress": [tensor.reshape(-1, 9)],
            "sigma_xx": [stress[:, 0]],
            "sigma_yy": [stress[:, 1]],
            "sigma_xy": [stress[:, 2]],
            "sigma_zz": [solution.stress_zz],
            "von_mises": [solution.von_mises],
            "error_indicator": [solution.estimator],
            "traction_indicator": [solution.traction_estimator],
            # Which body each triangle belongs to (0 for one body; two bodies in the order given).
            "body": [np.repeat(np.arange(len(problem.bodies)), [s[3] - s[2] for _, s, _ in problem.bodies])],
            # The material of each triangle: an index into problem.materials (a coating's, a layer's; per body
            # for two).
            "material": [np.asarray(problem.regions)],
            # In axisymmetry the out-of-plane stress is the hoop stress: said by its name too.
            **({"sigma_hoop": [solution.stress_zz]} if problem.model == "axisymmetric" else {}),
        },
    )
    if len(solution.pairs) > 1:
        contact, multipliers = _pair_blocks(meshio, problem, solution)
    else:
        n = len(solution.node_abscissae)
        lines = np.column_stack([np.arange(n - 1), np.arange(1, n)])
        contact = meshio.Mesh(
            _xyz(problem.contact_points(solution.node_abscissae)),
            [("line", lines)],
            point_data={
                "u_n": solution.u_n,
                "slip": solution.slip,
                "gap": solution.gap,
                "current_gap": solution.current_gap,
                "obstacle": _xyz(obstacle_points(problem, solution)),
            },
            cell_data={"sigma_n": [solution.sigma_n], "sigma_t": [solution.sigma_t]},
        )
        xi = problem.multiplier_mesh
        k = len(xi)
        fields: dict[str, npt.NDArray[Any]] = {
            "lambda_n": solution.lambda_n,
            "lambda_t": solution.lambda_t,
            "friction_threshold": solution.friction_threshold,
            "state": solution.states.astype(np.int32),
        }
        mlines = np.column_stack([np.arange(k - 1), np.arange(1, k)])
        if problem.space == "P1":
            fields = {name: at_points(v, k) for name, v in fields.items()}
            multipliers = meshio.Mesh(_xyz(problem.contact_points(xi)), [("line", mlines)], point_data=fields)
        else:
            multipliers = meshio.Mesh(
                _xyz(problem.contact_points(xi)), [("line", mlines)], cell_data={k: [v] for k, v in fields.items()}
            )
    paths = [path, Path(f"{stem}_contact.vtu"), Path(f"{stem}_multipliers.vtu")]
    meshes = [body, contact, multipliers]
    if per_body and len(problem.bodies) > 1:
        parts = [Path(f"{stem}_{name}.vtu") for name, _, _ in problem.bodies]
        meshes += [_part(meshio, body, spans) for _, spans, _ in problem.bodies]
        paths += parts
    for p, m in zip(paths, meshes, strict=True):
        p.parent.mkdir(parents=True, exist_ok=True)
        with _fast_compression():
            meshio.write(str(p), m, file_format="vtu")
    if per_body and len(problem.bodies) > 1:
        paths.append(_write_vtm(Path(f"{stem}.vtm"), [name for name, _, _ in problem.bodies], parts))
    return paths


def _pair_blocks(meshio: Any, problem: Problem, solution: Solution) -> tuple[Any, Any]:
    """The contact and multiplier meshes of several contact pairs: each pair's side a chain of lines (cell data
    ``pair``, its index in ``problem.pairs``), each multiplier dof a vertex at its abscissa on its own side."""
    points, lines, dofs, which, at = [], [], [], [], 0
    for r in solution.pairs:
        k = r.index
        xi = solution.node_abscissae[r.nodes]
        points.append(problem.contact_points(xi, k))
        lines.append(np.column_stack([np.arange(len(xi) - 1), np.arange(1, len(xi))]) + at)
        which.append(np.full(len(xi) - 1, k, dtype=np.int32))
        dofs.append(problem.contact_points(solution.multiplier_abscissae[r.multipliers], k))
        at += len(xi)
    contact = meshio.Mesh(
        _xyz(np.concatenate(points)), [("line", np.concatenate(lines))],
        point_data={"u_n": solution.u_n, "slip": solution.slip, "gap": solution.gap,
                    "current_gap": solution.current_gap, "obstacle": _xyz(obstacle_points(problem, solution))},
        cell_data={"sigma_n": [solution.sigma_n], "sigma_t": [solution.sigma_t], "pair": [np.concatenate(which)]},
    )
    q = len(solution.lambda_n)
    fields = {"lambda_n": solution.lambda_n, "lambda_t": solution.lambda_t,
              "friction_threshold": solution.friction_threshold, "state": solution.states.astype(np.int32),
              "pair": np.concatenate([np.full(r.multipliers.stop - r.multipliers.start, r.index) for r in
                                      solution.pairs]).astype(np.int32)}
    multipliers = meshio.Mesh(_xyz(np.concatenate(dofs)), [("vertex", np.arange(q).reshape(-1, 1))], point_data=fields)
    return contact, multipliers


def _part(meshio: Any, whole: Any, spans: Sequence[int]) -> Any:
    """The nodes ``spans[0]:spans[1]`` and triangles ``spans[2]:spans[3]`` of a meshio mesh, with their data
    (a body of a two-body problem: its nodes and triangles are contiguous)."""
    n0, n1, t0, t1 = spans
    triangles = whole.cells_dict["triangle"][t0:t1] - n0
    return meshio.Mesh(
        whole.points[n0:n1],
        [("triangle", triangles)],
        point_data={k: v[n0:n1] for k, v in whole.point_data.items()},
        cell_data={k: [v[0][t0:t1]] for k, v in whole.cell_data.items()},
    )


def _write_vtm(path: Path, names: Sequence[str], files: Sequence[Path]) -> Path:
    """A ParaView multiblock (``.vtm``) of one VTU file per named block (paths relative to it)."""
    rows = "\n".join(
        f'    <DataSet index="{k}" name={quoteattr(name)} file={quoteattr(f.relative_to(path.parent).as_posix())}/>'
        for k, (name, f) in enumerate(zip(names, files, strict=True))
    )
    path.write_text(
        '<?xml version="1.0"?>\n<VTKFile type="vtkMultiBlockDataSet" version="1.0">\n  <vtkMultiBlockDataSet>\n'
        f"{rows}\n  </vtkMultiBlockDataSet>\n</VTKFile>\n",
        encoding="utf-8",
    )
    return path


def stress_tensor(solution: Solution) -> npt.NDArray[np.float64]:
    """The full symmetric stress tensor per triangle, (T, 3, 3): the in-plane components, σ_zz (from the core:
    ν (σ_xx + σ_yy) in plane strain, 0 in plane stress, the hoop stress in axisymmetry) and σ_xz = σ_yz = 0."""
    s = solution.stress
    t = np.zeros((len(s), 3, 3))
    t[:, 0, 0], t[:, 1, 1], t[:, 2, 2] = s[:, 0], s[:, 1], solution.stress_zz
    t[:, 0, 1] = t[:, 1, 0] = s[:, 2]
    return t


def contact_tables(problem: Problem, solution: Solution) -> dict[str, dict[str, npt.NDArray[Any]]]:
    """The contact fields as three tables (name -> column -> array), one per kind of place on Γ_C:
    ``multipliers`` (dofs of λ), ``nodes`` (FE nodes) and ``edges`` (FE edges). With several contact pairs the rows
    hold the pairs one after the other, the first column ``pair`` naming each row's."""
    pairs = solution.pairs or []
    spans = [(r.index, (r.multipliers, r.nodes, r.edges)) for r in pairs] or [(0, (slice(None),) * 3)]

    def at(xi: npt.NDArray[np.float64], which: int) -> dict[str, npt.NDArray[Any]]:
        parts = [(xi[s[which]], problem.contact_points(xi[s[which]], k), problem.contact_normals(xi[s[which]], k))
                 for k, s in spans]
        x, p, n = (np.concatenate([part[i] for part in parts]) for i in range(3))
        names = [[r.name] * len(xi[s[which]]) for r, (_, s) in zip(pairs, spans)]
        named = {"pair": np.concatenate(names)} if len(pairs) > 1 else {}
        return named | {"xi": x, "x": p[:, 0], "y": p[:, 1], "n_x": n[:, 0], "n_y": n[:, 1]}

    po = obstacle_points(problem, solution)
    return {
        "multipliers": at(solution.multiplier_abscissae, 0)
        | {
            "lambda_n": solution.lambda_n,
            "lambda_t": solution.lambda_t,
            "friction_threshold": solution.friction_threshold,
            "state": np.asarray(solution.state_names),
        },
        "nodes": at(solution.node_abscissae, 1)
        | {
            "u_n": solution.u_n,
            "slip": solution.slip,
            "gap": solution.gap,
            "current_gap": solution.current_gap,
            "obstacle_x": po[:, 0],
            "obstacle_y": po[:, 1],
        },
        "edges": at(solution.edge_abscissae, 2) | {"sigma_n": solution.sigma_n, "sigma_t": solution.sigma_t},
    }


def write_contact_csv(directory: str | Path, problem: Problem, solution: Solution) -> list[Path]:
    """Writes ``contact.csv`` (per multiplier dof), ``contact_nodes.csv`` and ``contact_edges.csv``.

    Each file has one header line of column names, then ``#`` lines stating the conventions its columns
    are read in (n, t, the direction of ξ, the signs; ``numpy.genfromtxt(path, delimiter=",", names=True)``
    and ``pandas.read_csv(path, comment="#")`` skip them), then the rows."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    names = {"multipliers": "contact.csv", "nodes": "contact_nodes.csv", "edges": "contact_edges.csv"}
    paths = []
    said = conventions(problem, solution)
    for key, table in contact_tables(problem, solution).items():
        path = directory / names[key]
        columns = list(table)
        with path.open("w", encoding="utf-8") as f:
            f.write(",".join(columns) + "\n")
            stated = ["pair"] * ("pair" in columns) + ["n", "t", "xi"] + [c for c in columns if c in said and c not in ("xi", "pair")]
            stated += ["states"] if key == "multipliers" else []
            if key == "nodes":
                stated += ["shift"]
                f.write("# gap: g = g0 − δ along n; obstacle_x, obstacle_y: the obstacle's surface facing the node\n")
            for c in stated:
                f.write(f"# {c}: {said[c]}\n")
            for row in zip(*(table[c] for c in columns)):
                f.write(",".join(v if isinstance(v, str) else repr(float(v)) for v in row) + "\n")
        paths.append(path)
    return paths
