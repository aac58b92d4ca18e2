"""One version, written in stratum/blender_manifest.toml: the package, the native library
(CMakeLists.txt reads the manifest), the CLI and the pip metadata report it."""

from __future__ import annotations

import ast
import subprocess
import sys
import tomllib
from importlib.metadata import version as installed_version
from pathlib import Path
from typing import Any

import pytest
import stratum
from stratum.cli import main, version_report
from stratum.version import read_manifest_version, version_tuple

ADDON = Path(stratum.__file__).resolve().parent
MANIFEST = ADDON / "blender_manifest.toml"


def test_the_package_reads_the_manifest() -> None:
    assert stratum.__version__ == tomllib.loads(MANIFEST.read_text())["version"]


def test_the_native_library_was_built_with_the_manifest_version(native: Any) -> None:
    assert native.version() == stratum.__version__


def test_pip_metadata_reads_the_manifest() -> None:
    assert installed_version("stratum") == stratum.__version__


def test_bl_info_holds_no_second_copy() -> None:
    tree = ast.parse((ADDON / "__init__.py").read_text())
    info = next(n for n in tree.body if isinstance(n, ast.Assign)
                and getattr(n.targets[0], "id", "") == "bl_info")
    assert "version" not in ast.literal_eval(info.value), "make package writes it"


def test_cli_version_names_both(native: Any, capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as stop:
        main(["--version"])
    assert stop.value.code == 0
    out = capsys.readouterr().out
    assert out.splitlines()[0] == f"stratum {stratum.__version__}"
    assert f"native library {native.version()}: " in out
    assert str(native.library_status().path) in out


def test_cli_version_reports_a_missing_library(tmp_path: Path) -> None:
    """In a process of its own: the library is loaded once per process."""
    missing = tmp_path / "libstratum.so"
    run = subprocess.run([sys.executable, "-m", "stratum.cli", "--version"], capture_output=True,
                         text=True, check=False,
                         env={"STRATUM_LIBRARY": str(missing), "PATH": "/usr/bin:/bin"})
    assert run.returncode == 0, run.stderr
    assert f"native library: not loaded: Stratum native library not found at {missing}" \
        in run.stdout


def test_manifest_version_parsing(tmp_path: Path) -> None:
    manifest = tmp_path / "blender_manifest.toml"
    manifest.write_text('schema_version = "1.0.0"\nversion = "2.3.4-rc1"\n')
    assert read_manifest_version(manifest) == "2.3.4-rc1"
    assert version_tuple("2.3.4-rc1") == (2, 3, 4)
    assert version_tuple("1.0.0+local") == (1, 0, 0)
    manifest.write_text('schema_version = "1.0.0"\n')
    with pytest.raises(ValueError, match="no `version"):
        read_manifest_version(manifest)


def test_version_report_without_bpy() -> None:
    assert version_report().startswith(f"stratum {stratum.__version__}\n")
