"""The meaning of every scene key (the table of the scene-file guide) and the JSON Schema of scene files:
each made by ``tribo.scene_keys`` from the scene reader's own checkers, shipped as made, and in step with
what the reader accepts (the property tests of ``test_fuzz_scene.py`` check that on hostile scenes)."""

from __future__ import annotations

import json
import re
import tomllib
from pathlib import Path
from typing import Any

import jsonschema
import pytest

from tribo.scene import parse_scene
from tribo.scene_keys import SCHEMA_FILE, json_schema

ROOT = Path(__file__).resolve().parents[2]
SCENES = sorted((ROOT / "python" / "tribo" / "scenes").glob("*.toml"))


def validator() -> jsonschema.Draft202012Validator:
    return jsonschema.Draft202012Validator(json.loads(SCHEMA_FILE.read_text(encoding="utf-8")))


def test_the_scene_key_table_means_every_key_and_is_the_generated_one() -> None:
    """Issue 38: the scene-key table described 30 keys only as "A finite number…", cut one row
    mid-sentence and was empty on the repository host. Every key the reader takes has a meaning, a unit and
    a default (no meaning for a key it does not take), the core's defaults are shown, no cell is cut or
    holds reST quotes, and the page holds the table this module renders."""
    from tribo import solver_defaults
    from tribo.scene_keys import END, MEANINGS, markdown_table, rows
    from tribo.scene_schema import describe_keys

    keys = {f"{table}.{key}" for table, key, _ in describe_keys()}
    assert keys == set(MEANINGS), f"without a meaning: {keys - set(MEANINGS)}; unknown: {set(MEANINGS) - keys}"
    table = rows()
    assert all(all(cell.strip() for cell in row) for row in table)
    assert not any("``" in cell for row in table for cell in row)
    assert all(row[5].endswith((".", ")")) for row in table), "a value cut mid-sentence"
    shown = {row[1].strip("`"): row[4] for row in table if row[0] == "[solver]"}
    assert shown["qp_tol"] == "1e-12" == f"{solver_defaults()['qp_tol']:g}"
    page = (ROOT / "docs" / "guide" / "scene-files.md").read_text(encoding="utf-8")
    assert markdown_table() in page, "regenerate it: python -m tribo.scene_keys docs/guide/scene-files.md"
    assert page.count(END) == 1



def test_an_empty_supports_list_meets_the_schema_as_the_reader_takes_it() -> None:
    """``supports = []`` (held by the contact alone) is read; the schema flagged it (minItems 1)."""
    data = tomllib.loads((SCENES[0].parent / "demo.toml").read_text(encoding="utf-8"))
    data["supports"] = []
    parse_scene(data)
    assert not list(validator().iter_errors(data))


def test_the_json_schema_is_shipped_as_made_and_valid() -> None:
    """scene.schema.json is a valid draft 2020-12 schema, the one ``json_schema()`` makes (regenerate it:
    python -m tribo.scene_keys python/tribo/scene.schema.json), and describes every key."""
    shipped = json.loads(SCHEMA_FILE.read_text(encoding="utf-8"))
    jsonschema.Draft202012Validator.check_schema(shipped)
    assert shipped == json_schema(), "regenerate it: python -m tribo.scene_keys python/tribo/scene.schema.json"
    tables = shipped["properties"]
    assert tables["obstacle"]["properties"]["approach"]["description"].startswith("δ: how far")
    assert "Unit: length" in tables["obstacle"]["properties"]["approach"]["description"]


def _scenes() -> list[tuple[str, dict[str, Any]]]:
    out = [(p.name, tomllib.loads(p.read_text(encoding="utf-8"))) for p in SCENES]
    pages = [ROOT / "README.md", *sorted((ROOT / "docs" / "guide").glob("*.md")), ROOT / "docs" / "getting-started.md"]
    for page in pages:
        for k, block in enumerate(re.findall(r"```toml\n(.*?)```", page.read_text(encoding="utf-8"), re.S)):
            data = tomllib.loads(block)
            if "body" in data or "bodies" in data:  # whole scenes, not fragments
                out.append((f"{page.name}[{k}]", data))
    return out


@pytest.mark.parametrize(("name", "data"), _scenes(), ids=[n for n, _ in _scenes()])
def test_every_shipped_and_documented_scene_meets_the_schema(name: str, data: dict[str, Any]) -> None:
    parse_scene(data)  # the reader takes it
    errors = [e.message for e in validator().iter_errors(data)]
    assert not errors, errors


@pytest.mark.parametrize(
    ("edit", "where"),
    [
        (lambda d: d["obstacle"].update(radus=1.0), "radus"),
        (lambda d: d["material"].update(young="stiff"), "young"),
        (lambda d: d["discretization"].update(space="P2"), "space"),
        (lambda d: d["material"].pop("poisson"), "poisson"),
        (lambda d: d.update(solver={"qp_max_iter": -1}), "qp_max_iter"),
        (lambda d: d.update(supports=[{"kind": "roller"}]), "edge_set"),
    ],
)
def test_the_schema_flags_what_the_reader_refuses(edit: Any, where: str) -> None:
    """Unknown keys, wrong types, unknown choices and missing required keys: the schema flags them as the
    reader refuses them."""
    data = tomllib.loads((SCENES[0].parent / "demo.toml").read_text(encoding="utf-8"))
    edit(data)
    assert list(validator().iter_errors(data)), where
    with pytest.raises(Exception, match=where):
        parse_scene(data)
