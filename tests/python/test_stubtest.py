"""The .pyi stub matches the compiled module (mypy.stubtest), and the package type-checks."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest


def test_stubtest(tmp_path: Path) -> None:
    pytest.importorskip("mypy")
    r = subprocess.run(
        [sys.executable, "-m", "mypy.stubtest", "tribo._tribo", "--mypy-config-file", str(tmp_path / "none.ini")],
        capture_output=True,
        text=True,
        cwd=tmp_path,  # keeps .mypy_cache out of the repository
        timeout=300,
    )
    assert r.returncode == 0, r.stdout + r.stderr


def test_package_type_checks(tmp_path: Path) -> None:
    """`mypy --strict` on the pure-Python package (with the stub as the compiled module's types)."""
    pytest.importorskip("mypy")
    root = Path(__file__).resolve().parents[2]
    if not (root / "python" / "tribo" / "_tribo.pyi").exists():
        pytest.skip("needs the source tree")
    r = subprocess.run(
        [sys.executable, "-m", "mypy", "--config-file", str(root / "pyproject.toml"), "--cache-dir", str(tmp_path)],
        capture_output=True,
        text=True,
        cwd=root,
        timeout=600,
    )
    assert r.returncode == 0, r.stdout + r.stderr
