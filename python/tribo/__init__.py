"""tribo: 2D frictional contact in linear elasticity with the stabilized Lagrange multiplier method.

The compiled core lives in the private module ``tribo._tribo``; this package re-exports it, gives its
solves a typed surface (``tribo.problem.Problem``, whose results are the plain data classes of
``tribo.results``: ``Solution``, ``Report``, ``History``, and ``Adaptive`` and ``AdaptiveHistory`` with their ``Level``s) and adds mesh input/output (``tribo.io``), TOML scenes (``tribo.scene``), a command line (``tribo.cli``) and,
if matplotlib is installed, plots (``tribo.plot``, not imported here).

>>> import tribo
>>> mesh = tribo.Mesh.rectangle((0.0, 1.0), (0.0, 1.0), 4, 4)
>>> problem = tribo.Problem(mesh, young=1.0, poisson=0.3, clamped="bottom", contact="top",
...                         obstacle=tribo.Obstacle.flat(), approach=0.01)
>>> solution = problem.solve()
>>> solution.report.status
'converged'
"""

import os as _os

# The compiled module allocates with mimalloc. It keeps freed pages for a quarter of a second before it
# returns them to the system: long enough that the next level of an adaptive loop reuses them instead of
# faulting in fresh ones (the kernel zeroing fresh pages was 16 % of a loop's time), short enough that a
# large solve does not hold what it freed at its peak (1M unknowns: 1.08 times the Rust peak, 1.37 times
# when pages were never returned; docs/python_memory.md, study 17). A user's own MIMALLOC_PURGE_DELAY wins.
_os.environ.setdefault("MIMALLOC_PURGE_DELAY", "250")

from tribo._tribo import STATE_NAMES, Mesh, Obstacle, Support, __version__, choices, solver_defaults, solver_settings
from tribo.errors import ContactGeometryError, MeshError, SettingsError, SolverError, TriboError
from tribo.checks import SceneWarning, check_solution
from tribo.io import read_mesh, write_vtu
from tribo.problem import Body, Pair, Problem
from tribo.results import Adaptive, AdaptiveHistory, History, Level, PairResult, Report, Solution
from tribo.scene import SceneError, load_scene

__all__ = [
    "STATE_NAMES",
    "Adaptive",
    "AdaptiveHistory",
    "Body",
    "ContactGeometryError",
    "History",
    "Level",
    "Mesh",
    "MeshError",
    "Obstacle",
    "Pair",
    "PairResult",
    "Problem",
    "Report",
    "SceneError",
    "SceneWarning",
    "SettingsError",
    "Solution",
    "SolverError",
    "Support",
    "TriboError",
    "__version__",
    "check_solution",
    "choices",
    "load_scene",
    "read_mesh",
    "solver_defaults",
    "solver_settings",
    "write_vtu",
]
