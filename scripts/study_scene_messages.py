"""Study 16 — scene-file error messages: tribo's hand-written checkers against pydantic models.

Issue 38 asked whether pydantic models of the scene schema (which would also publish a JSON Schema) keep the
messages as good as today's, where every message names the key and lists the valid choices. This study
builds pydantic models from the same checkers (``tribo.scene_schema.SCHEMA``: each checker mapped to the
closest pydantic type, strict where tribo is strict, ``extra="forbid"``), feeds both readers the mistakes a
user makes (each an edit of the demo scene), and scores each message on three things a user needs: the key
named as a scene path (``obstacle.radius``), the valid choices or known keys listed where the mistake is a
name, and the bad value shown. It also counts how many errors pydantic reports for one mistake (a union type
reports one per member).

    python scripts/study_scene_messages.py          # docs/scene_messages.{md,csv}
    python scripts/study_scene_messages.py --smoke --out /tmp/x
"""

from __future__ import annotations

import copy
import csv
import math
import re
import sys
import tomllib
from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any, Literal, Union

from pydantic import BaseModel, ConfigDict, Field, StrictBool, StrictFloat, StrictInt, StrictStr, ValidationError
from pydantic import create_model

sys.path.insert(0, str(Path(__file__).resolve().parent))
import studylib as sl  # noqa: E402

from tribo.scene import parse_scene, scene_path  # noqa: E402
from tribo.scene_schema import MAX_HISTORY_STEPS, SCHEMA, SceneError  # noqa: E402

Num = Union[StrictInt, Annotated[StrictFloat, Field(allow_inf_nan=False)]]
Pair = tuple[Num, Num]
Path_ = Union[Num, Annotated[list[Num], Field(min_length=2)]]
Steps = Annotated[StrictInt, Field(ge=1, le=MAX_HISTORY_STEPS)]
# The pydantic type of each checker of tribo.scene_schema, by its name (the factories' checkers by their schema).
TYPES: dict[str, Any] = {
    "_number": Num,
    "_integer": StrictInt,
    "_boolean": StrictBool,
    "_string": StrictStr,
    "_pair": Pair,
    "_range": Pair,
    "_center": Union[Num, Pair],
    "_numbers": list[Num],
    "_path": Path_,
    "_counts": Union[Steps, Annotated[list[Steps], Field(min_length=1)]],
    "_every": Annotated[StrictInt, Field(ge=1)],
    "_steps": list[Annotated[StrictInt, Field(ge=0)]],
    "_names": Union[StrictStr, Annotated[list[StrictStr], Field(min_length=1)]],
    "_grading": Union[Literal["auto", "none"], Pair],
    "_pairs": dict[str, Pair],
    "_pressures": dict[str, Num],
    "_points": Annotated[list[Pair], Field(min_length=2)],
    "_paths": dict[str, Path_],
}
STRICT = ConfigDict(extra="forbid")


def _type(check: Callable[..., Any]) -> Any:
    if check.__name__ == "_regions":
        region = create_model("Region", __config__=STRICT, young=(Num, ...), poisson=(Num, ...),
                              group=(StrictStr | None, None), box=(Annotated[list[Num], Field(min_length=4, max_length=4)] | None, None))
        return list[region]
    if check.__name__ == "_contact_pairs":
        keys = {"edge_set": SCHEMA["contact"]["edge_set"], **{k: c for k, c in SCHEMA["obstacle"].items() if k != "rotation"}}
        return list[_model("Pair", keys, ("edge_set",))]
    if check.__name__ == "_rotation":
        return create_model("Rotation", __config__=STRICT, center=(Pair, ...), angle=(Num, ...))
    if check.__name__ == "_plate":
        return create_model("Plate", __config__=STRICT, center=(Pair, ...), radius=(Num, ...), half_widths=(Pair, ...))
    if check.__name__ == "_disc":
        return create_model("Disc", __config__=STRICT, center=(Pair, ...), radius=(Num, ...), angles=(Pair | None, None))
    if check.__name__ == "_ring":
        return create_model("Ring", __config__=STRICT, center=(Pair, ...), radii=(Pair, ...), angles=(Pair, ...))
    schema = getattr(check, "json_schema", None)
    if schema is not None and "enum" in schema:
        return Literal[tuple(schema["enum"])]
    if schema is not None:
        return Annotated[StrictInt, Field(ge=schema["minimum"], le=schema["maximum"])]
    if check.__name__ == "_shape":
        return _model("Gap", {k: c for k, c in SCHEMA["obstacle"].items() if k not in ("approach", "shift", "rotation")})
    return TYPES[check.__name__]


def _model(name: str, keys: dict[str, Callable[..., Any]], required: tuple[str, ...] = ()) -> type[BaseModel]:
    fields: dict[str, Any] = {k: (_type(c), ... if k in required else None) for k, c in keys.items()}
    return create_model(name, __config__=STRICT, **fields)


def scene_model() -> type[BaseModel]:
    """The pydantic model of a one-body scene file (the tables of ``SCHEMA``)."""
    support = create_model("Support", __config__=STRICT, kind=(Literal["clamp", "roller", "displacement", "rotation"], ...),
                           center=(Pair | None, None), angle=(Num | None, None),
                           edge_set=(StrictStr, ...), x=(Num | None, None), y=(Num | None, None))
    tables: dict[str, Any] = {}
    for table, keys in SCHEMA.items():
        model = _model(table.title(), keys, ("young", "poisson") if table == "material" else ())
        tables[table] = (Union[model, list[support]] if table == "supports" else model) | None, None
    return create_model("Scene", __config__=STRICT, title=(StrictStr | None, None),
                        description=(StrictStr | None, None), **tables)


def _set(table: str, key: str, value: Any) -> Callable[[dict[str, Any]], None]:
    return lambda d: d.setdefault(table, {}).__setitem__(key, value)


# The mistakes: (name, the key a message should name, edit of the demo scene, whether it is a name mistake,
# whose message should list the valid choices or known keys).
CASES: list[tuple[str, str, Callable[[dict[str, Any]], None], bool]] = [
    ("misspelled key", "obstacle.radus", _set("obstacle", "radus", 1.0), True),
    ("unknown table", "obstacles", lambda d: d.__setitem__("obstacles", {"radius": 1.0}), True),
    ("string for a number", "material.young", _set("material", "young", "200"), False),
    ("true for a number", "obstacle.approach", _set("obstacle", "approach", True), False),
    ("nan", "material.poisson", _set("material", "poisson", math.nan), False),
    ("integer beyond a float", "material.young", _set("material", "young", 10**400), False),
    ("unknown multiplier space", "discretization.space", _set("discretization", "space", "P2"), True),
    ("unknown obstacle shape", "obstacle.shape", _set("obstacle", "shape", "cone"), True),
    ("negative count", "solver.qp_max_iter", _set("solver", "qp_max_iter", -1), False),
    ("fraction for a count", "solver.fp_max_iter", _set("solver", "fp_max_iter", 1.5), False),
    ("interval of one number", "body.x", _set("body", "x", [0.0]), False),
    ("string in a pair", "loads.body_force", _set("loads", "body_force", [0.0, "a"]), False),
    ("missing required key", "material.poisson", lambda d: d["material"].pop("poisson"), False),
    ("number for a table", "friction", lambda d: d.__setitem__("friction", 0.3), False),
    ("zero steps", "history.steps", _set("history", "steps", 0), False),
    ("unknown stop", "adapt.stop_on", _set("adapt", "stop_on", "sharpest"), True),
    ("number for an edge set name", "supports.clamped", _set("supports", "clamped", [1]), False),
    ("unknown grading", "discretization.grading", _set("discretization", "grading", "some"), True),
    ("string for a boolean", "estimate.error_bars", _set("estimate", "error_bars", "yes"), False),
    ("misspelled solver setting", "solver.qp_tols", _set("solver", "qp_tols", 1e-10), True),
]
CHOICES = {"obstacle.radus": "radius", "obstacles": "obstacle", "discretization.space": "P1",
           "obstacle.shape": "circle", "adapt.stop_on": "hierarchical", "discretization.grading": "auto",
           "solver.qp_tols": "qp_tol"}
VALUES = {"string for a number": "200", "negative count": "-1", "fraction for a count": "1.5",
          "unknown multiplier space": "P2", "unknown obstacle shape": "cone", "unknown stop": "sharpest",
          "zero steps": "0", "unknown grading": "some", "string for a boolean": "yes"}


def run(smoke: bool, out: Path) -> list[dict[str, Any]]:
    out.mkdir(parents=True, exist_ok=True)
    base = tomllib.loads(scene_path("demo").read_text(encoding="utf-8"))
    model = scene_model()
    rows = []
    for name, key, edit, is_name in CASES[:6] if smoke else CASES:
        data = copy.deepcopy(base)
        edit(data)
        try:
            parse_scene(data)
            today = "(accepted)"
        except SceneError as e:
            today = str(e)
        try:
            model.model_validate(data)
            theirs, n = "(accepted)", 0
        except ValidationError as e:
            errors = e.errors()
            first = errors[0]
            theirs = f"{'.'.join(str(p) for p in first['loc'])}: {first['msg']} [input_value={first['input']!r}]"
            n = len(errors)
        score = {}
        for who, text, shown in (("tribo", today, today), ("pydantic", theirs, theirs.split(" [input_value=")[0])):
            score[f"{who}_names_key"] = key in text
            # Searched with the key and the value taken out: a choice inside the misspelled key ("obstacle" in
            # "obstacles") is no choice listed, nor is "0" inside a range's bound.
            rest = shown.replace(key.split(".")[-1], " ")
            score[f"{who}_lists_choices"] = CHOICES[key] in rest if is_name else None
            score[f"{who}_shows_value"] = (re.search(rf"(?<![\w.]){re.escape(VALUES[name])}(?![\w.])", text) is not None
                                           if name in VALUES else None)
        rows.append({"mistake": name, "key": key, "tribo": today, "pydantic": theirs, "pydantic_errors": n, **score})
        print(f"{name}: tribo: {today}\n    pydantic ({n}): {theirs}")
    with (out / "scene_messages.csv").open("w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    (out / "scene_messages.md").write_text(_page(rows), encoding="utf-8")
    return rows


def _page(rows: list[dict[str, Any]]) -> str:
    def count(col: str) -> str:
        asked = [r[col] for r in rows if r[col] is not None]
        return f"{sum(asked)} of {len(asked)}"

    def mark(v: bool | None) -> str:
        return "–" if v is None else ("yes" if v else "**no**")

    table = sl.markdown_table(
        ["mistake", "tribo's message", "pydantic's first error", "errors", "key (tribo / pydantic)",
         "choices", "value"],
        [[r["mistake"], f"`{r['tribo']}`", f"`{r['pydantic']}`", r["pydantic_errors"],
          f"{mark(r['tribo_names_key'])} / {mark(r['pydantic_names_key'])}",
          f"{mark(r['tribo_lists_choices'])} / {mark(r['pydantic_lists_choices'])}",
          f"{mark(r['tribo_shows_value'])} / {mark(r['pydantic_shows_value'])}"] for r in rows])
    many = [r["pydantic_errors"] for r in rows if r["pydantic_errors"] > 1]
    return "\n".join([
        "# Study 16: scene-file messages, tribo's checkers against pydantic models",
        "",
        "Regenerate with `python scripts/study_scene_messages.py`; every message is in `scene_messages.csv`. "
        "Each mistake is an edit of the demo scene; pydantic's models are built from the same checkers "
        "(strict types, `extra=\"forbid\"`), and its message is its first error as a user would read it "
        "(the location joined with dots, the message, the input value).",
        "",
        f"**Names the key**: tribo {count('tribo_names_key')}, pydantic {count('pydantic_names_key')}. "
        f"**Lists the valid choices or known keys** (where the mistake is a name): tribo "
        f"{count('tribo_lists_choices')}, pydantic {count('pydantic_lists_choices')}. **Shows the bad value** "
        f"(where it is a short one): tribo {count('tribo_shows_value')}, pydantic {count('pydantic_shows_value')}. "
        f"pydantic reports more than one error for {len(many)} of the {len(rows)} mistakes (up to {max(many, default=1)}: "
        "one per member of a union type).",
        "",
        table,
        "",
        "Conclusion: tribo keeps its hand-written checkers, whose messages do what these columns ask; the JSON "
        "Schema that pydantic would have published is made from the same checkers instead "
        "(`tribo.scene_keys`, shipped as `tribo/scene.schema.json`).",
        "",
    ])


def main(argv: list[str] | None = None) -> Any:
    return sl.cli(run, __doc__, argv)


if __name__ == "__main__":
    main()
