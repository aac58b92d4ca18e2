"""The `stratum compare` report: spectra on known images, and a report built from a synthetic
out_dir (EXR renders + results dict) that loads cleanly in headless Chromium."""

from __future__ import annotations

import math
import shutil
import tempfile
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from stratum.compare import spectra

REPO = Path(__file__).resolve().parents[2]
SAMPLERS = ("random", "sobol", "bluenoise")
SPP = (4, 16, 64)
SEEDS = (1, 2)
WIDTH, HEIGHT = 64, 48


# ---- spectra -----------------------------------------------------------------------------------


def _low_bins(n: int) -> int:
    f = np.fft.fftfreq(n)
    r = np.hypot(f[:, None], f[None, :])
    return int(((r > 0) & (r <= 1 / 8)).sum())


def test_white_noise_has_a_low_frequency_ratio_of_one() -> None:
    # Each non-DC power of white noise is σ²·Exp(1); a real image's spectrum is Hermitian, so
    # the n_low bins in the disc hold about n_low/2 independent values, and their mean has a
    # relative standard deviation of 1/sqrt(n_low/2). The overall mean (all bins) is ~40x
    # more precise. Tolerance: 5 standard deviations.
    n = 256
    image = np.random.default_rng(7).normal(size=(n, n))
    tolerance = 5.0 / math.sqrt(_low_bins(n) / 2)
    assert tolerance < 0.15
    assert abs(spectra.low_frequency_ratio(image) - 1.0) < tolerance


def test_high_pass_noise_has_a_small_low_frequency_ratio() -> None:
    # Discrete Laplacian of white noise: power ∝ (4 sin²(πf_x) + 4 sin²(πf_y))², tiny at low |f|.
    white = np.random.default_rng(3).normal(size=(128, 128))
    lap = (4 * white - np.roll(white, 1, 0) - np.roll(white, -1, 0) - np.roll(white, 1, 1)
           - np.roll(white, -1, 1))
    ratio = spectra.low_frequency_ratio(lap)
    assert ratio < 0.3, ratio
    # A non-square image uses |f| in cycles per pixel on each axis.
    assert spectra.low_frequency_ratio(lap[:, :96]) < 0.3


def test_radial_average_of_a_cosine_peaks_at_its_frequency() -> None:
    n, k = 128, 16  # 16 cycles over 128 px: |f| = 1/8
    x = np.arange(n)
    image = np.tile(np.cos(2 * np.pi * k * x / n), (n, 1))
    centres, power = spectra.radial_average(image, bins=32)
    peak = int(np.nanargmax(power))
    assert abs(centres[peak] - k / n) <= 0.5 / 32 * 1.0001
    # Parseval: total power = pixels · variance, all of it in the two bins at ±k (n²/4 each).
    full = spectra.power_spectrum(image)
    assert full.sum() == pytest.approx(image.var() * n * n, rel=1e-9)
    assert full[0, k] == pytest.approx(n * n / 4, rel=1e-9)


def test_radial_average_of_white_noise_is_flat_at_its_variance() -> None:
    image = np.random.default_rng(11).normal(scale=2.0, size=(256, 256))
    _, power = spectra.radial_average(image, bins=8)
    # The innermost ring has ~200 bins (relative sd ~ 0.1): 5 sd.
    np.testing.assert_allclose(power, 4.0, rtol=0.5)
    assert abs(np.mean(power) - 4.0) < 0.2


def test_bluenoise_texture_binding(native: Any) -> None:
    texture = native.bluenoise_texture()
    assert texture.shape == (128, 128) and texture.dtype == np.float32
    ranks = np.sort(texture.ravel().astype(np.float64) * 16384 - 0.5)
    np.testing.assert_array_equal(ranks, np.arange(16384))
    assert spectra.low_frequency_ratio(texture) < 0.3


# ---- synthetic out_dir -------------------------------------------------------------------------


def _write_exr(path: Path, rgb: np.ndarray) -> None:
    import OpenEXR

    path.parent.mkdir(parents=True, exist_ok=True)
    channels = {c: np.ascontiguousarray(rgb[..., i], dtype=np.float32)
                for i, c in enumerate("RGB")}
    header = {"compression": OpenEXR.ZIP_COMPRESSION, "type": OpenEXR.scanlineimage}
    with OpenEXR.File(header, channels) as f:
        f.write(str(path))


def _reference_image() -> np.ndarray:
    y, x = np.mgrid[0:HEIGHT, 0:WIDTH] / np.array([HEIGHT, WIDTH])[:, None, None]
    disk = ((x - 0.65) ** 2 + (y - 0.4) ** 2 < 0.04).astype(float)
    base = 0.2 + 0.5 * x[..., None] * np.array([1.0, 0.6, 0.3]) + 0.6 * disk[..., None]
    base[: HEIGHT // 6, WIDTH // 3: 2 * WIDTH // 3] = 4.0  # an over-exposed "light"
    return base


def _noise(sampler: str, rng: np.random.Generator, spp: int) -> np.ndarray:
    white = rng.normal(size=(HEIGHT, WIDTH, 3))
    if sampler == "bluenoise":  # high-passed, rescaled to unit variance
        white = (4 * white - sum(np.roll(white, s, a) for s in (1, -1) for a in (0, 1)))
        white /= white.std()
    scale = {"random": 0.2, "sobol": 0.1, "bluenoise": 0.12}[sampler]
    slope = {"random": 0.5, "sobol": 0.75, "bluenoise": 0.6}[sampler]
    return scale * white / spp**slope


def _ci(values: list[float]) -> tuple[float, float, float]:
    v = np.array(values)
    half = 1.96 * v.std(ddof=1) / math.sqrt(len(v))
    return float(v.mean()), float(v.mean() - half), float(v.mean() + half)


def build_out_dir(out: Path, crop: list[int] | None, with_summary: bool) -> dict[str, Any]:
    ref = _reference_image()
    _write_exr(out / "renders" / "reference.exr", ref)
    floor = {"mse": 2e-5, "rel_mse": 1e-4}
    renders = []
    for si, sampler in enumerate(SAMPLERS):
        for spp in SPP:
            for seed in SEEDS:
                rng = np.random.default_rng(1000 * si + 10 * spp + seed)
                img = np.maximum(ref + _noise(sampler, rng, spp), 0.0)
                rel = f"renders/{sampler}_{spp:04d}_{seed}.exr"
                _write_exr(out / rel, img)
                err = img - ref
                mse = float(np.mean(err**2))
                renders.append({
                    "sampler": sampler, "spp": spp, "seed": seed, "path": rel,
                    "seconds": 0.01 * spp * (1.0 + 0.3 * si), "mse": mse,
                    "rel_mse": float(np.mean(err**2 / (ref**2 + 1e-2))),
                    "flip_ldr": 0.4 * spp**-0.4 / (1 + si), "flip_hdr": 0.5 * spp**-0.4 / (1 + si),
                    "below_noise_floor": mse < floor["mse"]})
    summary = []
    for sampler in SAMPLERS:
        for spp in SPP:
            rows = [r for r in renders if r["sampler"] == sampler and r["spp"] == spp]
            for metric in ("mse", "rel_mse", "flip_ldr", "flip_hdr", "seconds"):
                mean, lo, hi = _ci([r[metric] for r in rows])
                summary.append({"sampler": sampler, "spp": spp, "metric": metric, "mean": mean,
                                "ci95_low": lo, "ci95_high": hi, "n": len(rows)})
    results: dict[str, Any] = {
        "scene": "scenes/synthetic.blend", "scene_sha256": "0" * 64,
        "resolution": [WIDTH, HEIGHT], "crop": crop, "integrator": "path",
        "hemisphere": "cosine", "max_bounces": 4, "samplers": list(SAMPLERS),
        "spp": list(SPP), "seeds": list(SEEDS),
        "reference": {"path": "renders/reference.exr", "spp": 4096, "seeds": [99],
                      "source": "rendered", "noise_floor": floor},
        "renders": renders,
    }
    if with_summary:
        results["summary"] = summary
        # "bluenoise" has no slopes: the report fits them itself.
        results["slopes"] = {s: {"mse": -1.0 - 0.5 * i, "rel_mse": -1.0, "flip_ldr": -0.4,
                                 "flip_hdr": -0.4, "mse_vs_seconds": -1.0}
                             for i, s in enumerate(SAMPLERS[:2])}
    return results


# ---- the report ----------------------------------------------------------------------------------


def _chrome() -> Any:
    if not (Path("/usr/bin/chromium").is_file() and Path("/usr/bin/chromedriver").is_file()):
        pytest.skip("Debian chromium / chromium-driver are not installed")
    webdriver = pytest.importorskip("selenium.webdriver")
    from selenium.webdriver.chrome.service import Service

    profile = tempfile.mkdtemp(prefix="stratum-report-chrome-")
    options = webdriver.ChromeOptions()
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                "--no-first-run", "--disable-background-networking",
                "--disable-component-update", "--disable-sync", f"--user-data-dir={profile}",
                "--window-size=1300,900"):
        options.add_argument(arg)
    options.binary_location = "/usr/bin/chromium"
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    driver = webdriver.Chrome(service=Service(executable_path="/usr/bin/chromedriver"),
                              options=options)
    driver.stratum_profile = profile
    return driver


def test_report_loads_in_chromium_with_every_image_and_section(native: Any,
                                                               tmp_path: Path) -> None:
    from stratum.compare.report import SECTION_TITLES, write_report

    results = build_out_dir(tmp_path, crop=None, with_summary=True)
    html_path = write_report(tmp_path, results)
    assert html_path == tmp_path / "report.html"
    text = html_path.read_text(encoding="utf-8")
    assert "could not be drawn" not in text and "Missing renders" not in text
    assert "http://" not in text and "https://" not in text and "<script" not in text
    assert len(list((tmp_path / "figures").rglob("*.png"))) > 20

    driver = _chrome()
    try:
        driver.get(html_path.as_uri())
        errors = [e for e in driver.get_log("browser") if e.get("level") == "SEVERE"]
        assert not errors, errors
        images = driver.execute_script(
            "return Array.from(document.images).map(i => [i.getAttribute('src'), "
            "i.complete, i.naturalWidth]);")
        assert len(images) > 20
        broken = [src for src, complete, width in images if not complete or width <= 0]
        assert not broken, broken
        headings = driver.execute_script(
            "return Array.from(document.querySelectorAll('h2')).map(h => h.textContent);")
        assert list(headings) == list(SECTION_TITLES)
        height = driver.execute_script("return document.documentElement.scrollHeight;")
        driver.set_window_size(1300, min(int(height) + 40, 16000))
        shot = REPO / "out" / "report_screenshot.png"
        shot.parent.mkdir(exist_ok=True)
        assert driver.save_screenshot(str(shot))
    finally:
        driver.quit()
        shutil.rmtree(driver.stratum_profile, ignore_errors=True)


def test_report_given_crop_and_no_summary_or_slopes(native: Any, tmp_path: Path) -> None:
    from stratum.compare.report import write_report

    results = build_out_dir(tmp_path, crop=[40, 20, 200, 12], with_summary=False)
    results["renders"] = [r for r in results["renders"]
                          if not (r["sampler"] == "sobol" and r["spp"] == 16)]
    text = write_report(tmp_path, results).read_text(encoding="utf-8")
    assert "could not be drawn" not in text
    assert "x=40, y=20, 24x12 px" in text  # clipped to the 64x48 image
    assert "Missing renders: sobol 16 spp" in text
    assert "fitted here from the means" in text


def test_report_of_an_estimator_comparison_shows_estimators_as_series(native: Any,
                                                                      tmp_path: Path) -> None:
    """Results of `--integrator A,B,C --samplers random`: one series per estimator label, in
    the tables, the convergence legends and the image grid; the sample-point section still
    draws the one sampler."""
    from stratum.compare.report import write_report

    results = build_out_dir(tmp_path, crop=None, with_summary=True)
    label = {"random": "bsdf", "sobol": "nee", "bluenoise": "mis-power"}
    for row in results["renders"] + results["summary"]:
        row["series"] = row["estimator"] = label[row["sampler"]]
        row["sampler"] = "random"
    results["slopes"] = {label[s]: v for s, v in results["slopes"].items()}
    results["series"] = list(label.values())
    results["samplers"] = ["random"]
    results["estimators"] = [{"label": v, "spec": f"path:light_sampling={v}"}
                             for v in label.values()]
    text = write_report(tmp_path, results).read_text(encoding="utf-8")
    assert "could not be drawn" not in text and "Missing renders" not in text
    for name in label.values():
        assert f'<td class="name">{name}</td>' in text  # slopes table row
        assert f'<th class="name">{name}</th>' in text  # image grid row
        assert f"{name} = path:light_sampling={name}" in text  # settings
    points = sorted(p.name for p in (tmp_path / "figures" / "points").glob("*.png"))
    assert points == ["random.png"]
    grid = sorted(p.name for p in (tmp_path / "figures" / "images").glob("*_full.png"))
    assert grid == sorted([f"{n}_{s}_full.png" for n in label.values() for s in SPP]
                          + ["reference_full.png"])
