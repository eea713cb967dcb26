"""The house rules of the Python side: modules readable in one sitting, import layers without circles, and a
binding that only converts.

The core's own rules (the layer table of ``crates/tribo/src``, its file sizes) are checked by
``crates/tribo/tests/integration/layout.rs``; ARCHITECTURE.md is the map of both.
"""

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
MAX_MODULE_LINES = 600
MAX_BINDING_LINES = 1274  # 1200 until several materials per body (1220), then curved contact (the obstacles given by their geometry, the ring sector, the curves of a mesh: 1300), then the rotation support, then the disc and the plate with a hole (1340), then several contact pairs (their input and output, and the points of each side: 1375), then the problem's attributes handed over as one dict and its keywords read by the core (`tribo::ProblemKeywords`: 1314), then the exception hierarchy defined in Python (`tribo.errors`: 1274)


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


# The modules of python/tribo, bottom to top: a module imports only modules of the layers below its own,
# at the top of the file or inside a function (an import inside a function is still a dependency: it hid the
# circle cli -> sweep -> cli). ``__init__`` is the facade above them all; nothing inside imports it.
LAYERS: list[set[str]] = [
    {"_tribo", "errors"},
    {"results", "inputs"},
    {"problem"},
    {"checks"},
    {"io", "plot"},
    {"history"},
    {"adaptive"},
    {"scene_values"},
    {"scene_schema"},
    {"scene", "scene_keys"},
    {"run"},
    {"sweep"},
    {"cli"},
    {"__init__"},
]


def _tribo_imports(path: Path) -> set[str]:
    """The tribo modules a file imports anywhere in it (``from tribo import X`` names module X when X is one;
    otherwise it imports from the facade, ``__init__``)."""
    modules = {p.stem for p in (ROOT / "python" / "tribo").glob("*.py")} | {"_tribo"}
    out: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            out |= {a.name.split(".")[1] for a in node.names if a.name.startswith("tribo.")}
            out |= {"__init__" for a in node.names if a.name == "tribo"}
        elif isinstance(node, ast.ImportFrom) and node.module is not None:
            if node.module == "tribo":
                out |= {a.name if a.name in modules else "__init__" for a in node.names}
            elif node.module.startswith("tribo."):
                out.add(node.module.split(".")[1])
    return out


def test_the_package_imports_in_layers() -> None:
    layer = {name: k for k, names in enumerate(LAYERS) for name in names}
    files = sorted((ROOT / "python" / "tribo").glob("*.py"))
    unplaced = sorted(f.stem for f in files if f.stem not in layer)
    assert not unplaced, f"modules without a layer in LAYERS: {unplaced}"
    bad = [
        f"{f.stem} (layer {layer[f.stem]}) imports {m} (layer {layer[m]})"
        for f in files
        for m in sorted(_tribo_imports(f))
        if m != f.stem and layer[m] >= layer[f.stem]
    ]
    assert not bad, "imports against the layers: " + "; ".join(bad)


def test_the_layer_check_sees_imports_inside_functions(tmp_path: Path) -> None:
    """The check reads imports wherever they are: the hidden import that made the circle is caught."""
    f = tmp_path / "sweep.py"
    f.write_text("import numpy\n\ndef run():\n    from tribo.cli import run_scene\n    from tribo import plot, Problem\n")
    assert _tribo_imports(f) == {"cli", "plot", "__init__"}
