"""The `stratum` command line (no Blender needed for these)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from stratum import cli
from stratum.cli import blender_process


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
    if blender_process.blender_executable() is None:
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


# ---- stratum points ------------------------------------------------------------------------------


def _points(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "stratum.cli", "points", *args],
                          capture_output=True, text=True, check=False, timeout=120)


def _csv(text: str, columns: int) -> np.ndarray:
    rows = [[float(v) for v in line.split(",")] for line in text.splitlines()]
    assert all(len(r) == columns for r in rows), text[:200]
    return np.array(rows, dtype=np.float64).reshape(-1, columns)


def _some_samplers(native: Any) -> list[str]:
    """A few registered samplers (all of them while the registry is small)."""
    names = [e.name for e in native.registry("sampler")]
    return names if len(names) <= 4 else names[:: max(1, len(names) // 4)]


def test_points_csv_for_several_samplers(native: Any, capsys: pytest.CaptureFixture[str]) -> None:
    for sampler in _some_samplers(native):
        assert cli.main(["points", "--sampler", sampler, "--count", "37", "--dims", "0,1",
                         "--pixel", "3,5", "--seed", "2", "--csv"]) == 0, sampler
        points = _csv(capsys.readouterr().out, 2)
        assert points.shape == (37, 2), sampler
        assert (points >= 0).all() and (points < 1).all(), sampler
        # the same points as the binding (the CSV keeps float32 exactly)
        expected = native.sampler_points(sampler, 37, 2, 64, 64, (3, 5), (0, 1), 37)
        np.testing.assert_array_equal(points.astype(np.float32), expected, err_msg=sampler)


def test_points_console_script_default_csv(native: Any) -> None:
    proc = _points("--sampler", native.registry("sampler")[0].name, "--count", "10", "--dims",
                   "10,11", "--samples", "64", "--resolution", "16x8", "--pixel", "15,7")
    assert proc.returncode == 0, proc.stderr
    points = _csv(proc.stdout, 2)
    assert points.shape == (10, 2)
    assert (points >= 0).all() and (points < 1).all()


@pytest.mark.parametrize("distribution", ["cosine", "uniform", "uniform_angles"])
def test_points_hemisphere_gives_unit_vectors(native: Any, distribution: str,
                                              capsys: pytest.CaptureFixture[str]) -> None:
    assert cli.main(["points", "--sampler", "random", "--count", "200", "--dims", "10,11",
                     "--hemisphere", distribution]) == 0
    xyz = _csv(capsys.readouterr().out, 3)
    assert xyz.shape == (200, 3)
    np.testing.assert_allclose(np.linalg.norm(xyz, axis=1), 1.0, atol=1e-5)
    assert (xyz[:, 2] >= 0).all()


@pytest.mark.parametrize("hemisphere", [None, "cosine"])
def test_points_plot_writes_a_png(native: Any, tmp_path: Path, hemisphere: str | None) -> None:
    pytest.importorskip("matplotlib")
    out = tmp_path / "points.png"
    args = ["--sampler", "random", "--count", "500", "--dims", "0,1", "--plot", str(out)]
    if hemisphere:
        args += ["--hemisphere", hemisphere]
    proc = _points(*args)
    assert proc.returncode == 0, proc.stderr
    assert out.is_file() and out.stat().st_size > 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_points_list_dims(native: Any, capsys: pytest.CaptureFixture[str]) -> None:
    assert cli.main(["points", "--list-dims"]) == 0
    out = capsys.readouterr().out
    assert "filter.x" in out and "bounce0.bsdf.u" in out and "bounce1.bsdf.u" in out
    assert "stride" in out
    camera = native.camera_dimensions()
    lines = {line.split()[0]: line.split()[1] for line in out.splitlines()
             if line.strip() and line.split()[0].isdigit()}
    assert lines["0"] == "filter.x" and lines["1"] == "filter.y"
    assert lines[str(camera)] == "bounce0.light_choice"


@pytest.mark.parametrize(("args", "named"), [
    (["--sampler", "bogus_sampler", "--count", "4", "--dims", "0,1"], "bogus_sampler"),
    (["--sampler", "random", "--count", "4", "--dims", "0,x"], "0,x"),
    (["--sampler", "random", "--count", "4", "--dims", "0,-3"], "-3"),
    (["--sampler", "random", "--count", "4", "--dims", "1.5,2"], "1.5,2"),
    (["--sampler", "random", "--count", "4", "--dims", "0,1,2"], "0,1,2"),
    (["--sampler", "random", "--count", "4", "--dims", "0,4294967296"], "4294967296"),
    (["--sampler", "random", "--count", "0", "--dims", "0,1"], "0"),
    (["--sampler", "random", "--count", "-5", "--dims", "0,1"], "-5"),
    (["--sampler", "random", "--count", "4", "--dims", "0,1", "--pixel", "64,0"], "64,0"),
    (["--sampler", "random", "--count", "4", "--dims", "0,1", "--resolution", "8x8",
      "--pixel", "2,8"], "2,8"),
    (["--sampler", "random", "--count", "4", "--dims", "0,1", "--hemisphere", "spiral"],
     "spiral"),
    (["--sampler", "random", "--count", "2000000", "--dims", "0,1"], "2000000"),
])
def test_points_rejects_bad_values_naming_them(native: Any, args: list[str], named: str) -> None:
    proc = _points(*args)
    assert proc.returncode != 0
    assert named in proc.stderr, proc.stderr
    assert not proc.stdout


def test_compare_help_documents_the_estimator_specs(native: Any,
                                                    capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as info:
        cli.main(["compare", "--help"])
    assert info.value.code == 0
    text = " ".join(capsys.readouterr().out.split())  # argparse wraps lines
    for expected in ("INTEGRATOR[:NAME=VALUE,...]", "light_sampling=mis|nee|bsdf",
                     "mis_heuristic=power|balance|max", "rr_mode=throughput|albedo|off",
                     "--set NAME=VALUE", "--reference-integrator SPEC", "mis-<heuristic>"):
        assert expected in text, expected
    for name in ("sampler", "integrator", "hemisphere"):  # the library's names, all of them
        assert ", ".join(native.setting(name).choice_names()) in text, name
    assert "rr_min_depth=<0..1024> (default 3)" in text


def test_help_works_without_the_library(tmp_path: Path) -> None:
    """`stratum compare --help` lists the library's names; without a library it still prints,
    saying they are not listed."""
    env = dict(os.environ, STRATUM_LIBRARY=str(tmp_path / "missing" / "libstratum.so"))
    for args in ([], ["compare"]):
        proc = subprocess.run([sys.executable, "-m", "stratum.cli", *args, "--help"], env=env,
                              capture_output=True, text=True, check=False, timeout=60)
        assert proc.returncode == 0, proc.stderr
        assert "usage: stratum" in proc.stdout
    assert "not listed: the native library cannot be loaded" in " ".join(proc.stdout.split())
