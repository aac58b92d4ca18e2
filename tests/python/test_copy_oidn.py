"""scripts/packaging/copy_oidn.py, which `make build` runs: it copies OIDN's four files from the
pyoidn wheel, a second run changes nothing, and OIDN files of another version are removed."""

from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
COPY = [sys.executable, "-m", "scripts.packaging.copy_oidn"]


@pytest.mark.skipif(importlib.util.find_spec("pyoidn") is None,
                    reason="pyoidn is not installed (scripts/requirements.txt)")
def test_copy_is_complete_idempotent_and_drops_stale_versions(tmp_path: Path) -> None:
    stale = tmp_path / "libOpenImageDenoise_core.so.2.0.0"
    stale.write_bytes(b"an older OIDN")
    subprocess.run([*COPY, str(tmp_path)], cwd=REPO, check=True)
    names = sorted(path.name for path in tmp_path.iterdir())
    assert not stale.exists()
    assert "libOpenImageDenoise.so.2" in names and "libtbb.so.12" in names
    assert any(n.startswith("libOpenImageDenoise_core.so.2.") for n in names), names
    assert any(n.startswith("libOpenImageDenoise_device_cpu.so.2.") for n in names), names
    assert len(names) == 4, names  # no GPU devices: the add-on asks for a CPU device
    inodes = {path.name: os.stat(path).st_ino for path in tmp_path.iterdir()}
    subprocess.run([*COPY, str(tmp_path)], cwd=REPO, check=True)
    assert {path.name: os.stat(path).st_ino for path in tmp_path.iterdir()} == inodes
