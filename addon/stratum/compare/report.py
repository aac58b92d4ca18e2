"""The `stratum compare` report: `write_report(out_dir, results)` writes out_dir/report.html
and its figures under out_dir/figures/ (static HTML, PNG images, no scripts, no external
resources). `results` follows the results.json schema of the compare runner; every field is
read defensively (missing summary or slopes are computed from the renders).

A section that cannot be drawn (a missing EXR, no native library) says why in the page
instead of failing the whole report.
"""

from __future__ import annotations

import html
import math
import re
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from .spectra import luminance

METRICS: dict[str, str] = {
    "mse": "MSE",
    "rel_mse": "relative MSE",
    "flip_ldr": "mean FLIP (LDR)",
    "flip_hdr": "mean FLIP (HDR)",
}
SLOPE_KEYS: tuple[str, ...] = ("mse", "rel_mse", "flip_ldr", "flip_hdr", "mse_vs_seconds")

# Headings of the report's sections, in page order (the report test checks every one).
SECTION_TITLES: tuple[str, ...] = (
    "Settings",
    "Convergence",
    "Results",
    "Convergence slopes",
    "Images",
    "Error spectra",
    "Sample points",
    "Blue-noise texture",
    "Hemisphere distributions",
    "Fibonacci lattice on the hemisphere",
)

_CSS = """
body { font-family: sans-serif; margin: 1.5em auto; max-width: 1250px; color: #222; }
h1 { font-size: 1.6em; } h2 { border-bottom: 1px solid #ccc; margin-top: 1.8em; }
table { border-collapse: collapse; margin: 0.6em 0; font-size: 0.85em; }
td, th { border: 1px solid #ccc; padding: 2px 7px; text-align: right; white-space: nowrap; }
th { background: #f0f0f0; } td.name, th.name { text-align: left; }
img { max-width: 100%; }
table.grid td { text-align: center; vertical-align: top; border: none; padding: 3px; }
table.grid img { display: block; width: 220px; }
table.grid img.crop { image-rendering: pixelated; margin-top: 3px; }
p.note { color: #555; font-size: 0.9em; max-width: 70em; }
p.problem { color: #a00; }
"""


def esc(value: Any) -> str:
    return html.escape(str(value), quote=True)


def safe_name(text: str) -> str:
    """A file-name-safe version of a sampler name or label."""
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", str(text)) or "x"


def fmt(value: Any, digits: int = 3) -> str:
    if value is None:
        return "–"
    try:
        v = float(value)
    except (TypeError, ValueError):
        return esc(value)
    if not math.isfinite(v):
        return "–"
    return f"{v:.{digits}g}"


def img_tag(out_dir: Path, path: Path, alt: str, css_class: str = "") -> str:
    rel = path.relative_to(out_dir).as_posix()
    cls = f' class="{esc(css_class)}"' if css_class else ""
    return f'<img src="{esc(rel)}" alt="{esc(alt)}"{cls}>'


def problem(text: str) -> str:
    return f'<p class="note problem">{esc(text)}</p>'


# ---- results, read defensively -----------------------------------------------------------------


def _series(row: dict[str, Any]) -> str:
    return str(row.get("series", row.get("sampler")))


class Results:
    """Accessors over the results dict that tolerate missing or null fields."""

    def __init__(self, out_dir: Path, raw: dict[str, Any]) -> None:
        self.out_dir = out_dir
        self.raw = raw
        self.renders: list[dict[str, Any]] = [r for r in raw.get("renders") or []
                                              if isinstance(r, dict)]
        # The series of the tables and plots: (estimator, sampler) pairs named as in
        # stratum.compare.series_name; results without `series` (sampler comparisons written
        # before estimators were an axis) have one series per sampler.
        self.sampler_names: list[str] = list(
            raw.get("samplers") or dict.fromkeys(str(r.get("sampler")) for r in self.renders))
        self.samplers: list[str] = list(
            raw.get("series") or dict.fromkeys(_series(r) for r in self.renders))
        spp = raw.get("spp") or sorted({int(r["spp"]) for r in self.renders if "spp" in r})
        self.spp: list[int] = sorted(int(s) for s in spp)
        seeds = raw.get("seeds") or sorted({int(r["seed"]) for r in self.renders if "seed" in r})
        self.seeds: list[int] = [int(s) for s in seeds]
        self.reference: dict[str, Any] = raw.get("reference") or {}
        self.slopes: dict[str, dict[str, Any]] = raw.get("slopes") or {}
        self._summary = self._index_summary(raw.get("summary") or [])
        self._images: dict[Path, np.ndarray] = {}

    def image(self, path: Path) -> np.ndarray:
        """read_exr(path), cached: the grid and the spectra read the same renders."""
        if path not in self._images:
            self._images[path] = read_exr(path)
        return self._images[path]

    @property
    def first_seed(self) -> int | None:
        return self.seeds[0] if self.seeds else None

    def resolution(self) -> tuple[int, int]:
        res = self.raw.get("resolution") or [64, 64]
        try:
            return max(1, int(res[0])), max(1, int(res[1]))
        except (TypeError, ValueError, IndexError):
            return 64, 64

    def resolve(self, path: Any) -> Path | None:
        if not path:
            return None
        p = Path(str(path))
        return p if p.is_absolute() else self.out_dir / p

    def reference_path(self) -> Path | None:
        return self.resolve(self.reference.get("path") or "renders/reference.exr")

    def noise_floor(self, metric: str) -> float | None:
        floor = self.reference.get("noise_floor") or {}
        value = floor.get(metric) if isinstance(floor, dict) else None
        return float(value) if isinstance(value, int | float) else None

    def render(self, sampler: str, spp: int, seed: int | None) -> dict[str, Any] | None:
        for r in self.renders:
            if (_series(r) == sampler and int(r.get("spp", -1)) == spp
                    and (seed is None or int(r.get("seed", -1)) == seed)):
                return r
        return None

    def values(self, sampler: str, spp: int, metric: str) -> np.ndarray:
        vals = [r.get(metric) for r in self.renders
                if _series(r) == sampler and int(r.get("spp", -1)) == spp]
        return np.array([float(v) for v in vals if isinstance(v, int | float)], dtype=float)

    def below_floor(self, sampler: str, spp: int, metric: str | None = None) -> bool:
        """Any seed below the reference noise floor: by `<metric>_below_noise_floor` when the
        runner gives it, else by `below_noise_floor`."""
        key = f"{metric}_below_noise_floor" if metric else "below_noise_floor"
        return any(bool(r.get(key, r.get("below_noise_floor"))) for r in self.renders
                   if _series(r) == sampler and int(r.get("spp", -1)) == spp)

    @staticmethod
    def _index_summary(rows: Sequence[Any]) -> dict[tuple[str, int, str], tuple[float, ...]]:
        index: dict[tuple[str, int, str], tuple[float, ...]] = {}
        for row in rows:
            if not isinstance(row, dict):
                continue
            try:
                key = (_series(row), int(row["spp"]), str(row["metric"]))
                index[key] = tuple(float(row[k]) if row.get(k) is not None else math.nan
                                   for k in ("mean", "ci95_low", "ci95_high", "n"))
            except (KeyError, TypeError, ValueError):
                continue
        return index

    def stat(self, sampler: str, spp: int, metric: str) -> tuple[float, float, float, int]:
        """(mean, 95% low, 95% high, n) over seeds: the runner's summary row, else computed
        here (mean ± 1.96 standard errors)."""
        row = self._summary.get((sampler, spp, metric))
        if row is not None:
            n = int(row[3]) if math.isfinite(row[3]) else 0
            return row[0], row[1], row[2], n
        v = self.values(sampler, spp, metric)
        if v.size == 0:
            return math.nan, math.nan, math.nan, 0
        half = 1.96 * v.std(ddof=1) / math.sqrt(v.size) if v.size > 1 else math.nan
        return float(v.mean()), float(v.mean() - half), float(v.mean() + half), int(v.size)

    def slope(self, sampler: str, key: str) -> tuple[float | None, bool]:
        """(slope, computed_here): the runner's fitted slope, else a least-squares fit of
        log(mean) against log(spp) (or log(seconds) for mse_vs_seconds)."""
        value = (self.slopes.get(sampler) or {}).get(key)
        if isinstance(value, int | float):
            return float(value), False
        metric = "mse" if key == "mse_vs_seconds" else key
        x = np.array([self.stat(sampler, s, "seconds")[0] if key == "mse_vs_seconds" else s
                      for s in self.spp], dtype=float)
        y = np.array([self.stat(sampler, s, metric)[0] for s in self.spp], dtype=float)
        ok = np.isfinite(x) & np.isfinite(y) & (x > 0) & (y > 0)
        if ok.sum() < 2 or np.ptp(np.log(x[ok])) == 0:
            return None, True
        return float(np.polyfit(np.log(x[ok]), np.log(y[ok]), 1)[0]), True


# ---- images ----------------------------------------------------------------------------------


def read_exr(path: Path) -> np.ndarray:
    """Linear RGB (H, W, 3) float32 of an EXR: channels R, G, B (or *.R, *.G, *.B of a
    multilayer file); a single-channel file is repeated into grey."""
    import OpenEXR

    with OpenEXR.File(str(path), separate_channels=True) as f:
        channels = {name: np.asarray(ch.pixels, dtype=np.float32)
                    for name, ch in f.channels().items()}
    if not channels:
        raise ValueError(f"{path}: no channels")
    picked = []
    for c in ("R", "G", "B"):
        name = next((n for n in channels if n == c or n.endswith("." + c)), None)
        picked.append(name)
    if all(picked):
        return np.stack([channels[n] for n in picked], axis=-1)  # type: ignore[index]
    grey = next(iter(channels.values()))
    return np.repeat(grey[..., None], 3, axis=-1)


def display_transform(linear: np.ndarray, gain: float = 1.0) -> np.ndarray:
    """Display-referred RGB in [0, 1]: linear × gain, clamped to [0, 1], sRGB transfer."""
    x = np.clip(np.nan_to_num(np.asarray(linear, dtype=np.float64)[..., :3] * gain), 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1.0 / 2.4) - 0.055)


def detail_region(reference: np.ndarray) -> tuple[int, int, int, int]:
    """(x, y, w, h) of the quarter-size window (w = W/4, h = H/4, at least 8 px) with the
    largest sum of |∇| of the display-transformed reference luminance (integral image),
    not counting pixels next to clipped ones (a channel > 1: lights), whose edges would win."""
    lum = luminance(display_transform(reference))
    clipped = np.asarray(reference)[..., :3].max(axis=-1) > 1.0
    near = clipped.copy()
    near[1:, :] |= clipped[:-1, :]
    near[:-1, :] |= clipped[1:, :]
    near[:, 1:] |= clipped[:, :-1]
    near[:, :-1] |= clipped[:, 1:]
    h_img, w_img = lum.shape
    w, h = min(w_img, max(8, w_img // 4)), min(h_img, max(8, h_img // 4))
    grad = np.zeros_like(lum)
    grad[:, 1:] += np.abs(np.diff(lum, axis=1))
    grad[1:, :] += np.abs(np.diff(lum, axis=0))
    grad[near] = 0.0
    s = np.zeros((h_img + 1, w_img + 1))
    s[1:, 1:] = grad.cumsum(0).cumsum(1)
    sums = s[h:, w:] - s[:-h, w:] - s[h:, :-w] + s[:-h, :-w]
    y, x = np.unravel_index(int(np.argmax(sums)), sums.shape)
    return int(x), int(y), w, h


def crop_region(results: Results, reference: np.ndarray) -> tuple[tuple[int, int, int, int], str]:
    """The results' `crop` (x, y, w, h from the top-left corner, clipped to the image) if it
    is given and non-empty, else detail_region(); with a sentence saying which."""
    h_img, w_img = reference.shape[:2]
    crop = results.raw.get("crop")
    if isinstance(crop, list | tuple) and len(crop) == 4:
        try:
            x, y, w, h = (int(v) for v in crop)
            x0, y0 = max(0, min(x, w_img - 1)), max(0, min(y, h_img - 1))
            x1, y1 = max(x0 + 1, min(x + w, w_img)), max(y0 + 1, min(y + h, h_img))
            if w > 0 and h > 0:
                how = "the region given as `crop` in results.json, where the metrics were measured"
                return (x0, y0, x1 - x0, y1 - y0), how
        except (TypeError, ValueError):
            pass
    return detail_region(reference), ("no `crop` was given, so the quarter-size window with "
                                      "the most detail in the reference (largest sum of the "
                                      "luminance gradient after the display transform, clipped "
                                      "pixels such as lights and their edges left out)")


def crop_gain(reference_crop: np.ndarray) -> float:
    """Exposure for the magnified crops, a power of two in [1, 16]: brings the reference
    crop's mean luminance towards 0.18 (mid grey). The same gain for every crop."""
    mean = float(luminance(reference_crop).mean())
    if not math.isfinite(mean) or mean <= 0:
        return 1.0
    return float(2.0 ** np.clip(np.round(np.log2(0.18 / mean)), 0, 4))


def magnify(image: np.ndarray, target: int = 220) -> np.ndarray:
    """Nearest-neighbour enlargement by an integer factor so the width approaches `target`."""
    k = max(1, min(16, target // max(1, image.shape[1])))
    return np.repeat(np.repeat(image, k, axis=0), k, axis=1)


# ---- page ------------------------------------------------------------------------------------


SectionBuilder = Callable[[Results, Path], str]


def _section(title: str, builder: SectionBuilder, results: Results, fig_dir: Path) -> str:
    try:
        body = builder(results, fig_dir)
    except Exception as exc:  # noqa: BLE001 - one broken section must not lose the report
        body = problem(f"This section could not be drawn: {type(exc).__name__}: {exc}")
    anchor = safe_name(title.lower())
    return f'<section id="{esc(anchor)}">\n<h2>{esc(title)}</h2>\n{body}\n</section>\n'


def write_report(out_dir: Path, results: dict[str, Any]) -> Path:
    """Writes out_dir/report.html and out_dir/figures/*.png; returns the html path."""
    out_dir = Path(out_dir)
    fig_dir = out_dir / "figures"
    fig_dir.mkdir(parents=True, exist_ok=True)
    from . import sections  # imports this module: loaded here, not at import time

    res = Results(out_dir, results if isinstance(results, dict) else {})
    builders: dict[str, SectionBuilder] = {
        "Settings": sections.settings,
        "Convergence": sections.convergence,
        "Results": sections.results_table,
        "Convergence slopes": sections.slopes_table,
        "Images": sections.image_grid,
        "Error spectra": sections.error_spectra,
        "Sample points": sections.sample_points,
        "Blue-noise texture": sections.bluenoise,
        "Hemisphere distributions": sections.hemisphere,
        "Fibonacci lattice on the hemisphere": sections.fibonacci,
    }
    scene = res.raw.get("scene") or "scene"
    toc = " · ".join(f'<a href="#{esc(safe_name(t.lower()))}">{esc(t)}</a>'
                     for t in SECTION_TITLES)
    body = "".join(_section(t, builders[t], res, fig_dir) for t in SECTION_TITLES)
    page = (
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
        f"<title>Stratum compare: {esc(Path(str(scene)).name)}</title>\n"
        f"<style>{_CSS}</style>\n</head>\n<body>\n"
        f"<h1>Stratum comparison: {esc(Path(str(scene)).name)}</h1>\n"
        f"<p>{toc}</p>\n{body}</body>\n</html>\n"
    )
    path = out_dir / "report.html"
    path.write_text(page, encoding="utf-8")
    return path


__all__ = ["SECTION_TITLES", "Results", "display_transform", "read_exr", "write_report"]
