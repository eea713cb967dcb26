"""Type stub of the compiled module tribo._tribo (checked with `python -m mypy.stubtest tribo._tribo`)."""

from collections.abc import Callable, Mapping, Sequence
from typing import Any, Literal, Self, final, overload

import numpy as np
import numpy.typing as npt
from typing_extensions import disjoint_base

_Floats1 = npt.NDArray[np.float64]
_Floats2 = npt.NDArray[np.float64]
_Ints = npt.NDArray[np.int64]
_ArrayLike = npt.ArrayLike
_Pair = tuple[float, float] | Sequence[float] | npt.NDArray[np.floating[Any]]

__all__ = [
    "__version__",
    "STATE_NAMES",
    "MAX_CELLS",
    "Mesh",
    "Obstacle",
    "Problem",
    "Support",
    "solver_defaults",
    "solver_settings",
    "choices",
    "format_number",
    "check_adapt",
]

__version__: str
STATE_NAMES: list[str]
MAX_CELLS: int

def solver_defaults() -> dict[str, Any]: ...
def solver_settings() -> dict[str, dict[str, Any]]: ...
def choices() -> dict[str, list[str]]: ...
def format_number(x: float, digits: int = 3) -> str: ...
def check_adapt(a: tuple[Any, ...]) -> None: ...
@final
class Mesh:
    def __new__(
        cls, points: _ArrayLike, triangles: _ArrayLike, edge_sets: Mapping[str, _ArrayLike] | None = None
    ) -> Mesh: ...
    @staticmethod
    def rectangle(
        x: _Pair, y: _Pair, nx: int, ny: int, *, diagonal: Literal["right", "left", "alternating"] | None = None
    ) -> Mesh: ...
    @staticmethod
    def graded_rectangle(
        x: _Pair,
        y: _Pair,
        *,
        side: Literal["bottom", "right", "top", "left"],
        segment: _Pair,
        h_max: float,
        h_min: float | None = None,
        growth: float | None = None,
    ) -> Mesh: ...
    @staticmethod
    def ring_sector(
        center: tuple[float, float],
        radii: tuple[float, float],
        angles: tuple[float, float],
        *,
        h_max: float,
        h_min: float | None = None,
        arc: tuple[float, float] | None = None,
        growth: float | None = None,
    ) -> Mesh: ...
    @staticmethod
    def disc(
        center: tuple[float, float], radius: float, *, rings: int, angles: tuple[float, float] = ...
    ) -> Mesh: ...
    @staticmethod
    def plate_with_hole(
        center: tuple[float, float], radius: float, half_widths: tuple[float, float], *, around: int, across: int
    ) -> Mesh: ...
    def with_curve(self, edge_set: str, center: tuple[float, float], radius: float) -> Mesh: ...
    @property
    def curves(self) -> dict[str, tuple[float, float, float]]: ...
    @property
    def points(self) -> _Floats2: ...
    @property
    def triangles(self) -> _Ints: ...
    @property
    def edge_sets(self) -> dict[str, _Ints]: ...
    @property
    def n_nodes(self) -> int: ...
    @property
    def n_triangles(self) -> int: ...
    @property
    def max_diameter(self) -> float: ...
    @property
    def bounding_box(self) -> tuple[float, float, float, float]: ...
    def diameters(self) -> _Floats1: ...

@final
class Obstacle:
    @staticmethod
    def flat() -> Obstacle: ...
    @staticmethod
    def circle(radius: float, center: float = 0.0) -> Obstacle: ...
    @staticmethod
    def parabola(radius: float, center: float = 0.0) -> Obstacle: ...
    @staticmethod
    def polyline(xi: _ArrayLike, gap: _ArrayLike) -> Obstacle: ...
    @staticmethod
    def function(gap: Callable[[float], float]) -> Obstacle: ...
    @staticmethod
    def line(point: tuple[float, float], normal: tuple[float, float]) -> Obstacle: ...
    @staticmethod
    def disc(center: tuple[float, float], radius: float) -> Obstacle: ...
    @staticmethod
    def hole(center: tuple[float, float], radius: float) -> Obstacle: ...
    @staticmethod
    def profile(points: _ArrayLike) -> Obstacle: ...
    @staticmethod
    def distance(distance: Callable[[float, float], float]) -> Obstacle: ...
    @property
    def kind(
        self,
    ) -> Literal["flat", "circle", "parabola", "polyline", "function", "line", "disc", "hole", "distance"]: ...
    @property
    def radius(self) -> float | None: ...
    @property
    def center(self) -> float | None: ...
    @overload
    def gap0(self, xi: float) -> float: ...
    @overload
    def gap0(self, xi: _ArrayLike) -> _Floats1: ...

@final
class Support:
    @staticmethod
    def clamp(edge_set: str) -> Support: ...
    @staticmethod
    def roller(edge_set: str) -> Support: ...
    @staticmethod
    def displacement(edge_set: str, *, x: float | None = None, y: float | None = None) -> Support: ...
    @staticmethod
    def rotation(edge_set: str, center: tuple[float, float], angle: float) -> Support: ...
    @property
    def kind(self) -> Literal["clamp", "roller", "displacement", "rotation"]: ...
    @property
    def edge_set(self) -> str: ...
    @property
    def value(self) -> tuple[float | None, float | None]: ...

@disjoint_base
class Problem:
    """The compiled problem; ``tribo.Problem`` (``tribo.problem``) is its typed surface."""

    @property
    def _data(self) -> dict[str, Any]: ...

    def __new__(
        cls,
        mesh: Mesh | Sequence[tuple[str, Mesh, list[tuple[float, float]], list[int] | None, list[str], list[Support], list[tuple[str, tuple[float, float]]]]],
        *,
        materials: Sequence[tuple[float, float]] | None = None,
        regions: _ArrayLike | None = None,
        contact: str,
        clamped: Sequence[str] | None = None,
        supports: Sequence[Support] | None = None,
        obstacle: Obstacle | None = None,
        approach: float | None = None,
        shift: float | None = None,
        tractions: Sequence[tuple[str, Sequence[float]]] | None = None,
        rotation: tuple[tuple[float, float], float] | None = None,
        body_force: _Pair | None = None,
        multiplier_ratio: float | None = None,
        multiplier_size: float | None = None,
        multiplier_points: _ArrayLike | None = None,
        space: Literal["P0", "P1", "p0", "p1"] | None = None,
        primary: str | None = None,
        model: Literal["plane_strain", "plane_stress", "axisymmetric"] | None = None,
        formulation: Literal["auto", "displacement", "mixed"] | None = None,
        pairs: Sequence[tuple[str, Obstacle | None, float | None, float | None, float | None]] | None = None,
    ) -> Self: ...
    def _solve(self, options: Mapping[str, Any]) -> dict[str, Any]: ...
    def _solve_history(self, steps: _ArrayLike, options: Mapping[str, Any]) -> dict[str, Any]: ...
    def _solve_adaptive(
        self,
        options: Mapping[str, Any],
        a: tuple[float | None, int | None, float | None, tuple[str | None, str | None, str | None], int | None, float | None],
        steps: npt.ArrayLike | None = None,
        on: list[int] = ...,
    ) -> tuple[
        dict[str, Any],
        list[
            tuple[
                tuple[int, int, int, list[tuple[str, float]], float, float],
                str,
                tuple[list[tuple[int, int, int, int]], Mesh, _Floats1, _Ints],
                bool,
            ]
        ],
        str,
    ]: ...
    def contact_normals(self, xi: _ArrayLike, pair: int = 0) -> _Floats2: ...
    def contact_points(self, xi: _ArrayLike, pair: int = 0) -> _Floats2: ...
    def evaluate_multiplier(self, values: _ArrayLike, xi: _ArrayLike) -> _Floats1: ...
    def energy_norm(self, u: _ArrayLike) -> float: ...
