"""Fuzzing the scene loader and ``tribo run`` (fuzzing report D14/D15).

Budget: about 1 600 examples in all by default; ``TRIBO_FUZZ_EXAMPLES=N`` runs N per test (fuzzing.py says
how). The promise checked: loading a scene gives a Scene or a TriboError (SceneError is one); ``tribo run``
exits with 0, 1 or 3 and prints no traceback, whatever the file holds.

The scenes ``tribo run`` solves keep a few values out, because they reach known core defects or would
only make the run long (each exclusion is commented where it is made): multiplier meshes far finer than
the FE mesh (D2, D3: a panic, which the command line reports as an internal error, or a process abort),
cell sizes between "refused" and "a few thousand cells" (a large mesh is slow, not wrong).
test_fuzz_api.py feeds those values to the API in a marked test.
"""

from __future__ import annotations

import contextlib
import io
import tempfile
import tomllib
from pathlib import Path
from typing import Any

from fuzzing import fuzz
from test_io import MSH22
from hypothesis import event, example, given
from hypothesis import strategies as st

import tribo
from tribo.cli import main
from tribo.scene import SCHEMA, Scene, load_scene, parse_scene

# ----- any dict, any bytes -----

LEAVES = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.integers(),
    st.integers(min_value=2**63),
    st.booleans(),
    st.text(max_size=8),
    st.none(),
)
VALUES = st.recursive(
    LEAVES, lambda inner: st.lists(inner, max_size=3) | st.dictionaries(st.text(max_size=6), inner, max_size=3), max_leaves=6
)
SECTION_NAMES = st.one_of(st.sampled_from([*SCHEMA, "title", "description"]), st.text(max_size=6))


@st.composite
def scene_dicts(draw: st.DrawFn) -> dict[str, Any]:
    """Dicts shaped like a parsed TOML scene: known tables and keys (and unknown ones), any values."""
    data: dict[str, Any] = {}
    for name in draw(st.lists(SECTION_NAMES, max_size=6, unique=True)):
        if name not in SCHEMA or draw(st.integers(0, 9)) == 0:
            data[name] = draw(VALUES)
            continue
        keys = st.one_of(st.sampled_from(sorted(SCHEMA[name])), st.text(max_size=6))
        data[name] = draw(st.dictionaries(keys, VALUES, max_size=4))
    return data


def loaded(f: Any) -> Scene | None:
    """f(): a Scene, or None for a TriboError; anything else fails."""
    try:
        scene = f()
    except tribo.TriboError as e:
        assert isinstance(e.kind, str) and isinstance(e.details, dict)
        return None
    assert isinstance(scene, Scene)
    return scene


@fuzz(800)
@given(scene_dicts())
@example({"solver": {"qp_max_iter": 2**64}, "material": {"young": 10**400}})
def test_fuzz_parse_scene_any_dict(data: dict[str, Any]) -> None:
    scene = loaded(lambda: parse_scene(data))
    if scene is not None:
        scene.to_dict()


@fuzz(300)
@given(st.one_of(st.binary(max_size=200), st.text(max_size=200).map(str.encode)))
@example(b"\xff\xfe[body]\n")
@example(b"")
def test_fuzz_load_scene_any_bytes(content: bytes) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "scene.toml"
        path.write_bytes(content)
        loaded(lambda: load_scene(path))
        run_cli(path, Path(tmp) / "out")


# ----- tribo run on hostile scenes -----

# A small Tresca scene (test_cli.SCENE) as {table: {key: TOML literal}}.
BASE: dict[str, dict[str, str]] = {
    "body": {"x": "[-1.0, 1.0]", "y": "[-1.0, 0.0]"},
    "material": {"young": "100.0", "poisson": "0.25"},
    "supports": {"clamped": '["bottom"]'},
    "contact": {"edge_set": '"top"'},
    "obstacle": {"shape": '"parabola"', "radius": "2.0", "approach": "0.005", "shift": "0.001"},
    "friction": {"threshold": "0.2"},
    "discretization": {"h": "0.25", "h_min": "0.03", "space": '"P0"', "multiplier_ratio": "2.0", "gamma0_fraction": "0.3"},
    "solver": {"qp_tol": "1e-9"},
}
# Accepted by the scene but extreme, and refused (not finite, too large for a float, not a number). The
# pools list the values that should run first: Hypothesis draws the first elements of a list more often.
NUMBERS = ["0.0", "-0.0", "-1.0", "1e-300", "1e300", "-1e300", "1e-12", "1e12", "nan", "-inf", "1" + "0" * 400, '"1.0"']
# Hostile TOML literals for each key (keys not listed take NUMBERS). Left out, with the reason:
# multiplier_ratio below 1e-2 and small multiplier_size: D2, D3;
# h, h_min and growth between 1e-300 (refused) and a few hundred cells per side: a long run, not a wrong one.
LITERALS: dict[str, list[str]] = {
    "young": ["1e-300", "1e300", "1.7976931348623157e308", "5e-324", "1e-310", "nan", "inf", "0.0", "-1.0", "1" + "0" * 400, '"stiff"'],
    "poisson": NUMBERS + ["0.5", "0.49999999999999994", "-1.0"],
    "x": ["[1.0, 1.0]", "[1.0, -1.0]", "[nan, 1.0]", "[-1e300, 1e300]", "[0.0, 1e-300]", "[0.0]", "[0.0, 1.0, 2.0]", '"x"'],
    "y": ["[0.0, 0.0]", "[0.0, -1.0]", "[-inf, 0.0]", "[-1e-300, 0.0]", "[-1e300, 0.0]", "[]"],
    "clamped": ["[]", '"top"', '["left", "right"]', '"nowhere"', "[1]", '["bottom", "bottom"]', "1"],
    "edge_set": ['"bottom"', '"left"', '"nowhere"', '""', "1"],
    "shape": ['"flat"', '"circle"', '"polyline"', '"cone"', "1"],
    "radius": NUMBERS + ["1e-12"],
    "approach": NUMBERS + ["1e-12", "10.0"],
    "shift": NUMBERS + ["1e-39", "10.0"],
    "threshold": NUMBERS + ["1e8"],
    "h": ["nan", "inf", "0.0", "-1.0", "1e-300", "1e300", "true", "2.0"],
    "h_min": ["nan", "0.0", "-1.0", "1e-300", "1e300", "0.25", "1.0"],
    "space": ['"P1"', '"p1"', '"P2"', '""', "1"],
    "multiplier_ratio": ["nan", "inf", "0.0", "-1.0", "1e300", "0.1", "true"],
    "gamma0_fraction": NUMBERS + ["1.0", "0.999999"],
    "qp_tol": NUMBERS + ["1e-16", "0.5"],
}
# Keys a scene may add: extra obstacle keys (D15), integers out of range (D14), other options.
EXTRA: dict[tuple[str, str], list[str]] = {
    ("obstacle", "xi"): ["[0.0, 1.0]", "[]", "[nan]"],
    ("obstacle", "gap"): ["[0.0, 0.0]", "[1.0]"],
    ("obstacle", "center"): NUMBERS,
    ("obstacle", "radus"): ["1.0"],
    ("friction", "mu"): NUMBERS + ["0.3"],
    ("loads", "body_force"): ["[0.0, -1.0]", "[nan, 0.0]", "[1e300, 0.0]", "[1.7976931348623157e308, 0.0]", "[0.0]"],
    ("loads", "tractions"): ['{ right = [1.0, 0.0] }', '{ top = [0.0, -1.0] }', '{ nowhere = [0.0, 1.0] }', "{ right = [nan, 0.0] }"],
    ("discretization", "grading"): ['"none"', '"auto"', "[0.0, 0.5]", "[0.5, -0.5]", "[nan, 1.0]", '"some"', "[-1e300, 1e300]"],
    ("discretization", "growth"): ["nan", "0.0", "-1.0", "1e-300", "1e300", "2.0"],
    ("discretization", "diagonal"): ['"left"', '"alternating"', '"up"'],
    ("discretization", "multiplier_size"): ["0.1", "0.0", "-1.0", "1e300"],
    ("discretization", "gamma0"): NUMBERS,
    ("solver", "qp_max_iter"): ["-1", "0", "1", "4294967295", "4294967296", "18446744073709551616", "1.5"],
    ("solver", "fp_max_iter"): ["-5", "0", "1", "4294967296", "true"],
    ("solver", "fp_tol"): NUMBERS,
    ("solver", "fp_relaxation"): NUMBERS + ["1.5"],
    ("solver", "qp_kkt_solver"): ['"qdldl"', '"mumps"'],
    ("solver", "qp_working_set"): ["false", "1"],
    ("body", "mesh"): ['"square.msh"', '"square.msh"', '"nowhere.msh"', '"scene.toml"', '"."'],
}
ENTRIES = sorted(EXTRA) + [(t, k) for t, keys in reversed(BASE.items()) for k in keys]
# What adding a key usually changes in the base scene so that it can still run (the rest of the time the
# conflict itself is tested): {(table, key): (entries removed, entries set)}. The multiplier sizes above
# are refused or coarse: a size far below the mesh's reaches D3.
ADJUST: dict[tuple[str, str], tuple[list[tuple[str, str]], dict[tuple[str, str], str]]] = {
    ("discretization", "multiplier_size"): ([("discretization", "multiplier_ratio")], {}),
    ("discretization", "gamma0"): ([("discretization", "gamma0_fraction")], {}),
    ("friction", "mu"): ([("friction", "threshold")], {}),
    ("discretization", "diagonal"): ([("discretization", "h_min")], {("discretization", "grading"): '"none"'}),
    ("obstacle", "xi"): ([("obstacle", "radius")], {("obstacle", "shape"): '"polyline"', ("obstacle", "gap"): "[0.0, 0.0]"}),
    ("obstacle", "gap"): ([("obstacle", "radius")], {("obstacle", "shape"): '"polyline"', ("obstacle", "xi"): "[-1.0, 1.0]"}),
    ("body", "mesh"): ([("body", "x"), ("body", "y"), ("discretization", "h"), ("discretization", "h_min")], {}),
}


@st.composite
def scene_texts(draw: st.DrawFn) -> str:
    """The base scene with one (or two) entries replaced or added with hostile TOML literals."""
    tables = {t: dict(keys) for t, keys in BASE.items()}
    n = draw(st.sampled_from([1, 1, 2]))
    for table, key in draw(st.lists(st.sampled_from(ENTRIES), min_size=n, max_size=n, unique=True)):
        removed, added = ADJUST.get((table, key), ([], {}))
        if draw(st.integers(0, 3)) > 0:
            for t, k in removed:
                tables[t].pop(k, None)
            for (t, k), v in added.items():
                tables.setdefault(t, {})[k] = v
        pool = EXTRA.get((table, key)) or LITERALS.get(key) or NUMBERS
        tables.setdefault(table, {})[key] = draw(st.sampled_from(pool))
        event(f"{table}.{key}")
    return render(tables)


def render(tables: dict[str, dict[str, str]]) -> str:
    return "".join(f"[{t}]\n" + "".join(f"{k} = {v}\n" for k, v in keys.items()) for t, keys in tables.items())


def run_cli(scene: Path, out: Path) -> int:
    """``tribo run SCENE --out OUT --no-plots`` in this process: exit code 0, 1 or 3, no traceback."""
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        code = main(["run", str(scene), "--out", str(out), "--no-plots"])
    text = err.getvalue()
    assert code in (0, 1, 3) and "Traceback" not in text, f"exit code {code}:\n{text}"
    if code == 1:
        assert text.splitlines()[-1].startswith("tribo: error: "), text
    return code


@fuzz(500)
@given(scene_texts())
@example(render(BASE))
def test_fuzz_tribo_run(text: str) -> None:
    with tempfile.TemporaryDirectory() as tmp:
        (Path(tmp) / "square.msh").write_text(MSH22)
        scene = Path(tmp) / "scene.toml"
        scene.write_text(text, encoding="utf-8")
        event(f"exit code {run_cli(scene, Path(tmp) / 'out')}")


# ----- the JSON Schema never flags what the reader takes -----


def _schema_errors(data: dict[str, Any]) -> list[str]:
    import json

    import jsonschema

    from tribo.scene_keys import SCHEMA_FILE

    schema = json.loads(SCHEMA_FILE.read_text(encoding="utf-8"))
    return [e.message for e in jsonschema.Draft202012Validator(schema).iter_errors(data)]


def _toml(text: str) -> dict[str, Any]:
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError:
        return {}


@fuzz(200)
@given(st.one_of(scene_texts().map(_toml), scene_dicts()))
@example(tomllib.loads(render(BASE)))
def test_fuzz_a_scene_the_reader_takes_meets_the_json_schema(data: dict[str, Any]) -> None:
    """An editor that checks scene files against scene.schema.json never flags one that tribo reads (the
    schema checks keys and types; the reader more)."""
    if loaded(lambda: parse_scene(data)) is not None:
        event("read")
        assert not _schema_errors(data), data
