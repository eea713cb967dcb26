"""Supports beyond clamping in Python and in scene files: rollers (symmetry lines), prescribed
displacements, the half Hertz model against the full one, and one rejection test per rule."""

from __future__ import annotations

import tomllib

import numpy as np
import pytest
from test_errors import raises

import tribo
from tribo.scene import SceneError, load_scene, parse_scene, scene_path

HERTZ = load_scene(scene_path("hertz"))


def square(n: int = 4) -> tribo.Mesh:
    return tribo.Mesh.rectangle((0.0, 1.0), (0.0, 1.0), n, n)


def test_support_values() -> None:
    s = tribo.Support.displacement("top", y=-0.01)
    assert (s.kind, s.edge_set, s.value) == ("displacement", "top", (None, -0.01))
    assert repr(s) == 'Support.displacement("top", x=None, y=-0.01)'
    assert tribo.Support.roller("left").kind == "roller" and tribo.Support.roller("left").value == (None, None)
    assert tribo.Support.clamp("bottom").value == (0.0, 0.0)
    assert tribo.Support.clamp("bottom") == tribo.Support.clamp("bottom")


def test_patch_driven_by_prescribed_displacements() -> None:
    """u_x = e x, u_y = −ν/(1−ν) e y (uniaxial plane-strain tension) reproduced to round-off, with only
    prescribed displacements and a roller driving it."""
    e, nu = 0.01, 0.3
    mesh = square(8)
    supports = [
        tribo.Support.displacement("left", x=0.0),
        tribo.Support.displacement("right", x=e),
        tribo.Support.roller("bottom"),
    ]
    problem = tribo.Problem(mesh, young=100.0, poisson=nu, contact="top", supports=supports, approach=-1.0)
    assert problem.clamped == [] and problem.supports == supports
    sol = problem.solve()
    assert sol.report.status == "converged"
    p = mesh.points
    exact = np.column_stack([e * p[:, 0], -nu / (1.0 - nu) * e * p[:, 1]])
    assert np.abs(sol.displacement - exact).max() < 1e-11 * e


def mirrored(half: tribo.Mesh) -> tribo.Mesh:
    """The full mesh whose right half is `half`: its mirror image about x = 0 glued along x = 0."""
    pts, tri = half.points, half.triangles
    on_axis = pts[:, 0] == 0.0
    image = np.arange(len(pts))
    image[~on_axis] = len(pts) + np.arange(int((~on_axis).sum()))
    points = np.vstack([pts, pts[~on_axis] * [-1.0, 1.0]])
    triangles = np.vstack([tri, image[tri][:, [0, 2, 1]]])
    sets = {k: np.vstack([v, image[v]]) for k, v in half.edge_sets.items() if k in ("bottom", "top")}
    return tribo.Mesh(points, triangles, sets)


def test_half_hertz_model_equals_the_full_one() -> None:
    """A roller on the symmetry line: the half model is the full model's right half, to solver tolerance."""
    half_mesh = tribo.Mesh.graded_rectangle(
        (0.0, 2.0), (-2.0, 0.0), side="top", segment=(0.0, 0.3), h_min=0.04, h_max=0.5, growth=0.3
    )
    common = dict(young=200.0, poisson=0.3, contact="top", obstacle=tribo.Obstacle.circle(1.0), approach=0.01)
    half = tribo.Problem(
        half_mesh, supports=[tribo.Support.clamp("bottom"), tribo.Support.roller("left")], **common  # type: ignore[arg-type]
    ).solve()
    full = tribo.Problem(mirrored(half_mesh), clamped="bottom", **common).solve()  # type: ignore[arg-type]
    n = half_mesh.n_nodes
    tol = float(np.sqrt(tribo.solver_defaults()["qp_tol"]))
    assert abs(2.0 * half.normal_force - full.normal_force) <= tol * full.normal_force
    assert np.abs(half.displacement - full.displacement[:n]).max() <= tol * np.abs(full.displacement).max()
    right = full.multiplier_abscissae >= 0.0
    assert np.abs(half.lambda_n - full.lambda_n[right]).max() <= tol * full.lambda_n.max()


def test_half_scene_equals_the_full_hertz_scene() -> None:
    """In scene files: the half of the Hertz scene with a [[supports]] roller. Its generated mesh is the full
    one's right half, and the full one is mirror-symmetric: the forces agree to round-off."""
    data = tomllib.loads((scene_path("hertz")).read_text(encoding="utf-8"))
    data["body"]["x"] = [0.0, 2.0]
    data["discretization"]["grading"] = [0.0, 0.3]
    data["supports"] = [{"kind": "clamp", "edge_set": "bottom"}, {"kind": "roller", "edge_set": "left"}]
    scene = parse_scene(data)
    assert [s.kind for s in scene.supports()] == ["clamp", "roller"]
    _, half = scene.solve()
    _, full = HERTZ.solve()
    assert half.report.status == full.report.status == "converged"
    rel = abs(2.0 * half.normal_force - full.normal_force) / full.normal_force
    assert rel < 1e-10, rel


def test_punch_pushed_by_a_prescribed_displacement() -> None:
    """A block pushed down by u_y = −0.002 on its top (u_x free) onto a flat foundation: the contact force
    equals the top's reaction, and the top moved by the prescribed amount."""
    mesh = tribo.Mesh.rectangle((0.0, 1.0), (0.0, 0.5), 8, 4)
    problem = tribo.Problem(
        mesh,
        young=100.0,
        poisson=0.3,
        contact="bottom",
        supports=[tribo.Support.displacement("top", y=-0.002), tribo.Support.roller("left")],
    )
    sol = problem.solve(mu=0.2)
    assert sol.report.status == "converged" and sol.normal_force > 0.0
    top = np.unique(mesh.edge_sets["top"])
    assert np.all(sol.displacement[top, 1] == -0.002)
    assert sol.reactions[top, 1].sum() == pytest.approx(-sol.normal_force, rel=1e-6)


def test_rejections() -> None:
    mesh = square()
    kw = dict(young=1.0, poisson=0.3, contact="bottom")
    raises(tribo.MeshError, "UnknownEdgeSet", lambda: tribo.Problem(mesh, supports=[tribo.Support.roller("lft")], **kw))  # type: ignore[arg-type]
    sets = {k: v for k, v in mesh.edge_sets.items()}
    sets["corner"] = np.vstack([sets["top"], sets["right"]])
    corner = tribo.Mesh(mesh.points, mesh.triangles, sets)
    e = raises(
        tribo.SettingsError,
        "SupportNotStraight",
        lambda: tribo.Problem(corner, supports=[tribo.Support.roller("corner")], **kw),  # type: ignore[arg-type]
    )
    assert e.details["set"] == "corner"
    clash = [tribo.Support.clamp("top"), tribo.Support.displacement("left", y=-0.01)]
    e = raises(tribo.SettingsError, "ConflictingSupports", lambda: tribo.Problem(mesh, supports=clash, **kw))  # type: ignore[arg-type]
    assert e.details["node"] == 20 and "left" in str(e)
    # A roller on a side tilted by 1e-6 rad beside u_x = 0.01 on the top moves the corner by 1e4: refused,
    # naming the node and the angle; with u_x = 0 there the corner is fixed at 0 and the problem is
    # accepted, and a history that moves u_x to 0.01 is refused at that step.
    points = mesh.points.copy()
    right = points[:, 0] == 1.0
    points[right, 0] += 1e-6 * points[right, 1]
    tilted = tribo.Mesh(points, mesh.triangles, mesh.edge_sets)
    near = [tribo.Support.displacement("top", x=0.01), tribo.Support.roller("right")]
    e = raises(tribo.SettingsError, "NearlyParallelSupports", lambda: tribo.Problem(tilted, supports=near, **kw))  # type: ignore[arg-type]
    assert e.details["node"] == 24 and e.details["angle_degrees"] == pytest.approx(np.degrees(1e-6), rel=1e-6)
    assert e.details["displacement"] == pytest.approx(1e4, rel=1e-6) and "node 24" in str(e)
    held = [tribo.Support.displacement("top", x=0.0), tribo.Support.roller("right")]
    at_rest = tribo.Problem(tilted, supports=held, **kw)  # type: ignore[arg-type]
    e = raises(tribo.SettingsError, "BadLoadStep", lambda: at_rest.solve_history(displacements={"top.x": [0.0, 0.01]}))
    assert e.details["step"] == 1 and "at an angle of 5.730e-5°" in str(e)
    # Rollers on both sides leave the body free in y, to the contact (Γ_C the bottom): with nothing pressing
    # it down its position is undetermined, said at the solve; a load on the top holds it there.
    parallel = [tribo.Support.roller("left"), tribo.Support.roller("right")]
    free = tribo.Problem(mesh, supports=parallel, **kw)  # type: ignore[arg-type]
    e = raises(tribo.ContactGeometryError, "HeldOnlyByContact", free.solve)
    assert "translation along (0.000" in e.details["motion"]
    pressed = tribo.Problem(mesh, supports=parallel, tractions={"top": (0.0, -1.0)}, **kw)  # type: ignore[arg-type]
    assert pressed.solve().normal_force == pytest.approx(1.0, rel=1e-9)
    raises(tribo.SettingsError, "BadSupport", lambda: tribo.Support.displacement("top"))
    raises(tribo.SettingsError, "BadSupport", lambda: tribo.Support.displacement("top", x=float("nan")))
    # No support at all and no friction: free to slide along the foundation, said by name.
    e = raises(tribo.ContactGeometryError, "HeldOnlyByContact", lambda: tribo.Problem(mesh, **kw).solve())  # type: ignore[arg-type]
    assert "frictionless" in e.details["what"]
    raises(tribo.SettingsError, "BadInput", lambda: tribo.Problem(mesh, supports="top", **kw))  # type: ignore[arg-type]
    raises(tribo.SettingsError, "BadInput", lambda: tribo.Problem(mesh, supports=[1], **kw))  # type: ignore[arg-type]


def test_two_disjoint_pieces_name_the_floating_one() -> None:
    points = [[0, 0], [1, 0], [1, 1], [0, 1], [2, 0], [3, 0], [3, 1], [2, 1]]
    triangles = [[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]]
    mesh = tribo.Mesh(points, triangles, {"bottom": [[0, 1]], "top": [[3, 2]]})
    e = raises(
        tribo.SettingsError,
        "FloatingPiece",
        lambda: tribo.Problem(mesh, young=1.0, poisson=0.3, clamped="bottom", contact="top", approach=0.01),
        match="has no support",
    )
    assert e.details == {"triangle": 2, "node": 4, "triangles": 2, "pieces": 2}


@pytest.mark.parametrize(
    ("entries", "key"),
    [
        ([{"edge_set": "left"}], "supports[0].kind"),
        ([{"kind": "roller"}], "supports[0].edge_set"),
        ([{"kind": "pin", "edge_set": "left"}], "supports[0].kind"),
        ([{"kind": "roller", "edge_set": "left", "y": 0.0}], "supports[0].y"),
        ([{"kind": "displacement", "edge_set": "left"}], "supports[0].x"),
        ([{"kind": "displacement", "edge_set": "left", "y": "down"}], "supports[0].y"),
        (["left"], "supports[0]"),
    ],
)
def test_scene_support_entries_are_checked(entries: list[object], key: str) -> None:
    data = tomllib.loads(scene_path("hertz").read_text(encoding="utf-8"))
    data["supports"] = entries
    with pytest.raises(SceneError) as info:
        parse_scene(data)
    assert info.value.details["key"] == key


def test_scene_without_supports_is_refused() -> None:
    data = tomllib.loads(scene_path("hertz").read_text(encoding="utf-8"))
    del data["supports"]
    with pytest.raises(SceneError, match="supports"):
        parse_scene(data)


def test_scene_with_a_prescribed_displacement() -> None:
    """A punch in a scene file: the block's top pushed down by [[supports]] kind = "displacement" (y only),
    a symmetry line on its left, a flat foundation under it, Coulomb friction."""
    scene = parse_scene(
        tomllib.loads(
            """
            [body]
            x = [0.0, 1.0]
            y = [0.0, 0.5]
            [material]
            young = 100.0
            poisson = 0.3
            [[supports]]
            kind = "displacement"
            edge_set = "top"
            y = -0.002
            [[supports]]
            kind = "roller"
            edge_set = "left"
            [contact]
            edge_set = "bottom"
            [friction]
            mu = 0.2
            [discretization]
            grading = "none"
            h = 0.125
            """
        )
    )
    problem, sol = scene.solve()
    assert [s.kind for s in problem.supports] == ["displacement", "roller"] and problem.clamped == []
    assert sol.report.status == "converged" and sol.normal_force > 0.0
    top = np.unique(problem.mesh.edge_sets["top"])
    assert np.all(sol.displacement[top, 1] == -0.002)
    assert scene.to_dict()["supports"]["entries"][0] == {"kind": "displacement", "edge_set": "top", "y": -0.002}


def test_supports_that_push_gamma_c_into_the_obstacle_are_refused() -> None:
    """Clamped sides hold the corners of Γ_C at 0 while the foundation moves 0.01 into them: the contact
    condition cannot hold there. Refused before the solve, naming the node (before, the solve said
    'converged' with the corners inside the obstacle)."""
    mesh = tribo.Mesh.rectangle((0.0, 2.0), (0.0, 1.0), 8, 4)
    problem = tribo.Problem(mesh, young=1.0, poisson=0.3, contact="bottom", clamped=["left", "right"],
                            obstacle=tribo.Obstacle.flat(), approach=0.01)
    with pytest.raises(tribo.ContactGeometryError, match="into the obstacle") as info:
        problem.solve()
    assert info.value.kind == "PrescribedPenetration"
    d = info.value.details
    assert d["node"] == int(problem.contact_nodes[0]) and d["u_n"] == 0.0 and d["gap"] == pytest.approx(-0.01)
    assert d["step"] == "static"
    with pytest.raises(tribo.ContactGeometryError, match="at step 1"):
        problem.solve_history([0.0, 0.01], 0.0)
    touching = tribo.Problem(mesh, young=1.0, poisson=0.3, contact="bottom", clamped=["left", "right"],
                             obstacle=tribo.Obstacle.flat())
    assert touching.solve().report.status == "converged"
