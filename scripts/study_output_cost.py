"""Study 19 — what `tribo run` spends on writing its files, against its solve.

Issue 38 asked that `tribo run` of an adaptive scene spend at most 10 % of its time on output, and that the files
of the demo and of a 100-step history be counted and sized. Each case runs `tribo run SCENE --out DIR` in a
process of its own, with the data files only (the default: JSON, CSV, VTU/PVD), with `--plots` (the PNG plots
and charts too), and for the adaptive cases with `--all-files --plots`: everything, every level solved again and
written as well, which is what `tribo run` wrote before issue 38 (the 101-step history writes every step by
default: up to 200 steps, `--all-files` adds nothing there). The run logs how long its solve took (scene building included) and how long it then spent
writing; the process's wall time includes Python's start, `import tribo` and reading the scene. `share` is the
writing over the process's wall time (what a user waits for), `share of solve + write` the writing over both.
The cases: the demo scene (`python/tribo/scenes/demo.toml`: adaptive Hertz with Coulomb friction to `tol` = 1 %),
the fretting scene (`fretting.toml`) as a 101-step history (8 + 16 + 16 steps made 20 + 40 + 40), and the fretting
scene with `[adapt]` `tol` = 2 % on a 21-step history (4 + 8 + 8 steps: the whole history is solved on every level).
The VTU files are deflated with zlib's run-length strategy (meshio's writer uses zlib's default level 6 and has no
setting for it; `tribo.io` compresses so in its own writing threads only): on the demo's body file 3.8 times as fast
as level 6 for a file 7 % larger.

    python scripts/study_output_cost.py                 # docs/output_cost.{md,csv}
    python scripts/study_output_cost.py --smoke --out /tmp/x   # the demo scene with tol = 20 %, data files only
"""

from __future__ import annotations

import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
import studylib as sl  # noqa: E402

SCENES = Path(__file__).resolve().parents[1] / "python" / "tribo" / "scenes"
REPEATS = 3  # runs of each case; the one of median wall time is reported
HEADERS = ["case", "files_asked", "unknowns", "solve_seconds", "write_seconds", "run_seconds", "share",
           "share_of_solve_and_write", "files", "megabytes"]


def edited(name: str, replace: dict[str, str], append: str = "") -> str:
    """The scene file ``name`` with whole lines replaced (each must be there) and a table appended."""
    text = (SCENES / name).read_text(encoding="utf-8")
    for old, new in replace.items():
        if not re.search(f"^{re.escape(old)}$", text, flags=re.M):
            raise RuntimeError(f"{name} has no line {old!r}: update this study")
        text = re.sub(f"^{re.escape(old)}$", new, text, flags=re.M)
    return text + append


def cases(smoke: bool) -> dict[str, str]:
    """The scenes run, by name: their TOML text."""
    if smoke:
        return {"demo, tol 20 %": edited("demo.toml", {"tol = 0.01           # relative estimated error of the "
                                                        "contact tractions at which to stop": "tol = 0.2"})}
    history = {"steps = [8, 16, 16]": "steps = [20, 40, 40]", "plot_steps = [8, 24, 40]": "plot_steps = [20, 60, 100]"}
    adaptive = {"steps = [8, 16, 16]": "steps = [4, 8, 8]", "plot_steps = [8, 24, 40]": "plot_steps = [4, 12, 20]"}
    return {"demo (adaptive, tol 1 %)": (SCENES / "demo.toml").read_text(encoding="utf-8"),
            "history, 101 steps": edited("fretting.toml", history),
            "adaptive history, 21 steps, tol 2 %": edited("fretting.toml", adaptive, "\n[adapt]\ntol = 0.02\n")}


# What a run is asked to write: its name in the table and the flags of `tribo run`.
ASKED = {"data": ["--no-plots"], "data + plots": ["--plots"], "everything": ["--plots", "--all-files"]}


def run_case(name: str, text: str, asked: str, work: Path) -> dict[str, Any]:
    """One `tribo run` in its own process: the times it logs, its wall time, the files it wrote."""
    scene, out = work / "scene.toml", work / "out"
    scene.write_text(text, encoding="utf-8")
    command = [sys.executable, "-m", "tribo.cli", "run", str(scene), "--out", str(out), *ASKED[asked]]
    clock = time.perf_counter()
    done = subprocess.run(command, check=True, capture_output=True, text=True)
    wall = time.perf_counter() - clock
    solve = re.search(r"solve ended: \w+ after ([0-9.]+) s", done.stderr)
    write = re.search(r"wrote (\d+) files in ([0-9.]+) s", done.stderr)
    unknowns = re.search(r"(\d+) free dofs", done.stderr)
    if not (solve and write and unknowns):
        raise RuntimeError(f"tribo run logged something this study does not read:\n{done.stderr}")
    files = [f for f in out.rglob("*") if f.is_file()]
    if len(files) != int(write[1]):
        raise RuntimeError(f"{name}: the run says it wrote {write[1]} files, {out} holds {len(files)}")
    s, w = float(solve[1]), float(write[2])
    # The unknowns of the last level: summary.json's, not the first mesh's that the log states first.
    last = re.findall(r"adaptive level: (\d+) unknowns", done.stderr)
    return dict(case=name, files_asked=asked, unknowns=int(last[-1]) if last else int(unknowns[1]),
                solve_seconds=s, write_seconds=w, run_seconds=wall, share=w / wall,
                share_of_solve_and_write=w / (s + w),
                files=len(files), megabytes=sum(f.stat().st_size for f in files) / 1e6)


def median_run(name: str, text: str, asked: str, repeats: int) -> dict[str, Any]:
    """`run_case` `repeats` times: the run of the median wall time (the machine's noise is tens of percent)."""
    runs = []
    for _ in range(repeats):
        with tempfile.TemporaryDirectory() as work:
            runs.append(run_case(name, text, asked, Path(work)))
    return sorted(runs, key=lambda r: r["run_seconds"])[len(runs) // 2]


def bar(rows: list[dict[str, Any]]) -> str:
    """What the rows say of issue 38's bar: an adaptive scene's `tribo run` spends at most 10 % of its time on
    its files (the default ones)."""
    adaptive = [r for r in rows if "adaptive" in r["case"] and r["files_asked"] == "data"]
    said = "; ".join(f"{r['case']}: {100 * r['share']:.1f} % of the run ({100 * r['share_of_solve_and_write']:.1f} % "
                     "of solve + write)" for r in adaptive)
    met = all(r["share"] <= 0.10 for r in adaptive)
    return (f"Issue 38's bar, at most 10 % of an adaptive run spent on its files (the default ones), is "
            f"{'met' if met else 'NOT met'}: {said}.")


def run(smoke: bool, out: Path) -> list[dict[str, Any]]:
    rows = []
    for name, text in cases(smoke).items():
        asked = ["data"] if smoke else ["data", "data + plots"] + (["everything"] if "adaptive" in name else [])
        for a in asked:
            rows.append(median_run(name, text, a, 1 if smoke else REPEATS))
            print(rows[-1], file=sys.stderr)
    out.mkdir(parents=True, exist_ok=True)
    sl.write_csv(out / "output_cost.csv", HEADERS, [[r[h] for h in HEADERS] for r in rows])
    table = sl.markdown_table(
        ["case", "files asked", "unknowns (last)", "solve (s)", "writing (s)", "run (s)", "share", "share of solve + write",
         "files", "MB"],
        [[r[h] for h in HEADERS] for r in rows])
    sl.write_page(out / "output_cost.md", "Study 19: what `tribo run` spends on its files", __doc__,
                  f"Regenerate with `python scripts/study_output_cost.py` ({REPEATS} runs of each, the one of median "
                  "wall time shown; the machine of the studies: two cores, its timings vary by tens of percent). "
                  + bar(rows), table)
    return rows


def main(argv: list[str] | None = None) -> Any:
    return sl.cli(run, __doc__, argv)


if __name__ == "__main__":
    main()
