"""The estimator part of `make study` (issue 6, acceptance 5): the textbook's ladder of
estimators on the Cornell box with a small light, a large light, and glossy surfaces; MSE at
equal samples and at equal time; out/study/estimators.md. run.py runs it.

| run          | scene                              | what it tests (textbook §5, digest claims) |
|--------------|------------------------------------|--------------------------------------------|
| est_small    | scenes/cornell_box.blend           | NEE wins for small lights (6); MIS gets both (8) |
| est_large    | scenes/cornell_large_light.blend   | BSDF sampling wins for large lights (7)    |
| est_glossy   | scenes/cornell_glossy.blend        | BSDF sampling wins for glossy surfaces (7) |

The ladder: path tracing with BSDF sampling only (bsdf), NEE only with the light's triangles
sampled by area as in the textbook (nee+tri-area, eq. 5.9) and by solid angle (nee, the
renderer's default: lights/emissive_triangle.h), both weighted by MIS with the balance, power and
maximum heuristics (mis-balance, mis-power, mis-max; and mis-power+tri-area), light tracing
(light, when the native registry has it: claim 11, its variance is usually higher) and direct
lighting only (direct: one bounce, a biased reference point for the NEE studies: its MSE against
the full-transport reference is mostly its missing indirect light). One sampler, `random`
(independent samples), so the variances are the textbook's and no sampler's stratification
favours one estimator. Reference: the path tracer's default (mis-power) at high spp, rendered
with sobol (its noise floor is reported).

Equal time: each estimator's mean MSE against its mean path-tracing time (trace_seconds, the
native renderer's own time) is interpolated linearly in log-log between the measured spp, at one
time budget T per scene, the largest time every unbiased estimator reached; outside an
estimator's measured times the line through its two nearest points is extended (marked *; only
below the cheapest time for an unbiased one, as T is within reach of all of them).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from scripts.study.plotting import pyplot
from scripts.study.results import fmt, series_means

LADDER: tuple[tuple[str, str], ...] = (
    ("bsdf", "path:light_sampling=bsdf"),
    ("nee+tri-area", "path:light_sampling=nee,triangle_sampling=area"),
    ("nee", "path:light_sampling=nee"),
    ("mis-balance", "path:light_sampling=mis,mis_heuristic=balance"),
    ("mis-power", "path:light_sampling=mis,mis_heuristic=power"),
    ("mis-max", "path:light_sampling=mis,mis_heuristic=max"),
    ("mis-power+tri-area", "path:light_sampling=mis,mis_heuristic=power,triangle_sampling=area"),
    ("light", "light"),
    ("direct", "direct"),
)
# The textbook's NEE (area sampling, eq. 5.9): the claims are about it.
BOOK_NEE = "nee+tri-area"
SCENES: tuple[tuple[str, str, str], ...] = (
    ("est_small", "scenes/cornell_box.blend", "small light (0.5 m quad, 1/16 of the ceiling)"),
    ("est_large", "scenes/cornell_large_light.blend",
     "large light (1.8 m quad, 81 % of the ceiling, same power)"),
    ("est_glossy", "scenes/cornell_glossy.blend",
     "small light, glossy metal floor, boxes and sphere (roughness 0.2)"),
)
SAMPLER = "random"
REFERENCE = "path"  # the path tracer's default: mis-power


def available_integrators() -> list[str]:
    from stratum import native

    return [e.name for e in native.registry("integrator")]


def ladder(integrators: list[str]) -> list[tuple[str, str]]:
    """The rungs whose integrator the native library has (light lands with chapter 6)."""
    return [(label, spec) for label, spec in LADDER if spec.split(":")[0] in integrators]


def plan_runs(quick: bool, run_type: Any) -> list[Any]:
    """The three runs as run.py's Run objects."""
    specs = ",".join(spec for _, spec in ladder(available_integrators()))
    if quick:
        spp, seeds, resolution, reference_spp = [1, 4], 2, "32x32", 64
    else:
        spp, seeds, resolution, reference_spp = [1, 4, 16, 64], 8, "64x64", 2048
    extra = ["--integrator", specs, "--reference-integrator", REFERENCE,
             "--reference-sampler", "sobol"]
    return [run_type(name, scene, SAMPLER, spp, seeds, resolution, reference_spp, list(extra))
            for name, scene, _ in SCENES]


# ---- numbers ---------------------------------------------------------------------------------


def median_errors(run_dir: Path, results: dict[str, Any]) -> dict[tuple[str, int], float]:
    """Per (series, spp): the mean over seeds of the median over pixels of the squared error
    (averaged over RGB). MSE is a mean, so a handful of fireflies can decide it; the median
    is the noise of a typical pixel, which is what the textbook's "NEE wins for small lights"
    is about (and its "fireflies" what the MSE then adds)."""
    import numpy as np
    from stratum.compare.exr import read_rgb

    reference = read_rgb(run_dir / results["reference"]["path"]).astype(np.float64)
    per: dict[tuple[str, int], list[float]] = {}
    for row in results["renders"]:
        err = ((read_rgb(run_dir / row["path"]).astype(np.float64) - reference) ** 2).mean(-1)
        per.setdefault((row["series"], int(row["spp"])), []).append(float(np.median(err)))
    return {k: float(np.mean(v)) for k, v in per.items()}


def equal_time(results: dict[str, Any], errors: dict[tuple[str, int], float] | None = None
               ) -> tuple[float, dict[str, tuple[float, bool]]]:
    """(T, {series: (error at time T, extrapolated)}): see the module doc. errors: per
    (series, spp), default the mean MSE."""
    mse = errors if errors is not None else series_means(results, "mse")
    seconds = series_means(results, "trace_seconds")
    spps = sorted(int(s) for s in results["spp"])
    curves = {s: [(seconds[(s, n)], mse[(s, n)]) for n in spps] for s in results["series"]}
    # direct is left out of the budget: it is biased, and far cheaper than full transport.
    budget = min(max(t for t, _ in pts) for s, pts in curves.items() if s != "direct")
    out: dict[str, tuple[float, bool]] = {}
    for series, pts in curves.items():
        pts = sorted(pts)
        lt = [math.log(t) for t, _ in pts]
        lm = [math.log(m) for _, m in pts]
        lb = math.log(budget)
        i = next((k for k in range(1, len(pts)) if lt[k] >= lb), len(pts) - 1)
        a, b = i - 1, i
        slope = (lm[b] - lm[a]) / (lt[b] - lt[a]) if lt[b] != lt[a] else -1.0
        out[series] = (math.exp(lm[a] + slope * (lb - lt[a])), not lt[0] <= lb <= lt[-1])
    return budget, out


def table(results: dict[str, Any], medians: dict[tuple[str, int], float]
          ) -> tuple[str, dict[str, Any]]:
    """Markdown: per series, MSE at every spp, ratio to mis-power at the largest spp, trace
    time at the largest spp, MSE at equal time and its ratio to mis-power; then the median
    pixel error (median_errors) at the largest spp and its ratios at equal spp and time."""
    spps = sorted(int(s) for s in results["spp"])
    top = spps[-1]
    mse, seconds = series_means(results, "mse"), series_means(results, "trace_seconds")
    budget, at_budget = equal_time(results)
    _, med_budget = equal_time(results, medians)
    base = "mis-power" if "mis-power" in results["series"] else results["series"][0]
    lines = ["| estimator | " + " | ".join(f"MSE {n} spp" for n in spps)
             + f" | MSE / {base} at {top} spp | path-tracing s at {top} spp"
             f" | MSE at {budget:.3g} s | MSE / {base} at equal time"
             f" | median px error {top} spp | its / {base} at equal spp | at equal time |",
             "|---|" + "---|" * (len(spps) + 7)]
    numbers: dict[str, Any] = {"equal_time_seconds": budget, "series": {}}
    for s in results["series"]:
        m_budget, extrapolated = at_budget[s]
        row = {"mse": {str(n): mse[(s, n)] for n in spps},
               "ratio_equal_spp": mse[(s, top)] / mse[(base, top)],
               "trace_seconds": seconds[(s, top)], "mse_equal_time": m_budget,
               "ratio_equal_time": m_budget / at_budget[base][0],
               "extrapolated": extrapolated,
               "median": {str(n): medians[(s, n)] for n in spps},
               "median_ratio_equal_spp": medians[(s, top)] / medians[(base, top)],
               "median_ratio_equal_time": med_budget[s][0] / med_budget[base][0]}
        numbers["series"][s] = row
        lines.append(f"| {s} | " + " | ".join(fmt(mse[(s, n)]) for n in spps)
                     + f" | {fmt(row['ratio_equal_spp'], 2)} | {fmt(seconds[(s, top)], 2)}"
                     f" | {fmt(m_budget)}{'*' if extrapolated else ''}"
                     f" | {fmt(row['ratio_equal_time'], 2)} | {fmt(medians[(s, top)])}"
                     f" | {fmt(row['median_ratio_equal_spp'], 2)}"
                     f" | {fmt(row['median_ratio_equal_time'], 2)} |")
    return "\n".join(lines), numbers


def verdicts(numbers: dict[str, dict[str, Any]]) -> list[str]:
    """One line per textbook claim, from the numbers (equal spp and equal time)."""

    def ratio(run: str, a: str, b: str, key: str) -> float | None:
        series = numbers.get(run, {}).get("series", {})
        if a not in series or b not in series:
            return None
        return series[a][key] / series[b][key]

    def say(claim: str, run: str, winner: str, loser: str) -> str:
        parts = []
        for key, what in (("ratio_equal_spp", "MSE, equal spp"),
                          ("ratio_equal_time", "MSE, equal time"),
                          ("median_ratio_equal_spp", "median px error, equal spp"),
                          ("median_ratio_equal_time", "median px error, equal time")):
            r = ratio(run, winner, loser, key)
            if r is None:
                return f"- {claim}: not measured ({run} has no {winner} or {loser})"
            parts.append(f"{winner}/{loser} = {r:.3g} ({what}: "
                         f"{'shown' if r < 1 else 'refuted'})")
        return f"- {claim} [{run}]: " + "; ".join(parts)

    lines = [say("NEE wins for small lights", "est_small", BOOK_NEE, "bsdf"),
             say("BSDF sampling wins for large lights", "est_large", "bsdf", BOOK_NEE),
             say("BSDF sampling wins for glossy surfaces", "est_glossy", "bsdf", BOOK_NEE)]
    for run in ("est_small", "est_large", "est_glossy"):
        lines.append(say("solid-angle sampling of the light's triangles beats area sampling "
                         "(NEE)", run, "nee", BOOK_NEE))
        lines.append(say("solid-angle sampling of the light's triangles beats area sampling "
                         "(MIS)", run, "mis-power", "mis-power+tri-area"))
        lines.append(say("NEE by solid angle beats BSDF sampling", run, "nee", "bsdf"))
        for rival in (BOOK_NEE, "nee", "bsdf"):
            lines.append(say(f"MIS (power) is at least as good as {rival}", run, "mis-power",
                             rival))
        lines.append(say("light tracing has higher variance than path tracing (MIS)", run,
                         "mis-power", "light"))
    return lines


def write_page(out: Path, load: Any) -> tuple[str, dict[str, Any]]:
    """out/estimators.md (the estimator page) from the runs' results.json; returns its text
    and the numbers (for headline.json)."""
    parts = ["# Estimator study: headline numbers", "",
             ("Generated by `scripts/study/run.py` (`make study`) from out/study/est_*/"
              "results.json. MSE is the mean over seeds against the reference; ratios < 1 "
              "mean the estimator beats mis-power (the path tracer's default). Equal time: "
              "MSE interpolated in log-log at the largest path-tracing time every estimator "
              "reached (* = extrapolated outside an estimator's measured times). Median "
              "px error = mean over seeds of the median over pixels of the squared error: "
              "the noise of a typical pixel, which a few fireflies cannot decide as they "
              "decide the MSE. direct is one bounce only: biased against the full-transport "
              "reference."), ""]
    numbers: dict[str, Any] = {}
    for name, scene, what in SCENES:
        res = load(out, name)
        if res is None:
            continue
        ref = res["reference"]
        parts += [(f"## {name}: {what} ({scene}, {res['resolution'][0]}x"
                   f"{res['resolution'][1]}, sampler {', '.join(res['samplers'])}, "
                   f"{len(res['seeds'])} seeds, reference {(ref.get('estimator') or {}).get('spec')}"
                   f" {ref.get('sampler')} {ref.get('spp')} spp x {len(ref.get('seeds') or [])},"
                   f" noise floor MSE {fmt((ref.get('noise_floor') or {}).get('mse'), 2)})"), ""]
        text, numbers[name] = table(res, median_errors(out / name, res))
        parts += [text, ""]
    parts += ["## The textbook's claims against these numbers", "", *verdicts(numbers), ""]
    text = "\n".join(parts)
    (out / "estimators.md").write_text(text)
    print(f"study: wrote {out / 'estimators.md'}")
    return text, numbers


def mse_figure(out: Path, load: Any) -> Path | None:
    """MSE vs spp (top) and vs path-tracing time (bottom), one column per scene."""
    plt = pyplot()

    runs = [(name, what, load(out, name)) for name, _, what in SCENES]
    runs = [(n, w, r) for n, w, r in runs if r is not None]
    if not runs:
        return None
    fig, axes = plt.subplots(2, len(runs), figsize=(4.6 * len(runs), 7.0), squeeze=False)
    colours = {label: plt.get_cmap("tab10")(k) for k, (label, _) in enumerate(LADDER)}
    for j, (name, what, res) in enumerate(runs):
        mse, seconds = series_means(res, "mse"), series_means(res, "trace_seconds")
        spps = sorted(int(s) for s in res["spp"])
        for s in res["series"]:
            ys = [mse[(s, n)] for n in spps]
            style = {"color": colours.get(s, "k"), "marker": "o", "ms": 3, "label": s}
            axes[0][j].plot(spps, ys, **style)
            axes[1][j].plot([seconds[(s, n)] for n in spps], ys, **style)
        axes[0][j].set_title(f"{name}: {what}", fontsize=8)
        axes[0][j].set_xlabel("samples per pixel")
        axes[1][j].set_xlabel("path-tracing time [s]")
        for ax in (axes[0][j], axes[1][j]):
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_ylabel("MSE")
            ax.grid(True, which="both", lw=0.3)
    axes[0][-1].legend(fontsize=7)
    fig.tight_layout()
    path = out / "figures" / "estimators_mse.png"
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=100)
    plt.close(fig)
    print(f"study: wrote {path}")
    return path
