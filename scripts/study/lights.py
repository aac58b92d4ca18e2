"""The light-selection part of `make study` (issue 16, item 4 and acceptance 4): tree vs power
vs uniform vs mixed selection on the many-light hall at equal time, against Cycles' light tree;
out/study/lights.md. run.py runs it.

| run         | scene                           | what it tests                                  |
|-------------|---------------------------------|------------------------------------------------|
| lights_hall | scenes/many_lights_hall.blend   | 1,000 small lamps: the tree's MSE at equal time |
|             |                                 | <= 0.2x power selection's                      |

The run is one `stratum compare` over the four light_selection values of the path tracer and
the tree without splitting (sampler sobol; reference: the default, auto = the tree in this
scene, at high spp). Equal time as in estimators.py (MSE interpolated in log-log at the largest
path-tracing time every mode reached). Two more measurements, run by `make study` outside
`compare`, are read when present:

* Cycles 5.0 with its light tree (the bpy wheel) and Stratum's modes at equal time, noise MSE
  x path-tracing seconds each against its own reference (scripts/bench/quality.py
  --section quality_lights): out/bench/quality_lights.json;
* the threshold of light_selection auto (auto_lights.py): out/study/auto_lights.json.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from scripts import REPO
from scripts.bench.results import noise_mse_seconds
from scripts.study.estimators import equal_time
from scripts.study.results import fmt, series_means

RUN = "lights_hall"
SCENE = "scenes/many_lights_hall.blend"
# light_selection values; tree:1 is the tree without splitting (light_tree_splits 1), tree alone
# the library's default of 8 cut nodes.
SELECTIONS = ("tree", "tree:1", "power", "uniform", "mixed")
SAMPLER = "sobol"
BASE = "power"  # the acceptance's yardstick: tree <= 0.2x power at equal time
QUALITY_LIGHTS = REPO / "out" / "bench" / "quality_lights.json"


def series(selection: str) -> str:
    """The compare label of the path tracer's default estimator with `selection`."""
    name, _, splits = selection.partition(":")
    return f"mis-power+sel-{name}" + (f"+split{splits}" if splits else "")


def spec(selection: str) -> str:
    """The compare --integrator spec of `selection` (SELECTIONS' syntax)."""
    name, _, splits = selection.partition(":")
    return f"path:light_selection={name}" + (f",light_tree_splits={splits}" if splits else "")


def plan_runs(quick: bool, run_type: Any) -> list[Any]:
    """The hall run as a run.py Run."""
    if quick:
        spp, seeds, resolution, reference_spp = [1, 4], 2, "48x27", 32
    else:
        spp, seeds, resolution, reference_spp = [1, 4, 16, 64], 4, "160x90", 2048
    specs = ",".join(spec(s) for s in SELECTIONS)
    extra = ["--integrator", specs, "--reference-integrator", "path", "--reference-sampler", SAMPLER]
    return [run_type(RUN, SCENE, SAMPLER, spp, seeds, resolution, reference_spp, extra)]


def hall_table(res: dict[str, Any]) -> tuple[list[str], dict[str, Any]]:
    spps = sorted(int(s) for s in res["spp"])
    mse, seconds = series_means(res, "mse"), series_means(res, "trace_seconds")
    budget, at_budget = equal_time(res)
    base = at_budget[series(BASE)][0]
    lines = ["| selection | " + " | ".join(f"MSE {n} spp" for n in spps)
             + f" | path-tracing s at {spps[-1]} spp | MSE at {budget:.3g} s | / {BASE} |",
             "|---|" + "---|" * (len(spps) + 3)]
    numbers: dict[str, Any] = {"equal_time_seconds": budget, "series": {}}
    for sel in SELECTIONS:
        s = series(sel)
        if s not in res["series"]:
            continue
        m, extrapolated = at_budget[s]
        numbers["series"][sel] = {"mse": {str(n): mse[(s, n)] for n in spps},
                                  "trace_seconds": seconds[(s, spps[-1])], "mse_equal_time": m,
                                  "ratio_to_power": m / base, "extrapolated": extrapolated}
        lines.append(f"| {sel} | " + " | ".join(fmt(mse[(s, n)]) for n in spps)
                     + f" | {fmt(seconds[(s, spps[-1])], 3)} | {fmt(m)}{'*' if extrapolated else ''}"
                     f" | {fmt(m / base, 3)} |")
    return lines, numbers


def cycles_lines(path: Path) -> tuple[list[str], dict[str, Any]]:
    if not path.is_file():
        return [(f"(not measured: {path} is missing; `make study` runs "
                 "python -m scripts.bench.quality --section quality_lights under the bpy "
                 "wheel)")], {}
    data = json.loads(path.read_text())
    hall = data["scenes"].get("many_lights_hall")
    if hall is None:
        return [f"({path} holds no many_lights_hall)"], {}
    cyc, st = hall["cycles"], hall["stratum"]["samplers"]
    base = noise_mse_seconds(cyc)
    lines = [(f"{data['res']}x{data['res']}, {data['samples']} spp, {data['seeds']} seeds, "
              f"references of {data['reference_samples']} spp; Cycles {cyc.get('blender', '?')}, "
              f"light tree {'on' if cyc.get('light_tree') else 'absent'}."), "",
             "| renderer | noise MSE | path-tracing s | MSE x s | / Cycles | light tree build |",
             "|---|---|---|---|---|---|",
             f"| Cycles | {fmt(cyc['noise_mse'])} | {fmt(cyc['seconds'], 3)} | {fmt(base)} | 1 | |"]
    numbers: dict[str, Any] = {"cycles_mse_x_seconds": base, "stratum": {}}
    for label, r in st.items():
        product = noise_mse_seconds(r)
        numbers["stratum"][label] = {"mse_x_seconds": product, "ratio_to_cycles": product / base}
        build = (f"{r['light_tree_seconds'] * 1e3:.1f} ms, {r['light_tree_bytes'] / 1e6:.2f} MB"
                 if r.get("light_tree_bytes") else "")
        lines.append(f"| Stratum {label} | {fmt(r['noise_mse'])} | {fmt(r['seconds'], 3)} | "
                     f"{fmt(product)} | {fmt(product / base, 3)} | {build} |")
    return lines, numbers


def auto_lines(path: Path) -> tuple[list[str], dict[str, Any]]:
    if not path.is_file():
        return [f"(not measured: {path} is missing; run python -m scripts.study.auto_lights)"], {}
    data = json.loads(path.read_text())
    lines = [(f"{data['size'][0]}x{data['size'][1]}, {data['spp']} spp, {data['seeds']} seeds, "
              f"path max_bounces 2; MSE x s of tree over mixed (< 1: the tree wins)."), "",
             "| layout | " + " | ".join(str(r["lamps"]) for r in data["rows"]
                                        if r["layout"] == data["rows"][0]["layout"]) + " |"]
    layouts = list(dict.fromkeys(r["layout"] for r in data["rows"]))
    lines.append("|---|" + "---|" * (len(lines[-1].split("|")) - 3))
    for layout in layouts:
        lines.append(f"| {layout} | " + " | ".join(fmt(r["tree_over_mixed"], 3)
                                                   for r in data["rows"] if r["layout"] == layout)
                     + " |")
    return lines, data


def write_page(out: Path, load: Any) -> tuple[str, dict[str, Any]]:
    """out/lights.md from the hall run's results.json and the two measurements above; returns
    its text and the numbers (for headline.json)."""
    parts = ["# Light selection study (issue 16)", "",
             ("Generated by `scripts/study/run.py` (`make study`). MSE is the mean over seeds "
              "against the reference; equal time: MSE interpolated in log-log at the largest "
              "path-tracing time every mode reached (* = extrapolated)."), ""]
    numbers: dict[str, Any] = {}
    res = load(out, RUN)
    if res is not None:
        ref = res["reference"]
        parts += [(f"## {RUN}: {SCENE}, {res['resolution'][0]}x{res['resolution'][1]}, sampler "
                   f"{', '.join(res['samplers'])}, {len(res['seeds'])} seeds, reference "
                   f"{(ref.get('estimator') or {}).get('spec')} {ref.get('sampler')} "
                   f"{ref.get('spp')} spp"), ""]
        lines, numbers["hall"] = hall_table(res)
        parts += [*lines, ""]
    lines, numbers["cycles"] = cycles_lines(QUALITY_LIGHTS)
    parts += ["## Against Cycles' light tree at equal time", "", *lines, ""]
    lines, numbers["auto"] = auto_lines(out / "auto_lights.json")
    parts += ["## Where the tree stops losing to mixed (light_selection auto)", "", *lines, ""]
    text = "\n".join(parts)
    (out / "lights.md").write_text(text)
    print(f"study: wrote {out / 'lights.md'}")
    return text, numbers
