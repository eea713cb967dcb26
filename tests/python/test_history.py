"""Loading histories from Python: the API, the scene table and what ``tribo run`` writes."""

from __future__ import annotations

import tomllib
import xml.etree.ElementTree as ET
from pathlib import Path

import meshio
import numpy as np
import pytest

import tribo
from tribo.cli import main
from tribo.scene import SceneError, parse_scene, scene_path


@pytest.fixture(scope="module")
def problem() -> tribo.Problem:
    mesh = tribo.Mesh.rectangle((-1.0, 1.0), (-1.0, 0.0), 24, 12)
    return tribo.Problem(mesh, young=1.0, poisson=0.45, clamped="bottom", contact="top",
                         obstacle=tribo.Obstacle.circle(radius=2.0), approach=0.01)


def test_one_step_is_the_static_solve(problem: tribo.Problem) -> None:
    h = problem.solve_history(0.01, [0.002], mu=0.3)
    static = tribo.Problem(problem.mesh, young=1.0, poisson=0.45, clamped="bottom", contact="top",
                           obstacle=tribo.Obstacle.circle(radius=2.0), approach=0.01, shift=0.002).solve(mu=0.3)
    assert h.status == "converged" and len(h) == 1
    np.testing.assert_array_equal(h.solutions[0].lambda_t, static.lambda_t)
    np.testing.assert_array_equal(h.solutions[0].displacement, static.displacement)


def test_arrays_have_one_entry_per_step(problem: tribo.Problem) -> None:
    s = np.linspace(0.0, 0.004, 6)
    h = problem.solve_history(0.01, s, mu=0.3)
    assert h.converged and h.factorizations in (0, 1) and h.ended_at is None and h.failed is None
    for a in (h.normal_force, h.tangential_force, h.stick_count, h.slip_count, h.separation_count, h.step_seconds):
        assert a.shape == (6,)
    assert h.contact_zone.shape == (6, 2) and h.stick_zone.shape == (6, 2)
    # The stick-slip boundaries of all steps in one table: midpoints between a dof that sticks and one that slips.
    steps, bounds = h.stick_slip_steps, h.stick_slip_boundaries
    assert steps.shape == bounds.shape and bounds.size > 0 and (np.diff(steps) >= 0).all()
    stick, slip = tribo.STATE_NAMES.index("stick"), tribo.STATE_NAMES.index("slip")
    for k in range(6):
        st, x = h.solution(k).states, h.solution(k).multiplier_abscissae
        change = ((st[:-1] == stick) & (st[1:] == slip)) | ((st[:-1] == slip) & (st[1:] == stick))
        np.testing.assert_array_equal(bounds[steps == k], 0.5 * (x[:-1] + x[1:])[change])
    np.testing.assert_array_equal(h.shift, s)
    assert (h.stick_count + h.slip_count + h.separation_count == problem.n_multipliers).all()
    # The drag loads tangentially and Q stays within μP.
    assert abs(h.tangential_force[-1]) > 0.0
    assert (np.abs(h.tangential_force) <= 0.3 * h.normal_force * (1 + 1e-9)).all()


def test_progress_can_stop_the_history(problem: tribo.Problem) -> None:
    seen: list[tuple[int, int, str]] = []

    def progress(step: int, steps: int, status: str, seconds: float) -> bool:
        seen.append((step, steps, status))
        return step < 2

    h = problem.solve_history(0.01, np.linspace(0.0, 0.004, 6), mu=0.3, progress=progress)
    assert h.status == "interrupted" and len(h) == 3 and h.ended_at == 2
    assert seen == [(0, 6, "converged"), (1, 6, "converged"), (2, 6, "converged")]


def test_a_raising_callback_keeps_the_steps_done(problem: tribo.Problem) -> None:
    """An exception from the callback ends the history and propagates, carrying the converged steps as a
    History (status 'interrupted'), the same as returning False would have kept."""

    def progress(step: int, steps: int, status: str, seconds: float) -> bool:
        if step == 2:
            raise RuntimeError("enough")
        return True

    shifts = np.linspace(0.0, 0.004, 6)
    with pytest.raises(RuntimeError, match="enough") as info:
        problem.solve_history(0.01, shifts, mu=0.3, progress=progress)
    kept = info.value.history  # type: ignore[attr-defined]
    assert isinstance(kept, tribo.History) and kept.status == "interrupted" and len(kept) == 3
    stopped = problem.solve_history(0.01, shifts, mu=0.3, progress=lambda step, *a: step < 2)
    assert np.array_equal(kept.normal_force, stopped.normal_force)
    assert np.array_equal(kept.solutions[-1].lambda_t, stopped.solutions[-1].lambda_t)


def test_a_history_beyond_the_memory_budget_is_refused(problem: tribo.Problem) -> None:
    """Every step's solution is kept by default, so a million steps are refused before any runs (they
    aborted the process before), with the bytes they would need; keeping fewer (``keep_every``) fits."""
    with pytest.raises(tribo.TriboError, match="a history of 1000000 steps") as info:
        problem.solve_history(0.01, np.zeros(1_000_000), mu=0.3)
    assert info.value.kind == "MemoryBudget" and info.value.details["needed"] > 4 * 2**30  # type: ignore[attr-defined]
    # 40 steps need about 2.5 MB of solutions (about 60 kB each): over a 1 MiB budget unless only every
    # 20th is kept.
    budget = 2**20
    with pytest.raises(tribo.TriboError, match="keeping 40 solutions"):
        problem.solve_history(0.01, np.zeros(40), mu=0.3, memory_budget=budget)
    h = problem.solve_history(0.01, np.zeros(40), mu=0.3, memory_budget=budget, keep_every=20)
    assert h.converged and h.kept.tolist() == [0, 20, 39] and len(h.normal_force) == 40


def test_the_default_budget_respects_the_address_space_limit(problem: tribo.Problem) -> None:
    """Defect D21: the default memory budget is what the process may still allocate, not only what the
    machine has free: under an address-space limit (``ulimit -v``) 1 GiB above what the process holds, it is
    at most that GiB, and a history that needs more is refused by name before any step (it aborted on
    "memory allocation failed" past the limit). In a child process, so the limit stays there."""
    import subprocess
    import sys

    code = """
import resource, numpy as np, tribo
vm = next(int(l.split()[1]) * 1024 for l in open("/proc/self/status") if l.startswith("VmSize:"))
resource.setrlimit(resource.RLIMIT_AS, (vm + 2**30, resource.RLIM_INFINITY))
budget = tribo.solver_defaults()["memory_budget"]
p = tribo.Problem(tribo.Mesh.rectangle((-1.0, 1.0), (-1.0, 0.0), 24, 12), young=200.0, poisson=0.3,
                  clamped="bottom", contact="top", obstacle=tribo.Obstacle.circle(1.0), approach=0.01)
try:
    p.solve_history(0.01, np.zeros(40_000), mu=0.3)
    print(budget, "solved")
except tribo.TriboError as e:
    print(budget, e.kind)
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300, check=True)
    budget, outcome = out.stdout.split()
    available = next(int(line.split()[1]) * 1024 for line in open("/proc/meminfo") if line.startswith("MemAvailable:"))
    assert int(budget) <= 2**30 < available and outcome == "MemoryBudget", out.stdout + out.stderr


def test_keep_every_keeps_what_is_asked(problem: tribo.Problem) -> None:
    """``keep_every=k`` keeps the solutions of steps 0, k, 2k, … and the last converged one, each equal to the
    full history's; the per-step arrays still cover every step and equal the full history's."""
    shifts = np.linspace(0.0, 0.004, 7)
    full = problem.solve_history(0.01, shifts, mu=0.3)
    sparse = problem.solve_history(0.01, shifts, mu=0.3, keep_every=3)
    assert full.kept.tolist() == list(range(7)) and sparse.kept.tolist() == [0, 3, 6]
    assert len(sparse) == 7 and len(sparse.solutions) == 3 and "kept=3" in repr(sparse)
    for name in ("normal_force", "tangential_force", "stick_count", "slip_count", "error_estimate", "contact_zone"):
        np.testing.assert_array_equal(getattr(sparse, name), getattr(full, name), err_msg=name)
    np.testing.assert_array_equal(sparse.traction_error, full.traction_error)
    np.testing.assert_array_equal(sparse.solution(3).displacement, full.solutions[3].displacement)
    np.testing.assert_array_equal(sparse.solution(-1).lambda_t, full.solutions[-1].lambda_t)
    assert sparse.error_estimate[2] == full.solutions[2].report.estimate["total"]
    with pytest.raises(KeyError, match="step 2 is not kept"):
        sparse.solution(2)
    stopped = problem.solve_history(0.01, shifts, mu=0.3, keep_every=3, progress=lambda step, *a: step < 4)
    assert stopped.kept.tolist() == [0, 3, 4] and len(stopped) == 5
    with pytest.raises(tribo.SettingsError, match="keep_every"):
        problem.solve_history(0.01, shifts, mu=0.3, keep_every=0)
    with pytest.raises(tribo.SettingsError, match="keep_every.*adaptive history"):
        problem.solve_history_adaptive(0.01, shifts, mu=0.3, keep_every=2)


def test_bad_histories_are_errors(problem: tribo.Problem) -> None:
    with pytest.raises(tribo.SettingsError, match="load step 1"):
        problem.solve_history(0.01, [0.0, float("nan")], mu=0.3)
    with pytest.raises(tribo.SettingsError, match="shift has 2 values, but the history has 3 steps"):
        problem.solve_history([0.01, 0.01, 0.01], [0.0, 0.001], mu=0.3)
    with pytest.raises(tribo.SettingsError, match="at least one step"):
        problem.solve_history(0.01, np.array([]), mu=0.3)
    with pytest.raises(tribo.SettingsError, match="progress"):
        problem.solve_history(0.01, [0.0], mu=0.3, progress=3)  # type: ignore[arg-type]


def _fretting(**history: object) -> dict[str, object]:
    data = tomllib.loads(scene_path("fretting").read_text(encoding="utf-8"))
    data["history"] = history
    return data


def test_scene_history_paths() -> None:
    approach, shift, factor = parse_scene(_fretting(shift=[0.0, 0.002, 0.0], approach=0.01, steps=[2, 4])).history_steps()
    np.testing.assert_allclose(shift, [0.0, 0.001, 0.002, 0.0015, 0.001, 0.0005, 0.0])
    assert (approach == 0.01).all() and (factor == 1.0).all()
    with pytest.raises(SceneError, match="different lengths"):
        parse_scene(_fretting(shift=[0.0, 0.1], approach=[0.0, 0.01, 0.02])).history_steps()
    with pytest.raises(SceneError, match="one count per segment"):
        parse_scene(_fretting(shift=[0.0, 0.1, 0.0], steps=[3])).history_steps()
    with pytest.raises(SceneError, match="history.steps"):
        parse_scene(_fretting(shift=[0.0, 0.1], steps=0))
    with pytest.raises(SceneError, match="history.shift"):
        parse_scene(_fretting(shift=[0.0]))
    with pytest.raises(SceneError, match="history.speed"):
        parse_scene(_fretting(speed=1.0))


def _small_fretting(tmp_path: Path, extra: str = "") -> str:
    """The fretting scene on a coarse mesh in 1 + 2 + 2 + 2 steps (plus ``extra`` lines of [history]),
    written to ``tmp_path``; returns its text."""
    text = scene_path("fretting").read_text(encoding="utf-8")
    text = text.replace("h_min = 0.01", "h_min = 0.04").replace("steps = [8, 16, 16]", "steps = [2, 2, 2]" + extra)
    text = text.replace("plot_steps = [8, 24, 40]", "plot_steps = [2, 4]")
    (tmp_path / "fretting.toml").write_text(text, encoding="utf-8")
    return text


def test_run_writes_a_time_series(tmp_path: Path) -> None:
    _small_fretting(tmp_path)
    out = tmp_path / "out"
    assert main(["-q", "run", str(tmp_path / "fretting.toml"), "--out", str(out), "--plots"]) == 0
    pvd = ET.parse(out / "result.pvd").getroot()
    files = [d.get("file") for d in pvd.iter("DataSet")]
    assert files == [f"steps/step_{k:04d}.vtu" for k in range(7)]
    for f in files:
        assert meshio.read(out / str(f)).points.shape[1] == 3
    rows = (out / "history.csv").read_text(encoding="utf-8").splitlines()
    assert rows[0].startswith("# s (shift)") and rows[1].startswith("step,approach,shift")
    assert len(rows) == 2 + 7
    assert (out / "history_loop.png").is_file() and (out / "history_tractions.png").is_file()


def test_gross_sliding_is_reported(problem: tribo.Problem) -> None:
    h = problem.solve_history(0.01, np.linspace(0.0, 0.05, 6), mu=0.3)
    assert h.converged
    assert not h.gross_sliding[0] and h.gross_sliding[-1]
    assert abs(abs(h.tangential_force[-1]) / (0.3 * h.normal_force[-1]) - 1.0) < 1e-8


def test_long_histories_write_a_bounded_series(tmp_path: Path) -> None:
    """A history writes the VTU files of at most MAX_VTU_STEPS steps unless told otherwise (every k-th step
    and the last); history.csv keeps every step."""
    from tribo.history import MAX_VTU_STEPS, vtu_steps

    assert vtu_steps(0) == [] and vtu_steps(5) == [0, 1, 2, 3, 4] and vtu_steps(5, 2) == [0, 2, 4]
    assert vtu_steps(6, 4) == [0, 4, 5]
    long = vtu_steps(1001)
    assert len(long) <= MAX_VTU_STEPS + 1 and long[-1] == 1000 and long[1] - long[0] == 6
    assert vtu_steps(MAX_VTU_STEPS) == list(range(MAX_VTU_STEPS))
    text = _small_fretting(tmp_path, "\nwrite_every = 3")
    out = tmp_path / "out"
    assert main(["-q", "run", str(tmp_path / "fretting.toml"), "--out", str(out), "--no-plots"]) == 0
    files = [d.get("file") for d in ET.parse(out / "result.pvd").getroot().iter("DataSet")]
    assert files == ["steps/step_0000.vtu", "steps/step_0003.vtu", "steps/step_0006.vtu"]
    assert len((out / "history.csv").read_text(encoding="utf-8").splitlines()) == 2 + 7
    # `tribo run --all-files` writes every step whatever the scene says.
    assert main(["-q", "run", str(tmp_path / "fretting.toml"), "--out", str(tmp_path / "all"), "--all-files"]) == 0
    files = [d.get("file") for d in ET.parse(tmp_path / "all" / "result.pvd").getroot().iter("DataSet")]
    assert files == [f"steps/step_{k:04d}.vtu" for k in range(7)]
    bad = text.replace("write_every = 3", "write_every = 0")
    with pytest.raises(SceneError, match="write_every"):
        parse_scene(tomllib.loads(bad))


def test_a_step_file_that_cannot_be_written_ends_the_writing(problem: tribo.Problem, tmp_path: Path,
                                                              monkeypatch: pytest.MonkeyPatch) -> None:
    """The step files are written side by side; the first error reaches the caller as it was raised, and the
    steps not begun by then are not written (a history of 40 steps, the fourth failing, one writer: it
    wrote all 40 before the queued steps were cancelled)."""
    import tribo.history as th

    history = problem.solve_history(0.01, np.linspace(0.0, 0.002, 40), mu=0.3)
    written = th.write_vtu
    begun: list[int] = []

    def failing(path: Path, *args: object, **kwargs: object) -> list[Path]:
        k = int(Path(path).stem.split("_")[1])
        begun.append(k)
        if k == 3:
            raise OSError(28, "No space left on device", str(path))
        return written(path, *args, **kwargs)  # type: ignore[arg-type]

    monkeypatch.setattr(th, "write_vtu", failing)
    monkeypatch.setattr(th, "WRITERS", 1)
    with pytest.raises(OSError, match="No space left"):
        th.write_history(tmp_path, problem, history, plots=False)
    # The writer may have begun the next step before the error reached the caller; none after it.
    assert begun[:4] == [0, 1, 2, 3] and len(begun) <= 5
    names = sorted(p.name for p in (tmp_path / "steps").glob("step_[0-9][0-9][0-9][0-9].vtu"))
    assert names == [f"step_{k:04d}.vtu" for k in begun if k != 3]
    assert not (tmp_path / "history.csv").exists() and not (tmp_path / "result.pvd").exists()
