"""What the fuzz tests (``test_fuzz_*.py``) share: their Hypothesis settings and the promise they check.

Budget. Each fuzz test runs a small fixed number of examples (its ``default``), so that all of them take
about a minute on two cores. ``TRIBO_FUZZ_EXAMPLES=N`` runs N examples per fuzz test instead, for a longer
campaign (``TRIBO_FUZZ_EXAMPLES=2000 python -m pytest tests/python -k fuzz``).

Reproducible. Examples are derandomized (a function of the test alone) and no example database is kept,
so CI, a laptop and a rerun see the same inputs; a failure prints the input that caused it.

The promise (README.md, "What tribo guarantees"). Whatever goes in, the outcome is one of: a ``tribo.TriboError``; a plain
``TypeError`` where an argument has a wrong Python type; or a result, and if that result is a solution
whose status is ``converged``, every field it reports is finite.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any, TypeVar

# Hypothesis keeps caches (and, for failing tests, patches) in .hypothesis/ under the working directory:
# keep them out of the repository.
os.environ.setdefault("HYPOTHESIS_STORAGE_DIRECTORY", str(Path(tempfile.gettempdir()) / "tribo-hypothesis"))

import numpy as np  # noqa: E402
from hypothesis import HealthCheck, settings  # noqa: E402

import tribo

T = TypeVar("T")

EXAMPLES = int(os.environ.get("TRIBO_FUZZ_EXAMPLES", "0"))


def fuzz(default: int) -> settings:
    """Settings of one fuzz test: ``default`` examples, or ``TRIBO_FUZZ_EXAMPLES`` when it is set."""
    return settings(
        max_examples=EXAMPLES or default,
        deadline=None,  # solve times vary with the machine's load; the budget is the example count
        derandomize=True,
        database=None,
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much],
    )


def outcome(f: Callable[[], T], *, wrong_type: bool = False) -> T | None:
    """Calls f: its result, or None if it raised a TriboError (or, when an argument has a wrong Python type,
    a TypeError). Anything else, pyo3's PanicException included, fails the test naming what was raised."""
    try:
        return f()
    except tribo.TriboError as e:
        assert isinstance(e.kind, str) and isinstance(e.details, dict), f"{type(e).__name__} without kind/details"
        return None
    except TypeError:
        if wrong_type:
            return None
        raise
    except (KeyboardInterrupt, SystemExit):
        raise
    except BaseException as e:  # PanicException derives from BaseException: report it as a failure
        raise AssertionError(f"raised {type(e).__module__}.{type(e).__name__}: {e}") from e


# Every array a Solution reports.
SOLUTION_ARRAYS = (
    "displacement",
    "stress",
    "von_mises",
    "reactions",
    "multiplier_abscissae",
    "lambda_n",
    "lambda_t",
    "friction_threshold",
    "edge_abscissae",
    "sigma_n",
    "sigma_t",
    "node_abscissae",
    "u_n",
    "slip",
    "gap",
)


def assert_honest(s: tribo.Solution) -> None:
    """A 'converged' solution reports only finite values (fields, forces, residuals, penetration)."""
    r = s.report
    if r.status != "converged":
        return
    bad = [name for name in SOLUTION_ARRAYS if not np.isfinite(getattr(s, name)).all()]
    scalars: dict[str, Any] = {
        "kkt_max": s.kkt_max,
        "max_penetration": s.max_penetration,
        "normal_force": s.normal_force,
        "tangential_force": s.tangential_force,
        "contact_width": s.contact_width,
        "stick_width": s.stick_width,
        **{f"kkt[{k}]": v for k, v in s.kkt.items()},
    }
    bad += [name for name, v in scalars.items() if not np.isfinite(v)]
    if not np.isfinite(r.residual_history).all():
        bad.append("report.residual_history")
    assert not bad, f"status 'converged' with non-finite {', '.join(bad)}"
