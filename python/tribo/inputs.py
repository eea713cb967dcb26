"""What a ``Problem`` is made of, as users give it and as the compiled constructor takes it: the loads and
materials of a body, a body of two (``Body``), a further contact pair (``Pair``) and the rows of a history
(``history_steps``). Inputs refused here raise the ``TriboError`` kinds the compiled module raises.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from tribo import _tribo
from tribo.errors import ContactGeometryError, SettingsError

__all__ = ["Body", "Pair", "history_steps"]


def _settings_error(message: str) -> SettingsError:
    """A SettingsError for input refused before it reaches the core (``kind`` 'BadInput', as the compiled
    module's)."""
    e = SettingsError(message)
    e.kind, e.details = "BadInput", {}
    return e


def _contact_error(message: str) -> ContactGeometryError:
    """A ContactGeometryError for input refused before it reaches the core (``kind`` 'BadInput')."""
    e = ContactGeometryError(message)
    e.kind, e.details = "BadInput", {}
    return e


def _pair(value: Any, what: str) -> tuple[float, float]:
    try:
        a = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise _settings_error(f"{what} must be a pair of real numbers, got {value!r}") from e
    if a.shape != (2,):
        raise _settings_error(f"{what} must have shape (2,), got shape {a.shape}")
    return float(a[0]), float(a[1])


def _loads(clamped: Any, supports: Any, tractions: Any, pressures: Any = None) -> dict[str, Any]:
    """``clamped`` (a name or names), ``supports`` (a Support or several), ``tractions`` (a dict edge set name →
    (tx, ty)) and ``pressures`` (a dict edge set name → p, pressing along each edge's outward normal) as the lists
    the compiled constructor takes (None stays None; a traction [tx, ty], a pressure [p])."""
    out: dict[str, Any] = {}
    if clamped is not None:
        names = [clamped] if isinstance(clamped, str) else clamped
        if not (isinstance(names, Sequence) and all(isinstance(n, str) for n in names)):
            raise _settings_error(f"clamped must be an edge set name or a list of names, got {clamped!r}")
        out["clamped"] = list(names)
    if supports is not None:
        listed = [supports] if isinstance(supports, _tribo.Support) else supports
        if not (isinstance(listed, Sequence) and all(isinstance(x, _tribo.Support) for x in listed)):
            raise _settings_error(f"supports must be a tribo.Support or a list of them, got {supports!r}")
        out["supports"] = list(listed)
    if tractions is not None:
        if not isinstance(tractions, Mapping) or not all(isinstance(k, str) for k in tractions):
            raise _settings_error(f"tractions must be a dict edge set name -> (tx, ty), got {tractions!r}")
        out["tractions"] = [(name, list(_pair(g, f"traction on '{name}'"))) for name, g in tractions.items()]
    if pressures is not None:
        if not isinstance(pressures, Mapping) or not all(isinstance(k, str) for k in pressures):
            raise _settings_error(f"pressures must be a dict edge set name -> p, got {pressures!r}")
        for name, p in pressures.items():
            if isinstance(p, bool) or not isinstance(p, (int, float, np.floating, np.integer)):
                raise _settings_error(f"the pressure on '{name}' must be a number, got {p!r}")
        out["tractions"] = out.get("tractions", []) + [(name, [float(p)]) for name, p in pressures.items()]
    return out


def _materials(arguments: dict[str, Any], what: str = "Problem()") -> dict[str, Any]:
    """The material keywords as the compiled constructor takes them: ``young`` and ``poisson`` as one material,
    or ``materials`` (pairs (E, ν)) with ``regions`` (each triangle's index into them), never both; nothing for
    two bodies (``primary``), whose materials are their own."""
    young, poisson, materials, regions = (arguments.get(k) for k in ("young", "poisson", "materials", "regions"))
    prefix = "" if what == "Problem()" else f"{what}: "
    out: dict[str, Any] = {}
    if materials is None and regions is None:
        if arguments.get("primary") is None:
            for key, value in (("young", young), ("poisson", poisson)):
                if value is None:
                    raise TypeError(f"{what} missing required keyword argument: '{key}'")
                if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
                    raise TypeError(f"{what} argument '{key}' must be a real number, got {value!r}")
            out["materials"] = [(young, poisson)]
        elif young is not None or poisson is not None:
            out["materials"] = []  # refused by the compiled constructor: with primary=, the material is per body
        return out
    if materials is None or regions is None or young is not None or poisson is not None:
        raise _settings_error(f"{prefix}several materials take materials=[(E, ν), …] and regions= together, "
                              "without young and poisson")
    try:
        m = np.asarray(materials, dtype=np.float64)
    except (TypeError, ValueError, OverflowError) as e:
        raise _settings_error(f"{prefix}materials must be pairs (E, ν), got {materials!r}") from e
    if m.ndim != 2 or m.shape[1] != 2 or m.shape[0] == 0:
        raise _settings_error(f"{prefix}materials must be one or more pairs (E, ν), shape (n, 2), got shape {m.shape}")
    return {"materials": [(float(e), float(nu)) for e, nu in m], "regions": regions}


def _compiled_arguments(arguments: dict[str, Any]) -> dict[str, Any]:
    """The keywords of ``Problem`` as the compiled constructor takes them: the loads as lists
    (``_loads``), several materials as ``_materials`` checks them, and a callable gap as ``Obstacle.function``."""
    loads = _loads(*(arguments.get(k) for k in ("clamped", "supports", "tractions", "pressures")))
    out = {k: v for k, v in {**arguments, **loads}.items() if k not in ("young", "poisson", "pressures")}
    out.update(_materials(arguments))
    obstacle = arguments.get("obstacle")
    if obstacle is not None and not isinstance(obstacle, _tribo.Obstacle):
        if not callable(obstacle):
            raise _contact_error(f"obstacle must be a tribo.Obstacle or a callable gap(xi) -> float, got {obstacle!r}")
        out["obstacle"] = _tribo.Obstacle.function(obstacle)
    if arguments.get("pairs") is not None:
        out["pairs"] = [Pair.of(p)._compiled() for p in arguments["pairs"]]
    return out

@dataclass(frozen=True)
class Body:
    """One elastic body of a two-body problem (``Problem.two_bodies``): its mesh, material (``young`` and
    ``poisson``; or a coated body's ``materials`` [(E, ν), …] and ``regions``, each triangle's index into them)
    and supports and loads, with the edge set names of its own mesh (the problem calls them ``'name.set'``)."""

    name: str
    mesh: _tribo.Mesh
    young: float | None = None
    poisson: float | None = None
    clamped: str | Sequence[str] | None = None
    supports: _tribo.Support | Sequence[_tribo.Support] | None = None
    tractions: Mapping[str, Any] | None = None
    materials: Sequence[tuple[float, float]] | None = None
    regions: npt.ArrayLike | None = None
    pressures: Mapping[str, float] | None = None

    def _compiled(self) -> tuple[Any, ...]:
        loads = _loads(self.clamped, self.supports, self.tractions, self.pressures)
        given = _materials({"young": self.young, "poisson": self.poisson, "materials": self.materials,
                            "regions": self.regions}, what=f"Body {self.name!r}")
        regions = given.get("regions")
        if regions is not None:
            r = np.asarray(regions)
            if r.ndim != 1 or not (r.size == 0 or np.issubdtype(r.dtype, np.integer)) or (r < 0).any():
                raise _settings_error(f"Body {self.name!r}: regions must be one non-negative integer per triangle, "
                                      f"got {r.dtype} of shape {r.shape}")
            regions = r.astype(np.int64).tolist()
        return (self.name, self.mesh, given["materials"], regions, loads.get("clamped", []), loads.get("supports", []),
                loads.get("tractions", []))


@dataclass(frozen=True)
class Pair:
    """A further contact pair (``Problem(pairs=[…])``, ``Problem.two_bodies(pairs=[…])``): the edge set ``edge_set``
    (of either body, 'body.set', for two) against its own rigid
    ``obstacle`` (a ``tribo.Obstacle``; None: a flat one), moved by its own ``approach`` δ and ``shift`` s (None: 0),
    with its own Coulomb coefficient ``mu`` (None: the friction law's; a pair's own μ needs Coulomb friction, and
    μ = 0 makes it frictionless). Its multiplier mesh is of the problem's ratio or size."""

    edge_set: str
    obstacle: _tribo.Obstacle | None = None
    approach: float | None = None
    shift: float | None = None
    mu: float | None = None

    @classmethod
    def of(cls, value: Any) -> Pair:
        """A ``Pair``, or one from a tuple of its fields in order (an edge set name alone, too)."""
        if isinstance(value, Pair):
            return value
        if isinstance(value, str):
            return cls(value)
        if isinstance(value, tuple) and 1 <= len(value) <= 5:
            return cls(*value)
        raise TypeError(f"a contact pair must be a tribo.Pair (or a tuple of its fields: edge set, obstacle, "
                        f"approach, shift, mu), got {value!r}")

    def _compiled(self) -> tuple[Any, ...]:
        if not isinstance(self.edge_set, str):
            raise TypeError(f"a contact pair's edge_set must be a string, got {self.edge_set!r}")
        if self.obstacle is not None and not isinstance(self.obstacle, _tribo.Obstacle):
            raise _contact_error(f"pair {self.edge_set!r}: obstacle must be a tribo.Obstacle, got {self.obstacle!r}")
        return (self.edge_set, self.obstacle, self.approach, self.shift, self.mu)


def history_steps(
    approach: Any,
    shift: Any,
    load_factor: Any = None,
    displacements: Mapping[str, Any] | None = None,
    prescribed: Sequence[tuple[str, float]] = (),
    rotation: Any = None,
) -> npt.NDArray[np.float64]:
    """The steps of a history as rows (approach, shift, load_factor, the obstacle's angle, then the prescribed
    displacement components): each a number (the same at every step) or one value per step; ``load_factor``
    defaults to 1, the angle to NaN (the problem's own). ``displacements`` maps components of ``prescribed`` (the problem's ``prescribed``: names
    'set.x'/'set.y' and values) to their values; a component left out keeps its value. Without
    ``displacements`` the rows have four columns (every prescribed displacement as the problem has it)."""
    columns = {"approach": approach, "shift": shift, "load_factor": 1.0 if load_factor is None else load_factor,
               "rotation": np.nan if rotation is None else rotation}
    if displacements is not None:
        known = dict(prescribed)
        if not isinstance(displacements, Mapping):
            raise _settings_error(f"displacements must be a dict 'set.x'/'set.y' -> values, got {displacements!r}")
        unknown = sorted(set(displacements) - set(known))
        if unknown:
            names = ", ".join(known) if known else "none: the problem has no prescribed displacement"
            raise _settings_error(f"displacements: no prescribed component {unknown[0]!r} (the components: {names})")
        columns.update({name: displacements.get(name, value) for name, value in known.items()})
    arrays = {}
    for name, value in columns.items():
        try:
            a = np.asarray(value, dtype=np.float64)
        except (TypeError, ValueError) as e:
            raise _settings_error(f"{name} must be a number or a sequence of numbers, got {value!r}") from e
        if a.ndim > 1:
            raise _settings_error(f"{name} must be a number or a sequence of numbers, got shape {a.shape}")
        if a.size == 0:
            raise _settings_error(f"a history needs at least one step ({name} has no value)")
        arrays[name] = a
    n = max(a.size for a in arrays.values())
    for name, a in arrays.items():
        if a.size not in (1, n):
            raise _settings_error(
                f"{name} has {a.size} values, but the history has {n} steps (give one value, or one per step)"
            )
    return np.stack(np.broadcast_arrays(*(a.reshape(-1) for a in arrays.values())), axis=1)
