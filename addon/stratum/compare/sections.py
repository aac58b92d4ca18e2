"""The sections of the `stratum compare` report: each builder takes the Results and the
figures folder, draws its figures and returns its HTML body (report.py adds the heading and
lays out the page)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from . import figures
from .report_data import Results
from .report_html import esc, fmt, img_tag, problem, safe_name
from .report_images import crop_gain, crop_region, display_transform, magnify
from .spectra import error_image, low_frequency_ratio, radial_average

METRICS: dict[str, str] = {
    "mse": "MSE",
    "rel_mse": "relative MSE",
    "flip_ldr": "mean FLIP (LDR)",
    "flip_hdr": "mean FLIP (HDR)",
}
SLOPE_KEYS: tuple[str, ...] = ("mse", "rel_mse", "flip_ldr", "flip_hdr", "mse_vs_seconds")

POINT_DIMS: tuple[tuple[int, int], ...] = ((0, 1), (3, 4), (9, 10))
POINT_COUNT = 256
HEMISPHERE_COUNTS: tuple[int, ...] = (500, 1000, 5000)
FIBONACCI_COUNTS: tuple[int, ...] = (100, 500, 1000)


def _note(text: str) -> str:
    return f'<p class="note">{text}</p>'


def _native() -> Any:
    from .. import native

    native.load_library()  # raises StratumError (shown in the section) when it is missing
    return native


def _fit(x: np.ndarray, y: np.ndarray) -> float | None:
    ok = np.isfinite(x) & np.isfinite(y) & (x > 0) & (y > 0)
    if ok.sum() < 2 or np.ptp(np.log(x[ok])) == 0:
        return None
    return float(np.polyfit(np.log(x[ok]), np.log(y[ok]), 1)[0])


# ---- tables and settings -----------------------------------------------------------------------


def settings(res: Results, _: Path) -> str:
    raw, ref = res.raw, res.reference
    floor = ref.get("noise_floor") or {}
    rows = [
        ("scene", raw.get("scene")),
        ("scene sha256", raw.get("scene_sha256")),
        ("resolution", "x".join(str(v) for v in raw.get("resolution") or []) or None),
        ("crop", raw.get("crop")),
        ("estimators", "; ".join(f"{e.get('label')} = {e.get('spec')}"
                                 for e in raw.get("estimators") or [] if isinstance(e, dict))
         or raw.get("integrator")),
        ("settings for every configuration (--set)",
         ", ".join(f"{k}={v}" for k, v in (raw.get("common_settings") or {}).items()) or None),
        ("hemisphere", raw.get("hemisphere")),
        ("max bounces", raw.get("max_bounces")),
        ("samplers", ", ".join(res.samplers)),
        ("spp", ", ".join(str(s) for s in res.spp)),
        ("seeds", ", ".join(str(s) for s in res.seeds)),
        ("reference", f"{ref.get('path', 'renders/reference.exr')} ({ref.get('source', '?')}, "
                      f"{ref.get('spp', '?')} spp, seeds {ref.get('seeds', '?')})"),
        ("reference estimator", (ref.get("estimator") or {}).get("spec")
         if isinstance(ref.get("estimator"), dict) else None),
        ("reference noise floor", f"MSE {fmt(floor.get('mse'))}, "
                                  f"relative MSE {fmt(floor.get('rel_mse'))}"),
    ]
    body = "".join(f'<tr><th class="name">{esc(k)}</th><td class="name">'
                   f'{esc("–" if v is None else v)}</td></tr>' for k, v in rows)
    return f"<table>{body}</table>"


def _cell(res: Results, sampler: str, spp: int, metric: str) -> str:
    mean, lo, hi, _ = res.stat(sampler, spp, metric)
    if not math.isfinite(mean):
        return "<td>–</td>"
    band = f" [{fmt(lo)}, {fmt(hi)}]" if math.isfinite(lo) and math.isfinite(hi) else ""
    return f"<td>{fmt(mean)}{band}</td>"


def results_table(res: Results, _: Path) -> str:
    head = ("<tr><th class=\"name\">series</th><th>spp</th><th>seeds</th>"
            + "".join(f"<th>{esc(label)} mean [95% CI]</th>" for label in METRICS.values())
            + "<th>seconds (mean)</th></tr>")
    rows = []
    for sampler in res.samplers:
        for spp in res.spp:
            n = res.stat(sampler, spp, "mse")[3]
            mark = " †" if res.below_floor(sampler, spp) else ""
            rows.append(f'<tr><td class="name">{esc(sampler)}{mark}</td><td>{spp}</td>'
                        f"<td>{n}</td>" + "".join(_cell(res, sampler, spp, m) for m in METRICS)
                        + f"<td>{fmt(res.stat(sampler, spp, 'seconds')[0])}</td></tr>")
    return (f"<table>{head}{''.join(rows)}</table>"
            + _note("Mean over seeds with its 95% confidence interval. † at least one seed's "
                    "render is below the reference noise floor (its error is dominated by the "
                    "reference's own noise)."))


def slopes_table(res: Results, _: Path) -> str:
    head = ('<tr><th class="name">series</th>'
            + "".join(f"<th>{esc(k)}</th>" for k in SLOPE_KEYS) + "</tr>")
    rows, computed = [], False
    for sampler in res.samplers:
        cells = []
        for key in SLOPE_KEYS:
            slope, here = res.slope(sampler, key)
            computed |= here and slope is not None
            cells.append(f"<td>{fmt(slope)}{'*' if here and slope is not None else ''}</td>")
        rows.append(f'<tr><td class="name">{esc(sampler)}</td>{"".join(cells)}</tr>')
    note = ("Slope of log(metric) against log(spp) (last column: log(MSE) against log(render "
            "time)). Independent random sampling gives −1 for MSE; stratified and "
            "low-discrepancy samplers reach −1.5 to −2 where the integrand allows.")
    if computed:
        note += " * fitted here from the means (results.json has no slope for it)."
    return f"<table>{head}{''.join(rows)}</table>" + _note(esc(note))


# ---- convergence -------------------------------------------------------------------------------


def convergence(res: Results, fig_dir: Path) -> str:
    spp = np.array(res.spp, dtype=float)
    parts = []
    for metric, label in METRICS.items():
        series = []
        for sampler in res.samplers:
            stats = np.array([res.stat(sampler, s, metric)[:3] for s in res.spp], dtype=float)
            seconds = np.array([res.stat(sampler, s, "seconds")[0] for s in res.spp], dtype=float)
            if stats.size == 0:
                continue
            slope_t = (res.slope(sampler, "mse_vs_seconds")[0] if metric == "mse"
                       else _fit(seconds, stats[:, 0]))
            series.append(figures.Series(
                sampler=sampler, spp=spp, seconds=seconds, mean=stats[:, 0], low=stats[:, 1],
                high=stats[:, 2],
                below_floor=np.array([res.below_floor(sampler, s, metric) for s in res.spp],
                                     dtype=bool),
                slope_spp=res.slope(sampler, metric)[0], slope_seconds=slope_t))
        path = figures.convergence_figure(fig_dir / f"convergence_{metric}.png", label, series,
                                          res.noise_floor(metric))
        parts.append(img_tag(res.out_dir, path, f"{label} vs spp and render time"))
    note = (
        "Log-log. Line and filled markers: mean over seeds; band: its 95% confidence interval; "
        "legend: fitted convergence slope. The reference is itself a Monte Carlo render, so "
        "every measured error includes the reference's own error: the dashed horizontal line "
        "is that reference noise floor (MSE and relative MSE; results.json gives none for "
        "FLIP). Hollow markers are points where at least one seed measured below the floor: "
        "there the curve is limited by the reference, not by the sampler, so read slopes "
        "above the line. A band that reaches zero or below (few seeds) runs off the bottom."
    )
    return "\n".join(parts) + _note(esc(note))


# ---- images ----------------------------------------------------------------------------------


def image_grid(res: Results, fig_dir: Path) -> str:
    ref_path = res.reference_path()
    if ref_path is None or not ref_path.is_file():
        return problem(f"The reference image {ref_path} is missing.")
    ref = res.image(ref_path)
    (x, y, w, h), how = crop_region(res, ref)
    gain = crop_gain(ref[y:y + h, x:x + w])
    out = fig_dir / "images"

    def pair(name: str, linear: np.ndarray, outline: bool = False) -> str:
        full = display_transform(linear)
        if outline:  # the crop rectangle, in red
            full = full.copy()
            x1, y1 = x + w - 1, y + h - 1
            full[[y, y1], x:x1 + 1] = (1.0, 0.0, 0.0)
            full[y:y1 + 1, [x, x1]] = (1.0, 0.0, 0.0)
        crop = magnify(display_transform(linear[y:y + h, x:x + w], gain))
        a = figures.save_image(out / f"{name}_full.png", full)
        b = figures.save_image(out / f"{name}_crop.png", crop)
        return (img_tag(res.out_dir, a, f"{name} full image")
                + img_tag(res.out_dir, b, f"{name} crop", "crop"))

    ref_cell = pair("reference", ref, outline=True)
    seed = res.first_seed
    head = ("<tr><th></th>" + "".join(f"<th>{s} spp</th>" for s in res.spp)
            + "<th>reference</th></tr>")
    rows, missing = [], []
    for sampler in res.samplers:
        cells = []
        for spp in res.spp:
            render = res.render(sampler, spp, seed)
            path = res.resolve(render.get("path")) if render else None
            if path is None or not path.is_file():
                missing.append(f"{sampler} {spp} spp")
                cells.append("<td>missing</td>")
                continue
            img = res.image(path)
            if img.shape != ref.shape:
                cells.append(f"<td>size {img.shape[1]}x{img.shape[0]} ≠ reference</td>")
                continue
            cells.append(f"<td>{pair(f'{safe_name(sampler)}_{spp}', img)}</td>")
        rows.append(f'<tr><th class="name">{esc(sampler)}</th>{"".join(cells)}'
                    f"<td>{ref_cell}</td></tr>")
    note = (f"Seed {seed}. Rows: the series (estimators and/or samplers); columns: samples "
            "per pixel; the reference on the right. Top of each cell: the full image, "
            "display-transformed (linear RGB clamped to [0, 1], then the sRGB transfer "
            "function; no tone mapping). Below: the crop "
            f"x={x}, y={y}, {w}x{h} px from the top-left corner (red box on the reference) — "
            f"{how} — magnified with nearest-neighbour pixels and brightened by ×{gain:g} "
            "(a power of two taking the reference crop's mean luminance towards 0.18; the same "
            "for every crop) before the same transform.")
    text = f'<table class="grid">{head}{"".join(rows)}</table>' + _note(esc(note))
    if missing:
        text += problem("Missing renders: " + ", ".join(missing))
    return text


def error_spectra(res: Results, fig_dir: Path) -> str:
    ref_path = res.reference_path()
    if ref_path is None or not ref_path.is_file() or not res.spp:
        return problem("No reference image or no spp: nothing to compare.")
    ref = res.image(ref_path)
    levels = sorted({res.spp[0], res.spp[-1]})
    seed = res.first_seed
    panels, ratios, tiles = [], {}, []
    bins = max(4, min(32, min(ref.shape[:2]) // 4))
    errors: dict[tuple[str, int], np.ndarray] = {}
    for spp in levels:
        curves = []
        for sampler in res.samplers:
            render = res.render(sampler, spp, seed)
            path = res.resolve(render.get("path")) if render else None
            if path is None or not path.is_file():
                continue
            img = res.image(path)
            if img.shape != ref.shape:
                continue
            err = error_image(img, ref)
            errors[(sampler, spp)] = err
            centres, power = radial_average(err, bins)
            curves.append((sampler, centres, power))
            ratios[(sampler, spp)] = low_frequency_ratio(err)
        panels.append((f"error spectrum at {spp} spp (seed {seed})", curves))
    path = figures.error_spectra_figure(fig_dir / "error_spectra.png", panels, res.samplers)
    head = ('<tr><th class="name">series</th>'
            + "".join(f"<th>low-frequency ratio, {s} spp</th>" for s in levels) + "</tr>")
    rows = "".join(f'<tr><td class="name">{esc(s)}</td>'
                   + "".join(f"<td>{fmt(ratios.get((s, spp)))}</td>" for spp in levels)
                   + "</tr>" for s in res.samplers)
    # The error images at the lowest spp, on one symmetric colour scale.
    from matplotlib import colormaps

    low = [(s, e) for (s, spp), e in errors.items() if spp == levels[0]]
    if low:
        # 99th percentile of |error|: a few fireflies must not wash out the noise pattern.
        scale = float(np.percentile(np.abs(np.stack([e for _, e in low])), 99)) or 1.0
        cmap = colormaps["RdBu_r"]
        for sampler, err in low:
            rgb = cmap(np.clip(0.5 + 0.5 * err / scale, 0.0, 1.0))[..., :3]
            p = figures.save_image(fig_dir / "errors" / f"{safe_name(sampler)}.png", rgb)
            tiles.append(f"<td>{img_tag(res.out_dir, p, f'{sampler} error')}"
                         f"{esc(sampler)}</td>")
    note = (
        "Error image = luminance (Rec. 709 weights) of render − reference, linear, first seed, "
        "over the full image (also when the metrics use a crop). "
        "Power = |DFT(error − mean)|² / pixels, averaged over rings of |f| (cycles per pixel). "
        "Low-frequency ratio = mean power within 0 &lt; |f| ≤ 1/8 (the disc |k| ≤ W/8, DC "
        "excluded) over the mean power at every f ≠ 0, as in "
        "tests/native/sampling/test_bluenoise.cpp and the zsobol test: white noise ≈ 1. "
        "Blue-noise strategies push the error to high "
        "frequencies (ratio well below 1), which the eye and FLIP forgive more than the same "
        "MSE spread as white noise. The reference's own noise adds a white floor.")
    text = (img_tag(res.out_dir, path, "radially averaged error spectra")
            + f"<table>{head}{rows}</table>" + _note(note))
    if tiles:
        text += (f"<p>Error images at {levels[0]} spp (red +, blue −, ±{fmt(scale)}: "
                 "the 99th percentile of |error|):</p>"
                 f'<table class="grid"><tr>{"".join(tiles)}</tr></table>')
    return text


# ---- sampling studies (native library, no scene) ---------------------------------------------


def sample_points(res: Results, fig_dir: Path) -> str:
    native = _native()
    known = {e.name for e in native.registry("sampler")}
    width, height = res.resolution()
    seed = res.first_seed or 0
    parts = []
    for sampler in res.sampler_names:
        if sampler not in known:
            parts.append(problem(f"{sampler}: not in the native sampler registry"))
            continue
        panels = []
        for dims in POINT_DIMS:
            xy = native.sampler_points(sampler, POINT_COUNT, seed, width, height, (0, 0), dims,
                                       POINT_COUNT)
            panels.append((xy, dims, (native.dimension_name(dims[0]),
                                      native.dimension_name(dims[1]))))
        path = figures.point_set_figure(
            fig_dir / "points" / f"{safe_name(sampler)}.png", sampler, panels,
            f"{POINT_COUNT} samples of pixel (0, 0), {POINT_COUNT} spp, seed {seed}")
        parts.append(img_tag(res.out_dir, path, f"{sampler} sample points"))
    note = (f"The first {POINT_COUNT} samples one pixel receives, as in a {width}x{height} render "
            f"at {POINT_COUNT} spp, in dimensions (0, 1), (3, 4) and (9, 10), with marginal "
            "histograms (stratum.native.sampler_points). (3, 4) straddles two of the sampler's "
            "pairs, so it shows how independent neighbouring dimensions are.")
    return "\n".join(parts) + _note(esc(note))


def bluenoise(res: Results, fig_dir: Path) -> str:
    texture = _native().bluenoise_texture()
    centres, radial = radial_average(texture, 32)
    ratio = low_frequency_ratio(texture)
    path = figures.bluenoise_figure(fig_dir / "bluenoise_texture.png", texture, centres, radial,
                                    ratio)
    note = ("The `bluenoise` sampler's 128x128 void-and-cluster rank texture, (rank + 0.5)/16384 "
            "(stratum_bluenoise_texture), its power spectrum and its radial average. Little "
            f"power at low frequencies: low-frequency ratio {ratio:.4f} (white noise ≈ 1).")
    return img_tag(res.out_dir, path, "blue-noise texture and spectrum") + _note(esc(note))


def _bsdf_pair(native: Any) -> tuple[int, int]:
    """The dimension pair of the first bounce's BSDF direction (what diffuse bounces read)."""
    first = native.camera_dimensions()
    for d in range(first, first + native.bounce_dimension_stride()):
        if native.dimension_name(d) == "bounce0.bsdf.u":
            return d, d + 1
    return 0, 1


def _warped_points_figure(res: Results, fig_dir: Path, sampler: str, counts: Sequence[int],
                          file_name: str, title: str) -> tuple[Path, tuple[int, int], int]:
    """fig_dir/file_name: for each hemisphere distribution, the sampler's first n points (each
    n of counts) of one pixel of a 1x1 image at n spp, in the dimensions of the first bounce's
    BSDF direction, mapped through the distribution. Returns (path, dimensions, seed)."""
    native = _native()
    dims = _bsdf_pair(native)
    seed = res.first_seed or 0
    rows = []
    for distribution in (e.name for e in native.registry("hemisphere")):
        sets = []
        for n in counts:
            uv = native.sampler_points(sampler, n, seed, 1, 1, (0, 0), dims, n)
            sets.append((n, native.warp_hemisphere(distribution, uv)[0]))
        rows.append((distribution, sets))
    return figures.hemisphere_figure(fig_dir / file_name, title, rows), dims, seed


def hemisphere(res: Results, fig_dir: Path) -> str:
    path, dims, seed = _warped_points_figure(
        res, fig_dir, "random", HEMISPHERE_COUNTS, "hemisphere_random.png",
        "random points mapped through each distribution")
    names = [_native().dimension_name(d) for d in dims]
    note = ("Points of the sampler `random` (dimensions "
            f"{dims[0]}, {dims[1]}: {names[0]}, {names[1]}; seed {seed}) mapped by each hemisphere "
            "distribution, as in the article's figures 2–4: top view = projection onto the "
            "tangent plane, side view = (x, z). uniform_angles crowds at the pole, uniform "
            "(sine) covers the hemisphere evenly, cosine thins out towards the horizon.")
    return img_tag(res.out_dir, path, "hemisphere distributions") + _note(esc(note))


def fibonacci(res: Results, fig_dir: Path) -> str:
    path, _, seed = _warped_points_figure(
        res, fig_dir, "fibonacci_static", FIBONACCI_COUNTS, "hemisphere_fibonacci.png",
        "Fibonacci lattice mapped through each distribution")
    note = ("The article's table 1: the Fibonacci lattice (frac((j+1)/φ), (j+0.5)/n) of "
            "the sampler `fibonacci_static` with n = spp points, mapped through each "
            "distribution. The sampler shifts the lattice toroidally by a per-seed offset "
            f"(seed {seed}), which moves the points but keeps their even spacing.")
    return img_tag(res.out_dir, path, "Fibonacci lattice on the hemisphere") + _note(esc(note))
