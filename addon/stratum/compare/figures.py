"""Matplotlib figures of the `stratum compare` report (PNG, Agg backend, dpi 100).

matplotlib is imported inside the functions, so importing this module (and stratum.cli) stays
fast and works where matplotlib is missing until a report is written.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

DPI = 100


def _pyplot() -> Any:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _colours(names: Sequence[str]) -> dict[str, Any]:
    plt = _pyplot()
    cmap = plt.get_cmap("tab10" if len(names) <= 10 else "tab20")
    return {name: cmap(i % cmap.N) for i, name in enumerate(names)}


def _save(fig: Any, path: Path) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=DPI)
    _pyplot().close(fig)
    return path


def save_image(path: Path, rgb: np.ndarray) -> Path:
    """Writes an (H, W, 3) display-referred image with values in [0, 1] as an 8-bit PNG."""
    from matplotlib import image as mpimg

    path.parent.mkdir(parents=True, exist_ok=True)
    mpimg.imsave(path, np.clip(rgb, 0.0, 1.0).astype(np.float32))
    return path


# ---- convergence ----------------------------------------------------------------------------


@dataclass
class Series:
    """One sampler's curve: per spp the mean over seeds, its 95% interval, the mean render
    time and whether any seed's render was below the reference's noise floor."""

    sampler: str
    spp: np.ndarray
    seconds: np.ndarray
    mean: np.ndarray
    low: np.ndarray
    high: np.ndarray
    below_floor: np.ndarray
    slope_spp: float | None = None
    slope_seconds: float | None = None
    extra: dict[str, Any] = field(default_factory=dict)


def _fmt_slope(slope: float | None) -> str:
    return "n/a" if slope is None or not np.isfinite(slope) else f"{slope:+.2f}"


def convergence_figure(path: Path, metric_label: str, series: Sequence[Series],
                       noise_floor: float | None) -> Path:
    """Two log-log panels, metric vs spp and vs render time: mean over seeds (line), 95%
    interval band, hollow markers where a seed fell below the reference noise floor, and the
    noise floor as a dashed horizontal line."""
    plt = _pyplot()
    colours = _colours([s.sampler for s in series])
    from matplotlib.ticker import LogLocator, NullFormatter, StrMethodFormatter

    fig, axes = plt.subplots(1, 2, figsize=(11.0, 4.4), constrained_layout=True)
    # y range from the means, the positive interval ends and the floor; a band that reaches
    # zero or below (few seeds) runs off the bottom instead of stretching the axis.
    ys_all = [v for s in series for v in (*s.mean, *s.high, *s.low)
              if np.isfinite(v) and v > 0]
    ys_all = [v for v in ys_all if v >= 0.01 * min((m for s in series for m in s.mean
                                                      if np.isfinite(m) and m > 0), default=v)]
    if noise_floor is not None and np.isfinite(noise_floor) and noise_floor > 0:
        ys_all.append(noise_floor)
    for ax, against in zip(axes, ("spp", "seconds"), strict=True):
        for s in series:
            x = s.spp if against == "spp" else s.seconds
            ok = np.isfinite(x) & (x > 0) & np.isfinite(s.mean) & (s.mean > 0)
            if not ok.any():
                continue
            c = colours[s.sampler]
            order = np.argsort(x[ok])
            xs, ys = x[ok][order], s.mean[ok][order]
            floor_of_band = ys * 1e-6
            lo = np.maximum(np.nan_to_num(s.low[ok][order], nan=0.0), floor_of_band)
            hi = np.maximum(np.nan_to_num(s.high[ok][order], nan=0.0), ys)
            slope = s.slope_spp if against == "spp" else s.slope_seconds
            ax.plot(xs, ys, "-", color=c, lw=1.4, label=f"{s.sampler} (slope {_fmt_slope(slope)})")
            ax.fill_between(xs, lo, hi, color=c, alpha=0.18, lw=0)
            below = s.below_floor[ok][order]
            ax.plot(xs[~below], ys[~below], "o", color=c, ms=5)
            ax.plot(xs[below], ys[below], "o", mfc="none", mec=c, mew=1.4, ms=7)
        if noise_floor is not None and np.isfinite(noise_floor) and noise_floor > 0:
            ax.axhline(noise_floor, color="0.3", ls="--", lw=1.0,
                       label="reference noise floor")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.xaxis.set_minor_formatter(NullFormatter())
        if against == "seconds":  # 1-2-5 ticks, plain numbers
            ax.xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
            ax.xaxis.set_major_formatter(StrMethodFormatter("{x:g}"))
        if ys_all:
            ax.set_ylim(min(ys_all) / 1.5, max(ys_all) * 1.5)
        if against == "spp" and series:  # label the measured spp, not powers of ten
            ticks = sorted({float(v) for s in series for v in s.spp if v > 0})
            ax.set_xticks(ticks, [f"{v:g}" for v in ticks])
            ax.set_xticks([], minor=True)
        ax.set_xlabel("samples per pixel" if against == "spp" else "render time [s]")
        ax.set_ylabel(metric_label)
        ax.grid(True, which="both", alpha=0.25)
        ax.set_title(f"{metric_label} vs {'spp' if against == 'spp' else 'render time'}")
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7, loc="best")
    return _save(fig, path)


# ---- point sets -------------------------------------------------------------------------------


def _scatter_with_marginals(fig: Any, cell: Any, xy: np.ndarray, xlabel: str,
                            ylabel: str, colour: Any) -> None:
    grid = cell.subgridspec(2, 2, width_ratios=[4, 1], height_ratios=[1, 4], wspace=0.1,
                            hspace=0.1)
    main = fig.add_subplot(grid[1, 0])
    top = fig.add_subplot(grid[0, 0], sharex=main)
    right = fig.add_subplot(grid[1, 1], sharey=main)
    n = len(xy)
    bins = max(8, min(32, int(np.sqrt(max(n, 1)))))
    main.scatter(xy[:, 0], xy[:, 1], s=max(1.0, min(10.0, 2500.0 / max(n, 1))), color=colour,
                 linewidths=0)
    main.set_xlim(0.0, 1.0)
    main.set_ylim(0.0, 1.0)
    main.set_aspect("equal", adjustable="box")
    main.set_xlabel(xlabel, fontsize=8)
    main.set_ylabel(ylabel, fontsize=8)
    main.tick_params(labelsize=7)
    top.hist(xy[:, 0], bins=bins, range=(0.0, 1.0), color=colour, alpha=0.7)
    right.hist(xy[:, 1], bins=bins, range=(0.0, 1.0), orientation="horizontal", color=colour,
               alpha=0.7)
    top.tick_params(labelbottom=False, labelsize=6)
    right.tick_params(labelleft=False, labelsize=6)


def point_set_figure(path: Path, sampler: str,
                     panels: Sequence[tuple[np.ndarray, tuple[int, int], tuple[str, str]]],
                     note: str) -> Path:
    """One row of scatter plots with marginal histograms, one per dimension pair."""
    plt = _pyplot()
    fig = plt.figure(figsize=(4.0 * len(panels), 4.3))
    outer = fig.add_gridspec(1, len(panels), wspace=0.3)
    for i, (xy, dims, names) in enumerate(panels):
        _scatter_with_marginals(fig, outer[0, i], xy, f"dim {dims[0]} ({names[0]})",
                                f"dim {dims[1]} ({names[1]})", "tab:blue")
    fig.suptitle(f"{sampler}: {note}", fontsize=10)
    return _save(fig, path)


def bluenoise_figure(path: Path, texture: np.ndarray, centres: np.ndarray,
                     radial: np.ndarray, ratio: float) -> Path:
    """The texture, its (shifted, log) power spectrum, and the radially averaged spectrum."""
    from .spectra import power_spectrum

    plt = _pyplot()
    fig, axes = plt.subplots(1, 3, figsize=(12.0, 4.0), constrained_layout=True)
    axes[0].imshow(texture, cmap="gray", vmin=0.0, vmax=1.0, interpolation="nearest")
    axes[0].set_title(f"void-and-cluster texture {texture.shape[1]}x{texture.shape[0]}")
    power = np.fft.fftshift(power_spectrum(texture))
    h, w = texture.shape
    power[h // 2, w // 2] = np.nan  # the (removed) DC term
    axes[1].imshow(np.log10(power + 1e-12), cmap="magma", interpolation="nearest",
                   extent=(-0.5, 0.5, -0.5, 0.5))
    axes[1].set_title("power spectrum (log10), DC at centre")
    axes[1].set_xlabel("f_x [cycles/pixel]")
    axes[1].set_ylabel("f_y [cycles/pixel]")
    axes[2].plot(centres, radial, "-o", ms=3, color="tab:blue")
    axes[2].axhline(np.var(texture), color="0.4", ls="--", lw=1, label="white noise, same variance")
    axes[2].axvline(1 / 8, color="tab:red", ls=":", lw=1, label="|f| = 1/8 (W/8)")
    axes[2].set_yscale("log")
    axes[2].set_xlabel("|f| [cycles/pixel]")
    axes[2].set_ylabel("mean power")
    axes[2].set_title(f"radial average; low-frequency ratio {ratio:.2g}")
    axes[2].legend(fontsize=7)
    axes[2].grid(True, which="both", alpha=0.25)
    return _save(fig, path)


# ---- hemisphere -------------------------------------------------------------------------------


def hemisphere_figure(path: Path, title: str,
                      rows: Sequence[tuple[str, Sequence[tuple[int, np.ndarray]]]],
                      side_view: bool = True) -> Path:
    """rows: (distribution, [(n, unit vectors (n, 3))]). Per point set, the projection onto
    the tangent plane (x, y) and, if side_view, the side view (x, z)."""
    plt = _pyplot()
    n_cols = max(len(sets) for _, sets in rows) * (2 if side_view else 1)
    fig = plt.figure(figsize=(2.3 * n_cols, 2.5 * len(rows)), constrained_layout=True)
    axes = fig.subplots(len(rows), n_cols, squeeze=False)
    theta = np.linspace(0.0, 2.0 * np.pi, 200)
    for r, (distribution, sets) in enumerate(rows):
        for j, (n, xyz) in enumerate(sets):
            size = max(0.3, min(6.0, 1500.0 / max(n, 1)))
            ax = axes[r, j * (2 if side_view else 1)]
            ax.scatter(xyz[:, 0], xyz[:, 1], s=size, color="tab:blue", linewidths=0)
            ax.plot(np.cos(theta), np.sin(theta), color="0.6", lw=0.7)
            ax.set_xlim(-1.05, 1.05)
            ax.set_ylim(-1.05, 1.05)
            ax.set_aspect("equal")
            ax.set_xticks([])
            ax.set_yticks([])
            ax.set_title(f"{distribution}, n={n}: top", fontsize=8)
            if side_view:
                side = axes[r, j * 2 + 1]
                side.scatter(xyz[:, 0], xyz[:, 2], s=size, color="tab:orange", linewidths=0)
                side.plot(np.cos(theta[:100]), np.sin(theta[:100]), color="0.6", lw=0.7)
                side.set_xlim(-1.05, 1.05)
                side.set_ylim(-0.05, 1.05)
                side.set_aspect("equal")
                side.set_xticks([])
                side.set_yticks([])
                side.set_title("side (x, z)", fontsize=8)
        for k in range(len(sets) * (2 if side_view else 1), n_cols):
            axes[r, k].axis("off")
    fig.suptitle(title, fontsize=10)
    return _save(fig, path)


# ---- error spectra ----------------------------------------------------------------------------


def error_spectra_figure(path: Path,
                         panels: Sequence[tuple[str, Sequence[tuple[str, np.ndarray, np.ndarray]]]],
                         samplers: Sequence[str]) -> Path:
    """panels: (title, [(sampler, ring centres, mean power)]): one log-scale panel each."""
    plt = _pyplot()
    colours = _colours(list(samplers))
    fig, axes = plt.subplots(1, max(1, len(panels)), figsize=(5.5 * max(1, len(panels)), 4.2),
                             constrained_layout=True, squeeze=False)
    for ax, (title, curves) in zip(axes[0], panels, strict=False):
        for sampler, centres, power in curves:
            ok = np.isfinite(power) & (power > 0)
            ax.plot(centres[ok], power[ok], "-", lw=1.3, color=colours.get(sampler, "k"),
                    label=sampler)
        ax.axvline(1 / 8, color="0.4", ls=":", lw=1, label="|f| = 1/8 (W/8)")
        ax.set_yscale("log")
        ax.set_xlabel("|f| [cycles/pixel]")
        ax.set_ylabel("mean error power (luminance)")
        ax.set_title(title)
        ax.grid(True, which="both", alpha=0.25)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7)
    return _save(fig, path)
