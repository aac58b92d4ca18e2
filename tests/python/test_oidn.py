"""The Open Image Denoise binding (stratum.native.oidn), without Blender: it denoises, it finds
its library where `make build` puts it, and a missing or broken library is a clear error."""

from __future__ import annotations

import sys
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest
from stratum.native import oidn


@pytest.fixture
def fresh_library(monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    """No library loaded yet, so that the search runs again; the loaded one is restored."""
    monkeypatch.setattr(oidn, "_lib", None)
    monkeypatch.setattr(oidn, "_lib_path", "")
    yield


@pytest.fixture(scope="module")
def library() -> str:
    try:
        return oidn.load_library()[1]
    except oidn.DenoiserUnavailable as exc:
        pytest.skip(f"Open Image Denoise not available (make build installs it): {exc}")


def smooth_image(size: int = 64) -> np.ndarray:
    y, x = np.mgrid[0:size, 0:size] / size
    return np.stack([0.2 + 0.6 * x, 0.3 + 0.5 * y, 0.5 + 0.3 * x * y], axis=-1).astype(np.float32)


def noisy(clean: np.ndarray, seed: int) -> np.ndarray:
    """Monte Carlo-like noise: each pixel the clean value times an Exp(1) variate (mean 1,
    standard deviation 1), so the noisy image's MSE is the mean of clean^2, about 0.3."""
    rng = np.random.default_rng(seed)
    return (clean * rng.exponential(1.0, clean.shape)).astype(np.float32)


def test_denoising_brings_a_noisy_smooth_image_closer_to_the_clean_one(library: str) -> None:
    clean = smooth_image()
    image = noisy(clean, seed=7)
    albedo = np.full_like(clean, 0.8)
    normal = np.zeros_like(clean)
    normal[..., 2] = 1.0
    noisy_mse = float(np.mean((image - clean) ** 2))
    for denoised in (oidn.denoise(image), oidn.denoise(image, albedo, normal)):
        assert denoised.shape == clean.shape and denoised.dtype == np.float32
        assert np.isfinite(denoised).all()
        mse = float(np.mean((denoised - clean) ** 2))
        # Measured: 0.308 -> 0.0020 (colour alone) and 0.0019 (with guides), a factor 150;
        # 20 leaves room for another OIDN version's weights.
        assert mse * 20 < noisy_mse, (mse, noisy_mse)
    assert np.array_equal(image, noisy(clean, seed=7)), "the input must be left alone"


def test_bad_images_are_value_errors(library: str) -> None:
    clean = smooth_image(8)
    with pytest.raises(ValueError, match="H x W x 3"):
        oidn.denoise(clean[..., :2])
    with pytest.raises(ValueError, match="albedo has shape"):
        oidn.denoise(clean, albedo=clean[:4])
    with pytest.raises(ValueError, match="normal guide only together with an albedo"):
        oidn.denoise(clean, normal=clean)
    bad = clean.copy()
    bad[0, 0, 0] = np.nan
    with pytest.raises(ValueError, match="not finite"):
        oidn.denoise(bad)


def test_library_is_found_without_importing_pyoidn(fresh_library: None,
                                                   monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv(oidn.ENV_VAR, raising=False)
    candidates = oidn.candidate_paths()
    assert candidates[-1] == oidn.LIBRARY_FILE  # the system's loader path comes last
    bundled = Path(oidn.__file__).resolve().parent.parent / "lib" / oidn.LIBRARY_FILE
    if bundled.is_file():
        assert candidates[0] == str(bundled)
    assert "pyoidn" not in sys.modules  # pyoidn imports cffi, which Blender 3.4 lacks


@pytest.mark.parametrize("make_file", ["missing", "not_a_library", "not_oidn"])
def test_missing_or_broken_library_names_the_path_and_the_reason(
        fresh_library: None, monkeypatch: pytest.MonkeyPatch, tmp_path: Path,
        make_file: str) -> None:
    if make_file == "missing":
        path, reason = tmp_path / "nowhere" / "libOpenImageDenoise.so.2", "No such file"
    elif make_file == "not_a_library":
        path, reason = tmp_path / "libOpenImageDenoise.so.2", "invalid ELF header"
        path.write_text("not a shared library\n" * 64)  # long enough to be read as ELF
    else:  # a real library that is not OIDN
        import ctypes.util

        name = ctypes.util.find_library("m")
        assert name is not None
        path, reason = Path(name), "undefined symbol: oidnNewDevice"
    monkeypatch.setenv(oidn.ENV_VAR, str(path))
    assert oidn.candidate_paths() == [str(path)]  # an override is the only candidate
    with pytest.raises(oidn.DenoiserUnavailable) as info:
        oidn.denoise(smooth_image(8))
    message = str(info.value)
    assert str(path) in message and reason in message and oidn.ENV_VAR in message
    assert not oidn.available()
    # The failure is not kept: the next call searches again.
    monkeypatch.delenv(oidn.ENV_VAR)
    assert oidn._lib is None
