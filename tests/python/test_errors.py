"""Every exception class is raised for the input it is about, with kind/details, and never a panic."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from conftest import hertz_problem

import tribo

SQUARE_PTS = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
SQUARE_TRI = [[0, 1, 2], [0, 2, 3]]
SETS = {"bottom": [[0, 1]], "top": [[2, 3]]}


def raises(cls: type[Exception], kind: str | None, f: Callable[[], Any], match: str | None = None) -> Any:
    """Asserts f raises exactly the subclass `cls` of TriboError (never a PanicException)."""
    with pytest.raises(cls, match=match) as info:
        f()
    assert isinstance(info.value, tribo.TriboError) and isinstance(info.value, ValueError)
    if kind is not None:
        assert info.value.kind == kind, info.value
    assert isinstance(info.value.details, dict)
    return info.value


def test_hierarchy() -> None:
    for cls in (tribo.MeshError, tribo.ContactGeometryError, tribo.SettingsError, tribo.SolverError):
        assert issubclass(cls, tribo.TriboError) and issubclass(cls, ValueError)


@pytest.mark.parametrize(
    ("points", "triangles", "sets", "kind", "match"),
    [
        (SQUARE_PTS, [[0, 1]], None, "BadInput", r"triangles must have shape \(N, 3\)"),
        ([0.0, 1.0, 2.0], SQUARE_TRI, None, "BadInput", r"points must have shape \(N, 2\)"),
        (SQUARE_PTS, np.array(SQUARE_TRI, dtype=float), None, "BadInput", "must hold integers"),
        ([["a", "b"]] * 4, SQUARE_TRI, None, "BadInput", "must hold real numbers"),
        (SQUARE_PTS, [[0, 1, -2]], None, "BadInput", "non-negative"),
        (SQUARE_PTS, "xyz", None, "BadInput", "integers"),
        (SQUARE_PTS, SQUARE_TRI, {"top": [[2, 3, 4]]}, "BadInput", "edge set 'top' must have shape"),
        (SQUARE_PTS, SQUARE_TRI, [1, 2], "BadInput", "edge_sets must be a dict"),
        ([[0.0, np.nan]] + SQUARE_PTS[1:], SQUARE_TRI, None, "NonFiniteCoordinate", "node 0"),
        (SQUARE_PTS, [[0, 1, 7]], None, "NodeIndexOutOfRange", "node 7"),
        (SQUARE_PTS, [[0, 2, 1], [0, 3, 2]], None, "InvertedTriangle", "counter-clockwise"),
        ([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]], [[0, 1, 2]], None, "DegenerateTriangle", "degenerate"),
        (SQUARE_PTS + [[5.0, 5.0]], SQUARE_TRI, None, "UnusedNode", "node 4"),
        (SQUARE_PTS, [[0, 1, 2], [1, 2, 0]], None, "DuplicateTriangle", "same nodes"),
        (SQUARE_PTS, SQUARE_TRI, {"diag": [[0, 2]]}, "NotABoundaryEdge", "'diag'"),
        (SQUARE_PTS, SQUARE_TRI, {"empty": np.zeros((0, 2), dtype=int)}, "EmptyEdgeSet", "'empty'"),
        (SQUARE_PTS, np.zeros((0, 3), dtype=int), None, "EmptyMesh", "no triangle"),
    ],
)
def test_mesh_errors(points: Any, triangles: Any, sets: Any, kind: str, match: str) -> None:
    raises(tribo.MeshError, kind, lambda: tribo.Mesh(points, triangles, sets), match)


def test_mesh_error_details() -> None:
    e = raises(tribo.MeshError, "NodeIndexOutOfRange", lambda: tribo.Mesh(SQUARE_PTS, [[0, 1, 7]]))
    assert e.details == {"element": 0, "node": 7, "n_nodes": 4}


def test_generator_errors() -> None:
    raises(tribo.MeshError, "BadGenerator", lambda: tribo.Mesh.rectangle((1.0, 0.0), (0.0, 1.0), 2, 2))
    raises(tribo.MeshError, "BadGenerator", lambda: tribo.Mesh.rectangle((0.0, 1.0), (0.0, 1.0), 0, 2))
    raises(tribo.MeshError, "UnknownChoice", lambda: tribo.Mesh.rectangle((0.0, 1.0), (0.0, 1.0), 2, 2, diagonal="up"))  # type: ignore[arg-type]
    raises(tribo.MeshError, "BadInput", lambda: tribo.Mesh.rectangle((0.0, 1.0, 2.0), (0.0, 1.0), 2, 2))
    g = dict(side="top", segment=(0.0, 0.5), h_min=0.1, h_max=0.5, growth=0.3)
    raises(tribo.MeshError, "BadGenerator", lambda: tribo.Mesh.graded_rectangle((0, 1), (0, 1), **{**g, "h_min": -1.0}))  # type: ignore[arg-type]
    raises(tribo.MeshError, "BadGenerator", lambda: tribo.Mesh.graded_rectangle((0, 1), (0, 1), **{**g, "segment": (0.5, 2.0)}))  # type: ignore[arg-type]
    raises(tribo.MeshError, "UnknownChoice", lambda: tribo.Mesh.graded_rectangle((0, 1), (0, 1), **{**g, "side": "middle"}))  # type: ignore[arg-type]
    raises(tribo.MeshError, "BadInput", lambda: tribo.Mesh.rectangle((0.0, 1.0), (0.0, 1.0), -1, 2), "nx = -1")
    raises(tribo.MeshError, "BadInput", lambda: tribo.Mesh.rectangle((0.0, 1.0), (0.0, 1.0), 2, 2**70), "ny")


def test_problem_mesh_level_errors() -> None:
    raises(tribo.MeshError, "UnknownEdgeSet", lambda: hertz_problem(contact="lid"), "no edge set named 'lid'")
    raises(tribo.MeshError, "UnknownEdgeSet", lambda: hertz_problem(clamped=["bottom", "base"]), "'base'")
    raises(tribo.MeshError, "UnknownEdgeSet", lambda: hertz_problem(tractions={"side": (0.0, 1.0)}))


def l_shape() -> tribo.Mesh:
    # An L-shaped boundary set "corner" = top edge + right edge of the unit square.
    m = tribo.Mesh.rectangle((0.0, 1.0), (0.0, 1.0), 2, 2)
    sets = m.edge_sets
    sets["corner"] = np.vstack([sets["top"], sets["right"]])
    sets["split"] = np.vstack([sets["top"][:1], sets["bottom"][:1]])
    sets["loop"] = np.vstack([sets["top"], sets["right"], sets["bottom"], sets["left"]])
    return tribo.Mesh(m.points, m.triangles, sets)


def test_contact_geometry_errors() -> None:
    m = l_shape()
    common: dict[str, Any] = dict(young=1.0, poisson=0.3, clamped="left")
    # A bent set is one chain of edges: accepted; all four sides are a closed loop, accepted too, but the clamp on
    # its left side overlaps it.
    xi = tribo.Problem(m, contact="corner", **common).node_abscissae
    assert xi[-1] - xi[0] == pytest.approx(2.0)
    raises(tribo.ContactGeometryError, "ContactOverlapsDirichlet", lambda: tribo.Problem(m, contact="loop", **common))
    raises(tribo.ContactGeometryError, None, lambda: tribo.Problem(m, contact="split", **common))
    raises(
        tribo.ContactGeometryError, "ContactOverlapsDirichlet", lambda: tribo.Problem(m, contact="left", **common)
    )
    raises(tribo.ContactGeometryError, "BadObstacle", lambda: tribo.Obstacle.circle(-1.0), "radius")
    raises(tribo.ContactGeometryError, "BadObstacle", lambda: tribo.Obstacle.polyline([0.0, 0.0], [1.0, 1.0]))
    raises(tribo.ContactGeometryError, "BadInput", lambda: tribo.Obstacle.function(3.0))  # type: ignore[arg-type]
    raises(tribo.ContactGeometryError, "BadInput", lambda: hertz_problem(obstacle="circle"))
    raises(tribo.ContactGeometryError, "BadObstacle", lambda: hertz_problem(approach=float("nan")))
    raises(tribo.ContactGeometryError, "UnknownChoice", lambda: hertz_problem(space="P2"))
    raises(tribo.ContactGeometryError, "BadMultiplierMesh", lambda: hertz_problem(multiplier_ratio=1.0, multiplier_size=0.1))


def test_multiplier_point_errors() -> None:
    raises(
        tribo.ContactGeometryError,
        "MultiplierPointsNotIncreasing",
        lambda: hertz_problem(multiplier_points=[-2.0, 0.5, 0.0, 2.0]),
    )
    e = raises(
        tribo.ContactGeometryError, "MultiplierPointOffContact", lambda: hertz_problem(multiplier_points=[-3.0, 0.0, 2.0])
    )
    assert e.details["index"] == 0 and e.details["distance"] == pytest.approx(1.0)
    raises(
        tribo.ContactGeometryError,
        "MultiplierPointOffContact",
        lambda: hertz_problem(multiplier_points=[[-2.0, 0.0], [0.0, 0.5], [2.0, 0.0]]),
    )
    raises(
        tribo.ContactGeometryError, "MultiplierMeshDoesNotCover", lambda: hertz_problem(multiplier_points=[-1.0, 2.0])
    )
    raises(tribo.ContactGeometryError, "BadMultiplierMesh", lambda: hertz_problem(multiplier_size=-0.1))
    raises(tribo.ContactGeometryError, "BadMultiplierMesh", lambda: hertz_problem(multiplier_ratio=0.0))


def test_gap_function_errors_are_chained() -> None:
    def bad(xi: float) -> float:
        raise RuntimeError("no gap here")

    e = raises(tribo.ContactGeometryError, "BadObstacle", lambda: hertz_problem(obstacle=bad))
    assert isinstance(e.__cause__, RuntimeError)
    e = raises(tribo.ContactGeometryError, "BadObstacle", lambda: hertz_problem(obstacle=lambda xi: "far"))
    assert isinstance(e.__cause__, TypeError)
    with pytest.raises(ZeroDivisionError):
        tribo.Obstacle.function(lambda xi: 1 / 0).gap0(1.0)


def test_a_gap_function_that_raises_during_a_solve_raises_from_it() -> None:
    """The error estimate evaluates the gap between the points checked when the problem was built: an
    exception the gap function raises there reaches the caller of `solve` (a KeyboardInterrupt as it is),
    and the next solve, with the function sound again, converges."""
    state: dict[str, Any] = {"raise": None}
    mesh = tribo.Mesh.rectangle((-2.0, 2.0), (-1.0, 0.0), 8, 2)
    nodes = set(np.round(np.linspace(-2.0, 2.0, 9), 12))

    def gap(xi: float) -> float:
        if state["raise"] is not None and round(xi, 12) not in nodes:
            raise state["raise"]("between the nodes")
        return xi * xi / 2.0

    problem = tribo.Problem(
        mesh, young=200.0, poisson=0.3, clamped="bottom", contact="top", obstacle=tribo.Obstacle.function(gap), approach=0.01
    )
    for exc in (RuntimeError, KeyboardInterrupt):
        state["raise"] = exc
        with pytest.raises(exc, match="between the nodes"):
            problem.solve(mu=0.3)
    state["raise"] = None
    assert problem.solve(mu=0.3).report.status == "converged"


def test_settings_errors(hertz: tribo.Problem) -> None:
    raises(tribo.SettingsError, "BadMaterial", lambda: hertz_problem(young=-1.0), "Young")
    raises(tribo.SettingsError, "BadMaterial", lambda: hertz_problem(poisson=0.5), "Poisson")
    # No support: the block is held by the contact alone, and nothing presses it against the cylinder.
    raises(tribo.ContactGeometryError, "HeldOnlyByContact", lambda: hertz_problem(clamped=[]).solve(), "support")
    raises(tribo.SettingsError, "NonFiniteLoad", lambda: hertz_problem(body_force=(0.0, np.inf)))
    raises(tribo.SettingsError, "TractionOnContact", lambda: hertz_problem(tractions={"top": (0.0, -1.0)}))
    raises(tribo.SettingsError, "BadInput", lambda: hertz_problem(body_force=(1.0, 2.0, 3.0)))
    raises(tribo.SettingsError, "BadInput", lambda: hertz_problem(clamped=3))
    raises(tribo.SettingsError, "BadSetting", lambda: hertz.solve(mu=-0.1), "'mu'")
    raises(tribo.SettingsError, "BadSetting", lambda: hertz.solve(mu=float("nan")))
    e = raises(tribo.SettingsError, "Gamma0TooLarge", lambda: hertz.solve(gamma0=2 * hertz.gamma0_bound))
    assert e.details["bound"] == hertz.gamma0_bound and e.details["element"] == hertz.gamma0_bound_element
    raises(tribo.SettingsError, "BadSetting", lambda: hertz.solve(gamma0_fraction=1.0), "gamma0_fraction")
    raises(tribo.SettingsError, "BadSetting", lambda: hertz.solve(gamma0=-1.0))
    raises(tribo.SettingsError, "BadSettingValue", lambda: hertz.solve(gamma0=0.0, gamma0_fraction=0.5))
    raises(tribo.SettingsError, "BadSettingValue", lambda: hertz.solve(check_gamma0=False), "explicit gamma0")
    raises(tribo.SettingsError, "BadSetting", lambda: hertz.solve(qp_tol=0.0), "'qp_tol'")
    raises(tribo.SettingsError, "BadSetting", lambda: hertz.solve(qp_max_iter=0))
    raises(tribo.SettingsError, "BadSetting", lambda: hertz.solve(mu=0.3, fp_tol=2.0))
    raises(tribo.SettingsError, "BadSetting", lambda: hertz.solve(mu=0.3, fp_relaxation=0.0))
    raises(tribo.SettingsError, "BadSetting", lambda: hertz.solve(mu=0.3, fp_max_iter=0))
    raises(tribo.SettingsError, "BadThreshold", lambda: hertz.solve(threshold=-1.0))
    raises(tribo.SettingsError, "BadThreshold", lambda: hertz.solve(threshold=[0.1, 0.2]), "multiplier dofs")
    raises(tribo.SettingsError, "BadThreshold", lambda: hertz.solve(threshold=np.full(hertz.n_multipliers, np.nan)))
    raises(tribo.SettingsError, "BadFriction", lambda: hertz.solve(mu=0.3, threshold=0.1))
    raises(tribo.SettingsError, "BadFriction", lambda: hertz.solve(friction="coulomb"))
    raises(tribo.SettingsError, "BadFriction", lambda: hertz.solve(friction="tresca", mu=0.3))
    raises(tribo.SettingsError, "UnknownChoice", lambda: hertz.solve(friction="viscous"))  # type: ignore[arg-type]
    raises(tribo.SettingsError, "UnknownChoice", lambda: hertz.solve(qp_kkt_solver="mumps"))  # type: ignore[arg-type]
    raises(tribo.SettingsError, "BadSettingValue", lambda: hertz.solve(qp_max_iter=2**32), "qp_max_iter")
    raises(tribo.SettingsError, "BadSettingValue", lambda: hertz.solve(qp_max_iter=-1), "qp_max_iter")
    raises(tribo.SettingsError, "BadSettingValue", lambda: hertz.solve(fp_max_iter=2.5), "fp_max_iter")
    raises(tribo.SettingsError, "BadSettingValue", lambda: hertz.solve(qp_tol="tight"), "qp_tol")
    raises(tribo.SettingsError, "BadInput", lambda: hertz.solve(fp_max_iter=2**70), "out of range")
    raises(tribo.SettingsError, "BadInput", lambda: hertz.solve(progress=42))  # type: ignore[arg-type]
    raises(tribo.SettingsError, "BadInput", lambda: hertz.evaluate_multiplier([1.0], [0.0]))


def test_unknown_and_renamed_settings_are_type_errors(hertz: tribo.Problem) -> None:
    """An unknown keyword is a TypeError, as for any Python function, and the message lists the settings
    (the names of 0.1's kkt_solver, working_set and relaxation now carry their qp_/fp_ prefix)."""
    for old in ("kkt_solver", "working_set", "relaxation", "fp_tolerance"):
        with pytest.raises(TypeError, match=f"'{old}'.*qp_kkt_solver.*fp_relaxation"):
            hertz.solve(**{old: 1})


def test_progress_callback_errors_propagate(hertz: tribo.Problem) -> None:
    def boom(*args: object) -> None:
        raise KeyError("stop")

    with pytest.raises(KeyError):
        hertz.solve(mu=0.3, progress=boom)


def test_solver_error_beyond_the_admissible_bound(hertz: tribo.Problem) -> None:
    # Far above the bound K − G is indefinite: with the bound check off the factorization of A fails.
    e = raises(
        tribo.SolverError,
        "NotPositiveDefinite",
        lambda: hertz.solve(gamma0=1e4 * hertz.gamma0_bound, check_gamma0=False),
        "not positive definite",
    )
    assert "what" in e.details
    # Slightly above it, the global matrix may still be definite: the solve goes through.
    assert hertz.solve(gamma0=1.01 * hertz.gamma0_bound, check_gamma0=False).report.gamma0 > hertz.gamma0_bound


def test_no_panic_on_garbage() -> None:
    """Whatever goes in is refused with an ordinary exception, never a pyo3 PanicException."""
    garbage: list[Callable[[], Any]] = [
        lambda: tribo.Mesh(None, None),  # type: ignore[arg-type]
        lambda: tribo.Mesh([[1e308, 1e308], [-1e308, 0.0], [0.0, 1e308]], [[0, 1, 2]]),
        lambda: tribo.Mesh(SQUARE_PTS, [[0, 1, 2**62]]),
        lambda: tribo.Mesh(np.zeros((0, 2)), np.zeros((0, 3), dtype=np.uint8)),
        lambda: tribo.Mesh.graded_rectangle((0, 1), (0, 1), side="top", segment=(0, 1), h_min=1e-300, h_max=1.0, growth=1e-300),
        lambda: tribo.Mesh.rectangle((0.0, 1e-310), (0.0, 1.0), 3, 3),
        lambda: tribo.Mesh.rectangle((0.0, 1.0), (0.0, 1.0), 2**40, 2**40),
        lambda: hertz_problem(multiplier_points=np.array([[np.nan, 0.0], [1.0, 0.0]])),
        lambda: hertz_problem(multiplier_points=[]),
        lambda: hertz_problem(multiplier_ratio=float("inf")),
        lambda: hertz_problem(young=float("nan")),
        lambda: hertz_problem(obstacle=tribo.Obstacle.polyline([], [])),
        lambda: hertz_problem(obstacle=lambda xi: float("inf")),
    ]
    for k, f in enumerate(garbage):
        with pytest.raises(BaseException) as info:  # noqa: PT011 - the point is to see every kind
            f()
        # Every one is refused, with an ordinary exception (a TriboError or a TypeError), not a panic.
        assert type(info.value).__name__ != "PanicException", (k, info.value)
        assert isinstance(info.value, (tribo.TriboError, TypeError)), (k, info.value)


@pytest.mark.parametrize("exc", [KeyboardInterrupt, SystemExit])
def test_interrupts_in_a_gap_function_propagate_unchanged(exc: type[BaseException]) -> None:
    """D7: KeyboardInterrupt or SystemExit raised inside a gap function is not turned into a TriboError."""

    def gap(xi: float) -> float:
        raise exc()

    with pytest.raises(exc):
        hertz_problem(obstacle=gap)


def test_gap_function_errors_belong_to_their_thread() -> None:
    """D8: two threads share one Obstacle.function; the failures of one never reach the other."""
    import threading

    def gap(xi: float) -> float:
        if threading.current_thread().name == "failing":
            raise RuntimeError("thread A's failure")
        return xi * xi / 2.0

    obstacle = tribo.Obstacle.function(gap)
    mesh = tribo.Mesh.rectangle((-2.0, 2.0), (-1.0, 0.0), 8, 2)
    leaked: list[BaseException] = []
    failures = 0

    def good() -> None:
        for _ in range(40):
            try:
                tribo.Problem(mesh, young=200.0, poisson=0.3, clamped="bottom", contact="top", obstacle=obstacle, approach=0.01).solve()
            except BaseException as e:  # noqa: BLE001 - any exception here is the leak under test
                leaked.append(e)

    def bad() -> None:
        nonlocal failures
        for _ in range(40):
            try:
                tribo.Problem(mesh, young=200.0, poisson=0.3, clamped="bottom", contact="top", obstacle=obstacle, approach=0.01)
            except tribo.ContactGeometryError as e:
                assert isinstance(e.__cause__, RuntimeError)
                failures += 1

    threads = [threading.Thread(target=good, name="good"), threading.Thread(target=bad, name="failing")]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not leaked, leaked[:3]
    assert failures == 40
