"""meshio interop: a Gmsh file in, VTU files out and back, the contact CSV tables."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import meshio
import numpy as np
import pytest
from conftest import hertz_problem

import tribo
from tribo.io import mesh_from_meshio, read_mesh, write_contact_csv, write_vtu

# A unit square split into 4 triangles around its centre (node 5); node 6 is a geometry point used by
# no triangle; triangle 2 is listed clockwise. Physical lines: bottom (1), top (2); surface: body (3).
MSH22 = """$MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
3
1 1 "bottom"
1 2 "top"
2 3 "body"
$EndPhysicalNames
$Nodes
6
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
5 0.5 0.5 0
6 3 3 0
$EndNodes
$Elements
7
1 15 2 0 6 6
2 1 2 1 1 1 2
3 1 2 2 3 3 4
4 2 2 3 1 1 2 5
5 2 2 3 1 2 3 5
6 2 2 3 1 3 5 4
7 2 2 3 1 4 1 5
$EndElements
"""


def test_read_gmsh_physical_groups(tmp_path: Path) -> None:
    path = tmp_path / "square.msh"
    path.write_text(MSH22)
    mesh = read_mesh(path)
    assert mesh.n_nodes == 5 and mesh.n_triangles == 4
    assert sorted(mesh.edge_sets) == ["bottom", "top"]
    assert len(mesh.edge_sets["top"]) == 1
    np.testing.assert_allclose(mesh.points[mesh.edge_sets["bottom"][0]], [[0.0, 0.0], [1.0, 0.0]])
    # The clockwise triangle was turned around: the mesh validated.
    renamed = read_mesh(path, edge_sets={"contact": "top", "base": "bottom"})
    assert sorted(renamed.edge_sets) == ["base", "contact"]
    with pytest.raises(tribo.MeshError, match="no edge set"):
        read_mesh(path, edge_sets={"contact": "lid"})


def test_gmsh_mesh_solves(tmp_path: Path) -> None:
    # A finer Gmsh file written by meshio itself (gmsh 2.2 ascii) from a generated mesh.
    src = tribo.Mesh.rectangle((0.0, 1.0), (0.0, 1.0), 6, 6)
    lines = np.vstack([src.edge_sets["bottom"], src.edge_sets["top"]])
    tags = np.array([1] * len(src.edge_sets["bottom"]) + [2] * len(src.edge_sets["top"]))
    m = meshio.Mesh(
        np.column_stack([src.points, np.zeros(src.n_nodes)]),
        [("triangle", src.triangles), ("line", lines)],
        cell_data={
            "gmsh:physical": [np.full(src.n_triangles, 3), tags],
            "gmsh:geometrical": [np.full(src.n_triangles, 3), tags],
        },
        field_data={"bottom": np.array([1, 1]), "top": np.array([2, 1]), "body": np.array([3, 2])},
    )
    path = tmp_path / "block.msh"
    meshio.write(str(path), m, file_format="gmsh22", binary=False)
    mesh = read_mesh(path)
    np.testing.assert_array_equal(mesh.edge_sets["top"], src.edge_sets["top"])
    a = tribo.Problem(mesh, young=1.0, poisson=0.3, clamped="bottom", contact="top", approach=0.01).solve()
    b = tribo.Problem(src, young=1.0, poisson=0.3, clamped="bottom", contact="top", approach=0.01).solve()
    np.testing.assert_allclose(a.displacement, b.displacement, rtol=1e-12, atol=1e-15)


def test_meshio_rejects_what_tribo_cannot_use() -> None:
    quad = meshio.Mesh(np.zeros((4, 2)), [("quad", np.array([[0, 1, 2, 3]]))])
    with pytest.raises(tribo.MeshError, match="no linear triangles"):
        mesh_from_meshio(quad)
    tilted = meshio.Mesh(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 1.0]]), [("triangle", np.array([[0, 1, 2]]))])
    with pytest.raises(tribo.MeshError, match="not planar"):
        mesh_from_meshio(tilted)
    with pytest.raises(tribo.MeshError, match="cannot read"):
        read_mesh("/nonexistent/mesh.msh")


@pytest.mark.parametrize("space", ["P1", "P0"])
def test_vtu_round_trip(tmp_path: Path, space: str) -> None:
    problem = hertz_problem(shift=0.004, space=space)
    s = problem.solve(mu=0.3)
    body, contact, multipliers = write_vtu(tmp_path / "out" / "result.vtu", problem, s)
    assert body.name == "result.vtu" and contact.name == "result_contact.vtu"
    m = meshio.read(body)
    np.testing.assert_allclose(m.points[:, :2], problem.mesh.points)
    np.testing.assert_array_equal(m.cells_dict["triangle"], problem.mesh.triangles)
    np.testing.assert_allclose(m.point_data["displacement"][:, :2], s.displacement)
    np.testing.assert_allclose(m.cell_data["von_mises"][0], s.von_mises)
    # The stress is the full symmetric tensor of plane strain, 9 components (a tensor in ParaView).
    tensor = m.cell_data["stress"][0].reshape(-1, 3, 3)
    np.testing.assert_allclose(tensor[:, 0, 0], s.stress[:, 0])
    np.testing.assert_allclose(tensor[:, 1, 1], s.stress[:, 1])
    np.testing.assert_allclose(tensor[:, [0, 1], [1, 0]], np.column_stack([s.stress[:, 2]] * 2))
    np.testing.assert_allclose(tensor[:, 2, 2], problem.poisson * (s.stress[:, 0] + s.stress[:, 1]), rtol=1e-12)
    np.testing.assert_array_equal(tensor[:, [0, 1, 2, 2], [2, 2, 0, 1]], 0.0)
    np.testing.assert_allclose(m.cell_data["sigma_zz"][0], tensor[:, 2, 2])
    # The von Mises stress of that tensor is the core's.
    dev = tensor - np.trace(tensor, axis1=1, axis2=2)[:, None, None] * np.eye(3) / 3
    np.testing.assert_allclose(np.sqrt(1.5 * (dev**2).sum(axis=(1, 2))), s.von_mises, rtol=1e-10)
    c = meshio.read(contact)
    np.testing.assert_allclose(c.point_data["u_n"], s.u_n)
    np.testing.assert_allclose(c.point_data["current_gap"], s.gap - s.u_n)
    # The obstacle's surface facing each node of Γ_C: the node moved by the gap along n.
    facing = problem.contact_points(s.node_abscissae) + np.outer(s.gap, problem.contact_normal)
    np.testing.assert_allclose(c.point_data["obstacle"][:, :2], facing)
    np.testing.assert_allclose(c.cell_data["sigma_n"][0], s.sigma_n)
    mm = meshio.read(multipliers)
    data = mm.point_data if space == "P1" else {k: v[0] for k, v in mm.cell_data.items()}
    np.testing.assert_allclose(data["lambda_n"], s.lambda_n)
    np.testing.assert_allclose(data["lambda_t"], s.lambda_t)
    np.testing.assert_array_equal(data["state"], s.states)


def test_vtu_files_are_compressed_fast_by_tribo_only(
    tmp_path: Path, hertz: tribo.Problem, monkeypatch: pytest.MonkeyPatch
) -> None:
    """tribo's VTU files are deflated with zlib's run-length strategy (study 19: most of the writing is
    compression); what meshio compresses outside tribo's writers, in another thread while they write or after
    them, is compressed as zlib does by default. The file reads back."""
    import threading
    import zlib

    import tribo.io
    from meshio.vtu import _vtu

    s = hertz.solve()
    data = np.linspace(0.0, 1.0, 5000).tobytes()
    fast: list[str] = []
    theirs: list[bytes] = []
    compress_fast = tribo.io._compress_fast

    def recorded(block: bytes) -> bytes:
        fast.append(threading.current_thread().name)
        if len(fast) == 1:  # while tribo writes, another thread compresses through meshio's module
            t = threading.Thread(target=lambda: theirs.append(_vtu.zlib.compress(data)), name="theirs")
            t.start()
            t.join()
        return compress_fast(block)

    write_vtu(tmp_path / "first.vtu", hertz, s)
    assert _vtu.zlib is not zlib  # the stand-in
    monkeypatch.setattr(tribo.io, "_compress_fast", recorded)
    write_vtu(tmp_path / "result.vtu", hertz, s)
    after = _vtu.zlib.compress(data)
    monkeypatch.undo()
    assert len(fast) > 10 and set(fast) == {threading.current_thread().name}
    assert theirs == [zlib.compress(data)] and after == zlib.compress(data) != compress_fast(data)
    assert zlib.decompress(compress_fast(data)) == data
    m = meshio.read(tmp_path / "result.vtu")
    np.testing.assert_allclose(m.points[:, :2], hertz.mesh.points)
    np.testing.assert_allclose(m.point_data["displacement"][:, :2], s.displacement)


def test_contact_csv(tmp_path: Path, hertz: tribo.Problem) -> None:
    s = hertz.solve(mu=0.3)
    paths = write_contact_csv(tmp_path, hertz, s)
    assert [p.name for p in paths] == ["contact.csv", "contact_nodes.csv", "contact_edges.csv"]
    table = np.genfromtxt(paths[0], delimiter=",", names=True, dtype=None, encoding="utf-8")
    np.testing.assert_allclose(table["lambda_n"], s.lambda_n)
    assert list(table["state"]) == s.state_names
    nodes = np.genfromtxt(paths[1], delimiter=",", names=True)
    np.testing.assert_allclose(nodes["slip"], s.slip)
    np.testing.assert_allclose(nodes["current_gap"], s.gap - s.u_n)
    # Its most negative value is the largest pointwise penetration (non-penetration holds weakly).
    assert -nodes["current_gap"].min() == pytest.approx(s.max_penetration, rel=1e-12)
    # Below the column names, '#' lines state the conventions: n, t, the direction of ξ, the signs.
    head = paths[0].read_text(encoding="utf-8").splitlines()
    said = [line for line in head if line.startswith("# ")]
    for needle in ("n = (0, 1)", "t = (−n₂, n₁) = (-1, 0)", "increasing with x (along −t)", "λ_t = −σ_t, along t"):
        assert any(needle in line for line in said), (needle, said)
    node_lines = paths[1].read_text(encoding="utf-8").splitlines()
    assert any("the obstacle moved toward −x" in line for line in node_lines), node_lines[:12]


def test_unreadable_files_raise_mesh_error(tmp_path: Path, capfd: pytest.CaptureFixture[str]) -> None:
    """D16: meshio calls sys.exit(1) when no reader accepts a file (and loops forever on a blank TetGen
    file); read_mesh raises MeshError naming the file, and meshio's own output does not leak."""
    cases = [("text.msh", "hello\n"), ("empty.msh", ""), ("text.vtu", "1 2 3\n"), ("empty.ele", ""), ("blank.node", "\n \n")]
    for name, content in cases:
        path = tmp_path / name
        path.write_text(content)
        with pytest.raises(tribo.MeshError, match=f"cannot read mesh file {path}") as info:
            read_mesh(path)
        assert info.value.kind == "UnreadableFile" and info.value.details == {"path": str(path)}
    out = capfd.readouterr()
    assert out.out == "" and out.err == ""


def triangles_only(points: object, triangles: object) -> meshio.Mesh:
    return meshio.Mesh(np.asarray(points, dtype=float), [("triangle", np.asarray(triangles))])


@pytest.mark.parametrize(
    ("triangles", "match"),
    [
        ([[0, 1, 2], [0, 2, -1]], "triangle 1 uses node -1, but the mesh has 4 nodes .* does not define"),
        ([[0, 1, 2], [0, 2, 4]], "triangle 1 uses node 4, but the mesh has 4 nodes"),
        ([[0, 1, 2], [0, 2, 2**40]], "triangle 1 uses node 1099511627776"),
    ],
)
def test_meshio_node_index_out_of_range(triangles: list[list[int]], match: str) -> None:
    """D17: −1 no longer wraps to the last node, and a large index is not an IndexError."""
    with pytest.raises(tribo.MeshError, match=match) as info:
        mesh_from_meshio(triangles_only([[0, 0], [1, 0], [1, 1], [0, 1]], triangles))
    assert info.value.kind == "NodeIndexOutOfRange" and info.value.details["element"] == 1


def test_meshio_line_index_out_of_range() -> None:
    m = meshio.Mesh(
        np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]),
        [("triangle", np.array([[0, 1, 2], [0, 2, 3]])), ("line", np.array([[0, 1], [3, -1]]))],
        cell_sets={"rim": [np.array([], dtype=int), np.array([0, 1])]},
    )
    with pytest.raises(tribo.MeshError, match="line 1 of edge set 'rim' uses node -1"):
        mesh_from_meshio(m)


def test_gmsh_node_tag_zero_is_refused(tmp_path: Path) -> None:
    """D17: with node tags 0…5, meshio maps the elements' node 0 onto node 5 (the geometry point at (3, 3)):
    the mesh overlaps itself, and solved to 'converged' before."""
    lines, section = [], ""
    for line in MSH22.splitlines():
        section = line if line.startswith("$") else section
        f = line.split()
        if section == "$Nodes" and len(f) == 4:
            f[0] = str(int(f[0]) - 1)
        elif section == "$Elements" and len(f) > 3:
            k = 3 + int(f[2])
            f[k:] = [str(int(n) - 1) for n in f[k:]]
        lines.append(" ".join(f))
    path = tmp_path / "tag0.msh"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(tribo.MeshError, match="triangles 2 and 3 overlap") as info:
        read_mesh(path)
    assert info.value.kind == "OverlappingTriangles" and f"in mesh file {path}" in info.value.__notes__


def test_meshio_overlapping_triangles_are_refused() -> None:
    # The folded mesh of D20: triangle 2 lies on triangle 0; turned counter-clockwise, both run from 0 to 1.
    folded = triangles_only([[0, 0], [1, 0], [1, 1], [0, 1], [0.5, 0.5]], [[0, 1, 2], [0, 2, 3], [0, 1, 4]])
    with pytest.raises(tribo.MeshError, match="triangles 0 and 2 overlap: both run from node 0 to node 1"):
        mesh_from_meshio(folded)
    # A fan that winds twice around its centre (six triangles of 120°): no edge is run twice the same way.
    angles = np.radians(120.0 * np.arange(6))
    ring = np.column_stack([np.cos(angles), np.sin(angles)]) * np.repeat([1.0, 2.0], 3)[:, None]
    fan = [[6, k, (k + 1) % 6] for k in range(6)]
    with pytest.raises(tribo.MeshError, match=r"around node 6 overlap: .* add up to 4π instead of 2π"):
        mesh_from_meshio(triangles_only(np.vstack([ring, [[0.0, 0.0]]]), fan))


def test_meshio_overlap_check_accepts_valid_meshes() -> None:
    """No false alarm on strongly graded, far-from-the-origin meshes with mixed orientations."""
    rng = np.random.default_rng(0)
    for mesh in (
        tribo.Mesh.graded_rectangle((-2, 2), (-2, 0), side="top", segment=(-0.01, 0.01), h_min=1e-5, h_max=0.5, growth=0.3),
        tribo.Mesh.rectangle((1e6, 1e6 + 1e-3), (0.0, 1e-3), 20, 20, diagonal="alternating"),
    ):
        t = mesh.triangles.copy()
        flip = rng.random(len(t)) < 0.5
        t[flip] = t[flip][:, [0, 2, 1]]
        again = mesh_from_meshio(triangles_only(mesh.points, t))
        np.testing.assert_array_equal(np.sort(again.triangles, axis=1), np.sort(mesh.triangles, axis=1))


def test_io_errors_carry_kind_and_details(tmp_path: Path) -> None:
    """MeshErrors raised in Python have the kind and details the core's errors have."""
    path = tmp_path / "square.msh"
    path.write_text(MSH22)
    quad = meshio.Mesh(np.zeros((4, 2)), [("quad", np.array([[0, 1, 2, 3]]))])
    cases: list[tuple[Callable[[], object], str]] = [
        (lambda: read_mesh(path, edge_sets={"contact": "lid"}), "UnknownEdgeSet"),
        (lambda: mesh_from_meshio(quad), "EmptyMesh"),
        (lambda: mesh_from_meshio(meshio.Mesh(np.zeros(3), [])), "BadInput"),
    ]
    for f, kind in cases:
        with pytest.raises(tribo.MeshError) as info:
            f()
        assert info.value.kind == kind and isinstance(info.value.details, dict)
