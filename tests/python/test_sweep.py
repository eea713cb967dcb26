"""Parameter sweeps on Dask (``tribo.sweep``, ``tribo sweep``): the cases, their hashes, the cache, a
failing case, a worker killed mid-case, and the same numbers as single ``tribo run``s. The cluster tests
start a real ``LocalCluster`` of 2 worker processes."""

from __future__ import annotations

import json
import os
import signal
import threading
import time
import tomllib
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

pd = pytest.importorskip("pandas")
distributed = pytest.importorskip("distributed")

from tribo.cli import main  # noqa: E402
from tribo.scene import SceneError, scene_path  # noqa: E402
from tribo.sweep import MAX_CASES, SweepError, case_key, cases, parse_axis, set_key, sweep  # noqa: E402

HERTZ_TEXT = scene_path("hertz").read_text(encoding="utf-8")


def hertz_data() -> dict[str, Any]:
    return tomllib.loads(HERTZ_TEXT)


# ----- axes and cases (no cluster) -----
def test_axes_read_toml_values() -> None:
    assert parse_axis("friction.mu=0,0.2,0.4") == ("friction.mu", [0, 0.2, 0.4])
    assert parse_axis("discretization.grading = [-0.3, 0.3], [-0.5,0.5]") == (
        "discretization.grading", [[-0.3, 0.3], [-0.5, 0.5]])
    assert parse_axis('discretization.space=P0,"P1"') == ("discretization.space", ["P0", "P1"])
    assert parse_axis("solver.qp_working_set=true,false")[1] == [True, False]
    for bad in ("friction.mu", "=1,2", "friction.mu=", "friction.mu=1,,2"):
        with pytest.raises(SweepError):
            parse_axis(bad)


def test_set_key_makes_tables_and_indexes_lists() -> None:
    data: dict[str, Any] = {"bodies": [{"name": "a"}, {"name": "b", "material": {"young": 1.0}}]}
    set_key(data, "friction.mu", 0.3)
    set_key(data, "bodies[1].material.young", 5.0)
    set_key(data, "bodies.0.material.poisson", 0.2)
    assert data["friction"] == {"mu": 0.3}
    assert data["bodies"][1]["material"]["young"] == 5.0 and data["bodies"][0]["material"] == {"poisson": 0.2}
    with pytest.raises(SceneError, match="entry 2 does not exist"):
        set_key(data, "bodies[2].material.young", 1.0)
    with pytest.raises(SceneError, match="not a table"):
        set_key(data, "friction.mu.x", 1.0)
    with pytest.raises(SweepError, match="names a table"):
        set_key(data, "friction", 1.0)


def test_cases_are_the_product_with_zipped_axes_last() -> None:
    got = cases(hertz_data(), {"friction.mu": [0.1, 0.2]},
                {"obstacle.shift": [0.0, 0.004, 0.008], "obstacle.approach": [0.01, 0.011, 0.012]})
    assert [c.values for c in got] == [
        {"friction.mu": mu, "obstacle.shift": s, "obstacle.approach": a}
        for mu in (0.1, 0.2) for s, a in ((0.0, 0.01), (0.004, 0.011), (0.008, 0.012))
    ]
    assert [c.index for c in got] == list(range(6)) and len({c.key for c in got}) == 6
    assert got[4].data["friction"]["mu"] == 0.2 and got[4].data["obstacle"]["shift"] == 0.004
    with pytest.raises(SweepError, match="equal lengths"):
        cases(hertz_data(), {}, {"obstacle.shift": [0.0, 0.1], "obstacle.approach": [0.01]})
    with pytest.raises(SweepError, match="no values"):
        cases(hertz_data(), {"friction.mu": []})


def test_equal_values_are_one_case() -> None:
    """Defect D33: ``friction.mu=0.1,0.1,1e-1,0.10`` is one scene (one hash), and ran four times at once into
    one folder; now it is one case, and a grid keeps one case per distinct scene, first seen first."""
    assert len(cases(hertz_data(), {"friction.mu": parse_axis("friction.mu=0.1,0.1,1e-1,0.10")[1]})) == 1
    got = cases(hertz_data(), {"friction.mu": [0.1, 0.2, 0.1], "obstacle.shift": [0.0, 0.0]})
    assert [c.values for c in got] == [{"friction.mu": 0.1, "obstacle.shift": 0.0},
                                       {"friction.mu": 0.2, "obstacle.shift": 0.0}]
    assert [c.index for c in got] == [0, 1] and len({c.key for c in got}) == 2


def test_files_are_replaced_whole(tmp_path: Path) -> None:
    """A reader sees the old file or the new one, never a part: the text goes to a temporary file that is
    renamed over the target, and nothing else is left in the folder."""
    from tribo.io import write_text_atomic

    path = tmp_path / "summary.json"
    write_text_atomic(path, "old\n")
    write_text_atomic(path, "new\n")
    assert path.read_text(encoding="utf-8") == "new\n" and [p.name for p in tmp_path.iterdir()] == ["summary.json"]


def test_a_typo_is_one_scene_error_naming_the_key_before_anything_runs() -> None:
    with pytest.raises(SceneError, match="friction.muu") as e:
        cases(hertz_data(), {"friction.muu": [0.1, 0.2]})
    assert "friction.muu" in " ".join(e.value.__notes__)
    with pytest.raises(SceneError, match="friction.mu' must be a number"):
        cases(hertz_data(), {"friction.mu": [0.1, "x"]})


def test_too_many_cases_are_refused_before_they_are_enumerated() -> None:
    big = {f"friction.mu{k}": list(range(10)) for k in range(6)}
    with pytest.raises(SweepError, match=f"more than the limit of {MAX_CASES}"):
        cases(hertz_data(), big)


def test_the_case_hash_is_the_checked_scene_and_the_mesh_files(tmp_path: Path) -> None:
    base = hertz_data()
    titled = {**hertz_data(), "title": "another title"}
    spelled = hertz_data()
    spelled["obstacle"]["radius"] = 1  # an integer spelling of 1.0
    assert case_key(base, tmp_path) == case_key(titled, tmp_path) == case_key(spelled, tmp_path)
    moved = hertz_data()
    moved["obstacle"]["approach"] = 0.011
    assert case_key(moved, tmp_path) != case_key(base, tmp_path)
    # A scene that reads a mesh file: the file's bytes are part of the name.
    mesh = tmp_path / "block.msh"
    mesh.write_bytes(b"first")
    data = {k: v for k, v in hertz_data().items() if k not in ("body", "discretization")}
    data["body"] = {"mesh": "block.msh"}
    first = case_key(data, tmp_path)
    mesh.write_bytes(b"second")
    assert case_key(data, tmp_path) != first


# ----- on a real LocalCluster -----
@pytest.fixture(scope="module")
def client() -> Iterator[Any]:
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=":0", env={"RAYON_NUM_THREADS": "1"})
    with distributed.Client(cluster) as c:
        yield c
    cluster.close()


def scene_file(tmp_path: Path) -> Path:
    """The Hertz scene with a [friction] table, as a file: the sweep's axes exist in it, so single runs of
    the cases are the same file with one line changed."""
    path = tmp_path / "hertz_mu.toml"
    path.write_text(HERTZ_TEXT + "\n[friction]\nmu = 0.3\n", encoding="utf-8")
    return path


AXES = {"friction.mu": [0.2, 0.4, 0.6], "obstacle.shift": [0.0, 0.004]}


def test_a_sweep_runs_every_case_once_and_reruns_none(tmp_path: Path, client: Any,
                                                      caplog: pytest.LogCaptureFixture) -> None:
    scene, out = scene_file(tmp_path), tmp_path / "out"
    seen: list[tuple[int, int]] = []
    df = sweep(scene, AXES, out=out, client=client, progress=lambda done, total: seen.append((done, total)))
    assert len(df) == 6 and list(df.columns[:2]) == ["friction.mu", "obstacle.shift"]
    assert (df["status"] == "converged").all() and (df["attempts"] == 1).all()
    assert (df["formulation"] == "displacement").all()  # ν = 0.3: auto keeps P1 displacements
    assert seen[-1] == (6, 6) and len(seen) == 6
    assert list(zip(df["friction.mu"], df["obstacle.shift"])) == [(m, s) for m in AXES["friction.mu"]
                                                                  for s in AXES["obstacle.shift"]]
    # What a user reads back: parquet and CSV hold the same table.
    assert pd.read_parquet(out / "results.parquet").equals(df)
    csv = pd.read_csv(out / "results.csv", keep_default_na=False)
    assert list(csv["case"]) == list(df["case"]) and (csv["normal_force"] == df["normal_force"]).all()
    for key in df["case"]:
        assert {p.name for p in (out / "cases" / key).iterdir()} == {"summary.json", "row.json", "attempts"}
    # Friction bites where the obstacle moves: a tangential force, and the grid is an xarray away.
    grid = df.set_index(list(AXES)).to_xarray()["tangential_force"]
    assert grid.sel({"obstacle.shift": 0.0}).pipe(abs).max() < 1e-12 < abs(float(grid.sel(
        {"obstacle.shift": 0.004, "friction.mu": 0.2})))
    # The rerun finds all six cached: nothing is submitted (no client needed), and the table is the same.
    caplog.set_level("INFO", logger="tribo")
    again = sweep(scene, AXES, out=out, client="tcp://127.0.0.1:1")
    assert "6 cached, 0 to run" in caplog.text and again.equals(df)
    # One more axis value runs one more column of cases only.
    more = sweep(scene, {**AXES, "friction.mu": [0.2, 0.4, 0.6, 0.8]}, out=out, client=client)
    assert len(more) == 8 and more.iloc[:6].equals(df) and (more["attempts"] == 1).all()


def test_the_numbers_are_those_of_single_runs(tmp_path: Path, client: Any) -> None:
    scene, out = scene_file(tmp_path), tmp_path / "out"
    df = sweep(scene, {"friction.mu": [0.2, 0.6]}, zipped={}, out=out, client=client)
    for mu, row in zip((0.2, 0.6), df.itertuples()):
        single = tmp_path / f"single_{mu}.toml"
        single.write_text(scene.read_text().replace("mu = 0.3", f"mu = {mu}"), encoding="utf-8")
        assert main(["-q", "run", str(single), "--out", str(tmp_path / f"run_{mu}"), "--no-plots"]) == 0
        s = json.loads((tmp_path / f"run_{mu}" / "summary.json").read_text())
        case = json.loads((out / "cases" / row.case / "summary.json").read_text())
        for name in ("normal_force", "tangential_force"):
            assert getattr(row, name) == pytest.approx(s[name], rel=1e-12, abs=1e-15)
            assert case[name] == pytest.approx(s[name], rel=1e-12, abs=1e-15)
        assert row.iterations == s["iterations"] and row.unknowns == s["n_free"]
        assert row.kkt_max == pytest.approx(s["kkt_max"], rel=1e-3, abs=1e-13)


def test_the_table_says_which_adaptive_answers_were_handed_back(tmp_path: Path, client: Any) -> None:
    """An adaptive scene stopped on the enriched estimate hands back the enriched answer (as ``tribo run`` says in
    summary.json); stopped on the level's own estimate, it does not; a case without ``[adapt]`` has False."""
    from test_cli import ADAPT_SCENE

    scene = tmp_path / "adapt.toml"
    scene.write_text(ADAPT_SCENE + 'stop_on = "enriched"\n', encoding="utf-8")
    df = sweep(scene, {"adapt.stop_on": ["enriched", "hierarchical"]}, out=tmp_path / "out", client=client)
    rows = df.set_index("adapt.stop_on")
    assert (rows["adapt_stop"] == "tolerance").all() and (rows["status"] == "converged").all()
    assert rows.loc["enriched", "adapt_handed_back"] and not rows.loc["hierarchical", "adapt_handed_back"]
    for row in df.itertuples():
        summary = json.loads((tmp_path / "out" / "cases" / row.case / "summary.json").read_text())
        assert summary["adapt_handed_back"] is bool(row.adapt_handed_back)
    plain = sweep(scene_file(tmp_path), {"friction.mu": [0.2]}, out=tmp_path / "plain", client=client)
    assert plain["adapt_handed_back"].tolist() == [False] and plain["adapt_stop"].tolist() == [""]


def test_a_failing_case_is_a_row_and_not_the_end(tmp_path: Path, client: Any) -> None:
    df = sweep(scene_file(tmp_path), {"material.poisson": [0.3, 0.5], "solver.fp_max_iter": [1, 50]},
               out=tmp_path / "out", client=client)
    assert len(df) == 4
    bad = df[df["material.poisson"] == 0.5]
    assert (bad["status"] == "error").all()
    assert bad["failure"].str.contains("SettingsError: material: Poisson's ratio").all()
    good = df[df["material.poisson"] == 0.3].set_index("solver.fp_max_iter")["status"]
    assert good[1] == "max_iterations" and good[50] == "converged"
    assert main(["-q", "sweep", str(scene_file(tmp_path)), "--set", "material.poisson=0.3,0.5",
                 "--set", "solver.fp_max_iter=1,50", "--out", str(tmp_path / "out"), "--workers", "1"]) == 3


def test_a_worker_killed_mid_case_loses_and_duplicates_nothing(tmp_path: Path, client: Any) -> None:
    # Cases of about a second each (37k unknowns), so that the kill falls inside one.
    axes = {"friction.mu": [0.2, 0.3, 0.4, 0.5], "discretization.h_min": [0.001], "discretization.growth": [0.1],
            "obstacle.shift": [0.004]}
    out = tmp_path / "out"
    result: dict[str, Any] = {}
    runner = threading.Thread(target=lambda: result.update(df=sweep(scene_file(tmp_path), axes, out=out,
                                                                    client=client, progress=False)))
    runner.start()
    killed = None
    deadline = time.monotonic() + 120.0
    while killed is None and time.monotonic() < deadline and runner.is_alive():
        for attempts in out.glob("cases/*/attempts"):
            lines = attempts.read_text().splitlines()
            if lines:
                killed = int(lines[0].split()[1])
                os.kill(killed, signal.SIGKILL)
                break
        time.sleep(0.002)
    runner.join(timeout=300.0)
    assert killed is not None and not runner.is_alive()
    df = result["df"]
    assert len(df) == 4 and df["case"].is_unique and (df["status"] == "converged").all()
    assert sorted(df["friction.mu"]) == axes["friction.mu"]
    # The case the dead worker held was started again elsewhere; the others once.
    assert sorted(df["attempts"]) == [1, 1, 1, 2]
    client.wait_for_workers(2, timeout=60)  # the nanny restarts the killed worker


def test_cli_sweep_writes_the_table_and_a_map(tmp_path: Path, client: Any, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "out"
    code = main(["-q", "sweep", str(scene_file(tmp_path)), "--set", "friction.mu=0.2,0.4", "--set",
                 "obstacle.shift=0,0.004", "--out", str(out), "--scheduler", client.scheduler.address,
                 "--plot", "tangential_force"])
    printed = capsys.readouterr().out
    assert code == 0 and "4 cases: 4 converged" in printed and (out / "sweep_tangential_force.png").is_file()
    assert len(pd.read_parquet(out / "results.parquet")) == 4
    # An unknown column to plot is one error line (the cases are cached by then).
    assert main(["-q", "sweep", str(scene_file(tmp_path)), "--set", "friction.mu=0.2,0.4", "--set",
                 "obstacle.shift=0,0.004", "--out", str(out), "--plot", "nonsense"]) == 1
    assert "--plot nonsense: not an output column" in capsys.readouterr().err


def test_cli_sweep_errors_are_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    scene = str(scene_file(tmp_path))
    for args, message in (
        (["--set", "friction.muu=0.1,0.2"], "scene key 'friction.muu' is not known"),
        (["--set", "friction.mu=0.1", "--set", "friction.mu=0.2"], "given twice"),
        ([], "at least one axis"),
        (["--set", "friction.mu"], "an axis is KEY=V1,V2"),
    ):
        assert main(["-q", "sweep", scene, *args, "--out", str(tmp_path / "out")]) == 1
        err = capsys.readouterr().err
        assert err.startswith("tribo: error:") and message in err and err.count("\n") == 1


def test_missing_extra_says_how_to_install(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    import builtins

    real = builtins.__import__

    def no_dask(name: str, *args: Any, **kw: Any) -> Any:
        if name == "distributed":
            raise ImportError("No module named 'distributed'", name="distributed")
        return real(name, *args, **kw)

    monkeypatch.setattr(builtins, "__import__", no_dask)
    with pytest.raises(SweepError, match=r'pip install "tribo\[sweep\]"'):
        sweep(scene_file(tmp_path), {"friction.mu": [0.1]}, out=tmp_path / "out")


def test_ctrl_c_writes_what_is_done_and_the_rerun_resumes(tmp_path: Path, client: Any) -> None:
    scene, out = scene_file(tmp_path), tmp_path / "out"

    def interrupt(done: int, total: int) -> None:
        if done == 2:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        sweep(scene, AXES, out=out, client=client, progress=interrupt)
    partial = pd.read_parquet(out / "results.parquet")
    assert len(partial) == 2 and (partial["status"] == "converged").all()
    full = sweep(scene, AXES, out=out, client=client, progress=False)
    assert len(full) == 6 and full["case"].is_unique
    assert set(partial["case"]) <= set(full["case"]) and (full["attempts"] == 1).all()


def test_the_guide_sweep_example_runs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    import re

    page = (Path(__file__).resolve().parents[2] / "docs" / "guide" / "sweeps.md").read_text(encoding="utf-8")
    (code,) = [b for b in re.findall(r"```python\n(.*?)```", page, flags=re.S) if "tribo.sweep" in b]
    monkeypatch.chdir(tmp_path)
    namespace: dict[str, Any] = {"__name__": "__main__"}
    exec(compile(code, "docs/guide/sweeps.md", "exec"), namespace)  # noqa: S102 - our own page
    df, grid = namespace["df"], namespace["grid"]
    assert len(df) == 4 and (df["status"] == "converged").all() and (tmp_path / "sweep-out" / "results.csv").is_file()
    assert grid["tangential_force"].shape == (2, 2)


def test_a_case_that_kills_every_worker_is_a_row_and_not_cached(tmp_path: Path) -> None:
    """A case that runs its worker out of memory (the nanny kills a worker above 95 % of its limit) is
    retried on a fresh worker, and after `allowed-failures` + 1 deaths it is a row with status
    `killed_worker`, not cached; the other cases complete."""
    import dask

    scene, out = scene_file(tmp_path), tmp_path / "out"
    # 17 cases on two workers go in batches of 2: the big one shares its batch with a small one, which must
    # not be marked with it (the batch is split into single cases once it kills workers). Two workers, not
    # one: in 1 of 4 runs a nanny that had restarted its worker four times in seconds did not start a fifth,
    # and the sweep waited for ever on a cluster with no worker. The no-workers timeout turns such a loss
    # into a failed task (an `internal_error` row that fails this test) rather than a hang.
    zipped = {"friction.mu": [0.05 * k for k in range(1, 18)],
              "discretization.h_min": [0.04] * 4 + [0.0001] + [0.04] * 12, "discretization.growth": [0.02] * 17}
    with dask.config.set({"distributed.scheduler.allowed-failures": 1,
                          "distributed.scheduler.no-workers-timeout": "120s"}):
        with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0",
                                      memory_limit="600MB", env={"RAYON_NUM_THREADS": "1"}) as cluster, \
                distributed.Client(cluster) as c:
            df = sweep(scene, {}, zipped=zipped, out=out, client=c, progress=False)
    big = df.iloc[4]
    small = df.drop(index=4)
    assert (small["status"] == "converged").all() and len(small) == 16
    assert big["status"] == "killed_worker" and "killed every worker" in big["failure"]
    assert big["attempts"] >= 2  # allowed-failures = 1: tried twice alone (and in its batch before)
    assert not (out / "cases" / big["case"] / "row.json").exists()
    assert all((out / "cases" / k / "row.json").is_file() for k in small["case"])
