"""tribo's exceptions: ``TriboError`` (a ``ValueError``) and one subclass per kind of bad input.

Every error the core reports is raised as the subclass of its category by the compiled module
(``tribo._tribo``), with the core's message (what and where), ``kind`` (the name of the core's error
variant, e.g. ``'DegenerateTriangle'``; ``'BadInput'`` for input refused before it reaches the core) and
``details`` (a dict of the variant's fields, e.g. ``{'element': 3, 'area': 0.0}``). A numerical outcome is
never an exception: it is ``Report.status``.
"""

from __future__ import annotations

from typing import Any

__all__ = ["ContactGeometryError", "MeshError", "SettingsError", "SolverError", "TriboError"]


class TriboError(ValueError):
    """Base class of tribo's errors: bad input, never a numerical outcome (see Report.status).

    Attributes: ``kind`` (the name of the core's error variant, e.g. 'DegenerateTriangle') and ``details``
    (a dict of its fields, e.g. {'element': 3, 'area': 0.0, ...}).
    """

    kind: str
    details: dict[str, Any]


class MeshError(TriboError):
    """A bad mesh: arrays of the wrong shape or dtype, non-finite coordinates, degenerate or inverted triangles,
    unknown or bad edge sets, bad generator parameters."""


class ContactGeometryError(TriboError):
    """A bad contact set-up: Γ_C not one chain of edges (open or closed) or clamped, two sides that do not face,
    a bad obstacle, bad multiplier points."""


class SettingsError(TriboError):
    """A bad material, load, support, friction law or solver setting (γ0 above its admissible bound among
    them)."""


class SolverError(TriboError):
    """The linear algebra refused the problem (factorization or QP set-up failed)."""
