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
