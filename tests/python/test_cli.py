"""The `stratum` command line (no Blender needed for these)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
from stratum import cli


def test_samplers_lists_the_registry(native: Any, capsys: pytest.CaptureFixture[str]) -> None:
    assert cli.main(["samplers"]) == 0
    lines = capsys.readouterr().out.splitlines()
    entries = native.registry("sampler")
    assert len(lines) == len(entries)
    for line, entry in zip(lines, entries, strict=True):
        assert line.split()[0] == entry.name
        assert entry.description in line


def test_samplers_console_script(native: Any) -> None:
    out = subprocess.run([sys.executable, "-m", "stratum.cli", "samplers"], capture_output=True,
                         text=True, check=True).stdout
    assert native.registry("sampler")[0].name in out


def test_render_rejects_unknown_sampler(native: Any, tmp_path: Path) -> None:
    blend = tmp_path / "scene.blend"
    blend.write_bytes(b"")
    proc = subprocess.run(
        [sys.executable, "-m", "stratum.cli", "render", str(blend), "--sampler", "bogus_sampler",
         "-o", str(tmp_path / "out.png")],
        capture_output=True, text=True, check=False)
    assert proc.returncode != 0
    assert "bogus_sampler" in proc.stderr


def test_render_rejects_bad_resolution(tmp_path: Path) -> None:
    with pytest.raises(SystemExit) as info:
        cli.main(["render", "x.blend", "--resolution", "64by64", "-o", str(tmp_path / "o.png")])
    assert info.value.code != 0


def test_render_missing_scene(native: Any, tmp_path: Path,
                              capsys: pytest.CaptureFixture[str]) -> None:
    assert cli.main(["render", str(tmp_path / "none.blend"), "-o", str(tmp_path / "o.png")]) != 0
    assert "none.blend" in capsys.readouterr().err


def test_render_through_blender(native: Any, tmp_path: Path) -> None:
    """End to end: `stratum render` runs Blender in the background with the add-on."""
    scene = Path(__file__).resolve().parents[2] / "scenes" / "cornell_box.blend"
    if not scene.is_file():
        pytest.skip(f"{scene} does not exist yet")
    if cli.blender_executable() is None:
        pytest.skip("Blender not found (set STRATUM_BLENDER)")
    out = tmp_path / "cornell.png"
    sampler = native.registry("sampler")[0].name
    proc = subprocess.run(
        [sys.executable, "-m", "stratum.cli", "render", str(scene), "--samples", "2",
         "--sampler", sampler, "--seed", "3", "--max-bounces", "2", "--resolution", "24x16",
         "-o", str(out)],
        capture_output=True, text=True, check=False, timeout=300)
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert out.is_file() and out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    width, height = int.from_bytes(out.read_bytes()[16:20], "big"), int.from_bytes(
        out.read_bytes()[20:24], "big")
    assert (width, height) == (24, 16)
