"""The figures of `make study` (run.py), drawn from the runs' results.json into
out/study/figures/: image grids with magnified crops (as in the coursework's figures 35-38),
the AO image tables of the article, the MSE ratio to `lcg` against spp, the estimators' MSE
(estimators.py); and the copy of the figures docs/study.md shows into docs/study/.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from scripts.study import estimators
from scripts.study.plotting import pyplot, srgb8
from scripts.study.results import fmt, load_results, mean_of
from scripts.study.summary import AO_HEMISPHERES, AO_SAMPLERS, BASELINE

# Samplers shown in the image grids: the coursework's five, plus the two Sobol variants.
GRID_SAMPLERS = ("lcg", "halton", "halton_rd", "halton_owen", "bluenoise", "sobol", "zsobol")
# Magnified crops (x, y, w, h from the top left, as fractions of the image): floor regions as in
# the coursework's figures (Cornell: lower left floor; Wolf: the floor in the wolf's shadow).
CROPS = {"cornell": (0.06, 0.66, 0.31, 0.31), "wolf": (0.53, 0.62, 0.2, 0.27)}


def render_path(res: dict[str, Any], sampler: str, spp: int, seed: int = 0) -> str | None:
    for row in res["renders"]:
        if row["sampler"] == sampler and row["spp"] == spp and row["seed"] == seed:
            return str(row["path"])
    return None


def image_grid(out: Path, name: str, spp: int, gain: float = 1.0) -> Path | None:
    """Reference and each GRID_SAMPLERS render (seed 0) at spp: the full image with the crop
    marked, and the crop magnified and brightened (as in the coursework's figures 35-38)."""
    plt = pyplot()
    from matplotlib.patches import Rectangle
    from stratum.compare.exr import read_rgb

    res = load_results(out, name)
    if res is None:
        return None
    width, height = res["resolution"]
    fx, fy, fw, fh = CROPS[name]
    x, y = int(fx * width), int(fy * height)
    w, h = max(4, int(fw * width)), max(4, int(fh * height))
    columns = [("reference", res["reference"]["path"])]
    columns += [(s, render_path(res, s, spp)) for s in GRID_SAMPLERS if s in res["samplers"]]
    columns = [(label, p) for label, p in columns if p]
    fig, axes = plt.subplots(2, len(columns), figsize=(1.6 * len(columns), 3.4), squeeze=False)
    for i, (label, rel) in enumerate(columns):
        img = read_rgb(out / name / rel)
        axes[0][i].imshow(srgb8(img))
        axes[0][i].add_patch(Rectangle((x, y), w, h, fill=False, edgecolor="yellow", lw=0.8))
        axes[1][i].imshow(srgb8(gain * img[y:y + h, x:x + w]), interpolation="nearest")
        axes[0][i].set_title(label if label == "reference" else f"{label}\n{spp} spp",
                             fontsize=7)
        for ax in (axes[0][i], axes[1][i]):
            ax.set_xticks([])
            ax.set_yticks([])
    fig.suptitle(f"{name}: seed 0 at {spp} spp; bottom: crop x{gain:g} brightness", fontsize=8)
    fig.tight_layout()
    path = out / "figures" / f"{name}_grid_{spp}spp.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def ao_grids(out: Path) -> list[Path]:
    """The article's tables 2 and 3: rows = distributions with pseudo-random numbers (table 2),
    or random / fibonacci / fibonacci_static with the cosine distribution (table 3); columns =
    8, 16, 32 rays; each cell the seed-0 AO image."""
    plt = pyplot()
    from stratum.compare.exr import read_rgb

    paths: list[Path] = []
    tables = {
        "ao_table2_distributions": [(f"ao_{h}", "random", h) for h in AO_HEMISPHERES],
        "ao_table3_fibonacci": [("ao_cosine", s, s) for s in AO_SAMPLERS],
    }
    for fig_name, rows in tables.items():
        loaded = [(load_results(out, run), s, label) for run, s, label in rows]
        loaded = [(r, s, label, run) for (r, s, label), (run, _, _) in zip(loaded, rows)
                  if r is not None]
        if not loaded:
            continue
        spps = loaded[0][0]["spp"]
        fig, axes = plt.subplots(len(loaded), len(spps),
                                 figsize=(2.2 * len(spps), 1.8 * len(loaded)), squeeze=False)
        for i, (res, sampler, label, run) in enumerate(loaded):
            for j, spp in enumerate(spps):
                ax = axes[i][j]
                rel = render_path(res, sampler, spp)
                if rel is not None:
                    ax.imshow(srgb8(read_rgb(out / run / rel)), interpolation="nearest")
                mse = mean_of(res, sampler, spp, "mse")
                ax.set_title(f"{label}, {spp} rays  MSE {fmt(mse, 2)}", fontsize=6)
                ax.set_xticks([])
                ax.set_yticks([])
        fig.tight_layout()
        path = out / "figures" / f"{fig_name}.png"
        fig.savefig(path, dpi=100)
        plt.close(fig)
        paths.append(path)
    return paths


def ratio_plot(out: Path) -> Path | None:
    """MSE / MSE(lcg) vs spp for every sampler, Cornell and Wolf side by side."""
    plt = pyplot()

    runs = [(n, load_results(out, n)) for n in ("cornell", "wolf")]
    runs = [(n, r) for n, r in runs if r is not None]
    if not runs:
        return None
    fig, axes = plt.subplots(1, len(runs), figsize=(5.2 * len(runs), 3.8), squeeze=False)
    for ax, (name, res) in zip(axes[0], runs):
        colors = plt.get_cmap("tab20").colors
        for k, sampler in enumerate(res["samplers"]):
            xs, ys = [], []
            for spp in res["spp"]:
                m, b = mean_of(res, sampler, spp, "mse"), mean_of(res, BASELINE, spp, "mse")
                if m is not None and b:
                    xs.append(spp)
                    ys.append(m / b)
            style = "-" if sampler in GRID_SAMPLERS else "--"
            ax.plot(xs, ys, style, marker="osv^D<>ph*Xd"[k % 12], ms=3, label=sampler,
                    color=colors[(2 * k) % 20 + (2 * k) // 20])
        ax.axhline(0.5, color="grey", lw=0.6, ls=":")
        ax.set_xscale("log", base=2)
        ax.set_yscale("log")
        ax.set_xlabel("spp")
        ax.set_ylabel("mean MSE / mean MSE of lcg")
        ax.set_title(name)
        ax.grid(True, which="both", lw=0.3)
    axes[0][-1].legend(fontsize=6, ncol=2)
    fig.tight_layout()
    path = out / "figures" / "mse_ratio_to_lcg.png"
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def make_figures(out: Path) -> None:
    (out / "figures").mkdir(parents=True, exist_ok=True)
    made = [image_grid(out, "cornell", 8, gain=2.0), image_grid(out, "wolf", 1, gain=1.0),
            image_grid(out, "wolf", 8, gain=1.0), ratio_plot(out), *ao_grids(out),
            estimators.mse_figure(out, load_results)]
    for p in made:
        if p is not None:
            print(f"study: wrote {p}")


# The figures docs/study.md shows: (source under out/study, name under docs/study).
DOC_FIGURES = (
    ("figures/mse_ratio_to_lcg.png", "mse_ratio_to_lcg.png"),
    ("figures/cornell_grid_8spp.png", "cornell_grid_8spp.png"),
    ("figures/wolf_grid_1spp.png", "wolf_grid_1spp.png"),
    ("wolf/figures/error_spectra.png", "wolf_error_spectra.png"),
    ("wolf/figures/convergence_flip_ldr.png", "wolf_convergence_flip_ldr.png"),
    ("figures/ao_table2_distributions.png", "ao_table2_distributions.png"),
    ("figures/ao_table3_fibonacci.png", "ao_table3_fibonacci.png"),
    ("figures/estimators_mse.png", "estimators_mse.png"),
    ("est_small/figures/convergence_mse.png", "est_small_convergence_mse.png"),
    ("est_large/figures/convergence_mse.png", "est_large_convergence_mse.png"),
    ("est_glossy/figures/convergence_mse.png", "est_glossy_convergence_mse.png"),
)
DOC_MAX_BYTES = 300_000


def export_docs(out: Path, docs: Path) -> None:
    """Copies DOC_FIGURES into docs as 256-colour PNGs (each under DOC_MAX_BYTES, halving the
    size until it fits), so the repository stays small."""
    from PIL import Image

    docs.mkdir(parents=True, exist_ok=True)
    for src, name in DOC_FIGURES:
        if not (out / src).is_file():
            print(f"study: {out / src} missing, not copied")
            continue
        img = Image.open(out / src).convert("RGB")
        while True:
            img.quantize(colors=256, method=Image.Quantize.MEDIANCUT).save(
                docs / name, optimize=True)
            if (docs / name).stat().st_size <= DOC_MAX_BYTES or img.width < 400:
                break
            img = img.resize((img.width * 3 // 4, img.height * 3 // 4), Image.LANCZOS)
        print(f"study: wrote {docs / name} ({(docs / name).stat().st_size // 1000} KB)")
