"""What the `stratum compare` report reads: the results.json document through `Results`, whose
accessors tolerate missing or null fields (missing summary or slopes are computed from the
renders), and the EXR renders it names (read_exr)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np


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
        # stratum.compare.results.series_name; results without `series` (sampler comparisons written
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
