"""The house rules of the Python side: modules readable in one sitting, and a binding that only converts.

The core's own rules (the layer table of ``crates/tribo/src``, its file sizes) are checked by
``crates/tribo/tests/integration/layout.rs``; ARCHITECTURE.md is the map of both.
"""

from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
MAX_MODULE_LINES = 600
MAX_BINDING_LINES = 1200


def test_every_python_module_is_readable_in_one_sitting() -> None:
    modules = sorted((ROOT / "python" / "tribo").rglob("*.py"))
    assert len(modules) > 5, modules
    long = [f"{m.relative_to(ROOT)}: {n} lines" for m in modules if (n := len(m.read_text().splitlines())) > MAX_MODULE_LINES]
    assert not long, f"modules over {MAX_MODULE_LINES} lines: {long}"


def test_the_binding_only_converts() -> None:
    """The pyo3 crate stays a thin layer: rules, tables and defaults live in the core, convenience in Python."""
    files = sorted((ROOT / "crates" / "tribo-py" / "src").glob("*.rs"))
    total = sum(len(f.read_text().splitlines()) for f in files)
    assert total <= MAX_BINDING_LINES, f"crates/tribo-py/src holds {total} lines (at most {MAX_BINDING_LINES})"
