"""Every figure of issue 15 in one table: target, measured, met or not, gathered from the JSON
the benchmark sections wrote into out/bench/ (speed.py: render, export; samplers.py;
quality.py; adaptive.py; memory.py; distributed_render.py; and issue 18's shader_nodes.py). The
last step of `make bench`.

    .venv/bin/python -m scripts.bench.summary [--results out/bench] [--out out/bench_summary.txt]

A section that did not run (no JSON) shows its figures as n/a. Each section's settings, time of
writing and load average (1, 5, 15 min) follow the table.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

from scripts import REPO
from scripts.bench.results import (
    RESULTS,
    Row,
    format_table,
    noise_mse_seconds,
    ratio,
    read_sections,
)

Section = dict[str, Any]


def render_rows(s: Section | None) -> list[Row]:
    """Target 1: path tracing <= 0.8x Cycles' time on each scene."""
    scenes = (s or {}).get("scenes", {})
    rows = []
    for name in ("cornell_box", "wolf", "materials"):
        r = scenes.get(name, {})
        st = r.get("stratum") or {}
        rows.append(Row(f"1 path tracing Stratum/Cycles, {name}", "<= 0.80x",
                        ratio(st.get("trace"), r.get("cycles", {}).get("trace")), limit=0.8))
    return rows


def embree_rows(s: Section | None) -> list[Row]:
    """Target 2: >= 0.6x the raw Embree ray rate of the same ray mix (bench.py's render)."""
    st = (s or {}).get("scenes", {}).get("cornell_box", {}).get("stratum") or {}
    return [Row("2 rays/s Stratum/raw Embree, cornell_box", ">= 0.60x",
                ratio(st.get("rays_per_s"), st.get("raw_rays_per_s")), at_least=0.6)]


def sampler_rows(s: Section | None) -> list[Row]:
    """Target 1's samplers: the Owen-scrambled ones within 5 % of random's samples/s."""
    s = s or {}
    samplers = s.get("samplers", {})
    owen = s.get("owen_scrambled", ["sobol", "zsobol", "halton_owen"])
    base = samplers.get("random", {}).get("samples_per_s")
    rows = []
    for name in owen + [n for n in samplers if n not in owen and n != "random"]:
        value = ratio(samplers.get(name, {}).get("samples_per_s"), base)
        if name in owen:
            rows.append(Row(f"1 samples/s {name}/random", ">= 0.95x", value, at_least=0.95))
        else:
            rows.append(Row(f"  samples/s {name}/random", "", value))
    return rows


def triangle_rows(s: Section | None) -> list[Row]:
    """Target 3: solid-angle triangle sampling costs <= 8 % over area sampling."""
    tri = (s or {}).get("triangle_sampling", {})
    return [Row("3 time solid-angle/area triangle sampling", "<= 1.08x",
                ratio(tri.get("solid_angle", {}).get("trace"),
                      tri.get("area", {}).get("trace")), limit=1.08)]


def quality_rows(s: Section | None) -> list[Row]:
    """Target 4: the best Stratum sampler's MSE x time <= 0.6x Cycles', every Owen-scrambled
    sampler's within 1.2x of the best's."""
    s = s or {}
    owen = s.get("owen_scrambled", ["sobol", "zsobol", "halton_owen"])
    rows = []
    for name in ("cornell_box", "wolf"):
        r = s.get("scenes", {}).get(name, {})
        base = noise_mse_seconds(r.get("cycles", {}))
        samplers = r.get("stratum", {}).get("samplers", {})
        products = {k: p for k, v in samplers.items() if (p := noise_mse_seconds(v)) is not None}
        best_name = min(products, key=products.__getitem__) if products else None
        best = products.get(best_name) if best_name else None
        rows.append(Row(f"4 MSE x time best Stratum ({best_name or '-'})/Cycles, {name}",
                        "<= 0.60x", ratio(best, base), limit=0.6))
        for sampler in owen:
            rows.append(Row(f"4 MSE x time {sampler}/best, {name}", "<= 1.20x",
                            ratio(products.get(sampler), best), limit=1.2))
        for sampler, value in products.items():
            rows.append(Row(f"  MSE x time {sampler}/Cycles, {name}", "", ratio(value, base)))
    return rows


def adaptive_rows(s: Section | None) -> list[Row]:
    """Issue 16, acceptance 4: adaptive sampling's MSE x time <= 0.7x fixed sampling's, per
    Stratum sampler, beside Cycles' own ratio (adaptive.py)."""
    rows = []
    for name in ("cornell_box", "wolf"):
        r = (s or {}).get("scenes", {}).get(name, {})
        groups = [("Cycles", r.get("cycles", {}).get("cycles", {}))]
        groups += list(r.get("stratum", {}).items())
        for who, runs in groups:
            fixed = noise_mse_seconds(runs.get("fixed", {}))
            for label, run in runs.items():
                if label == "fixed":
                    continue
                target, limit = ("", None) if who == "Cycles" else ("<= 0.70x", 0.7)
                rows.append(Row(f"16 MSE x time {label}/fixed {who}, {name}", target,
                                ratio(noise_mse_seconds(run), fixed), limit=limit))
    return rows


def export_rows(s: Section | None) -> list[Row]:
    """Target 5: Stratum's export + BVH against Cycles' whole sync."""
    cases = (s or {}).get("cases", {})
    rows = []
    for name, limit in (("monkey_1m", 0.8), ("monkey_1m_smooth", 0.8), ("instances_10k", 1.0)):
        r = cases.get(name, {})
        both = (r["export"] + r["build"]) if "export" in r and "build" in r else None
        rows.append(Row(f"5 export+BVH Stratum/Cycles sync, {name}", f"<= {limit:.2f}x",
                        ratio(both, r.get("sync_total")), limit=limit))
    return rows


def distributed_rows(s: Section | None) -> list[Row]:
    """Target 6: the merged image bit-identical; the speed-up of 2 workers over 1."""
    s = s or {}
    same = s.get("bit_identical")
    return [Row("6 cluster image bit-identical, 1 vs 2 workers", "yes",
                None if same is None else float(same), at_least=1.0, unit="yes/no"),
            Row("6 speed-up 2 local workers / 1", "(reported)",
                ratio(s.get("one_worker"), s.get("two_workers")))]


def memory_rows(s: Section | None) -> list[Row]:
    """Target 7: Stratum's peak RSS <= Cycles'; the renderers' own increase alongside."""
    cases = (s or {}).get("cases", {})
    rows = []
    for name in ("monkey_1m", "monkey_1m_smooth", "instances_10k"):
        c, st = cases.get(name, {}).get("cycles", {}), cases.get(name, {}).get("stratum", {})
        rows.append(Row(f"7 peak RSS Stratum/Cycles, {name}", "<= 1.00x",
                        ratio(st.get("after_kib"), c.get("after_kib")), limit=1.0))
        inc_c = c["after_kib"] - c["before_kib"] if c else None
        inc_s = st["after_kib"] - st["before_kib"] if st else None
        rows.append(Row(f"  RSS increase in render Stratum/Cycles, {name}", "",
                        ratio(inc_s, inc_c)))
    return rows


def shader_node_rows(s: Section | None) -> list[Row]:
    """Issue 18: a 20-node procedural material's cost per shading point <= 1.5x Cycles'
    (shader_nodes.py); both renderers' absolute costs (ns) alongside."""
    s = s or {}
    cost = s.get("cost_ns", {})
    check = s.get("agreement") or {}
    best = s.get("best", {})
    return [Row("18 node cost per point Stratum/Cycles, 20 nodes", "<= 1.50x", s.get("ratio"),
                limit=1.5),
            Row("   node cost per point, Cycles", "", cost.get("cycles"), unit="ns"),
            Row("   node cost per point, Stratum", "", cost.get("stratum"), unit="ns"),
            Row("   T_C (constant material), Cycles", "", best.get("cycles", {}).get("C"), unit="s"),
            Row("   T_C (constant material), Stratum", "", best.get("stratum", {}).get("C"),
                unit="s"),
            Row("   20-node material's channel means agree (2 %)", "",
                None if "agree" not in check else float(check["agree"]), unit="yes/no")]


BUILDERS: tuple[tuple[str, Callable[[Section | None], list[Row]]], ...] = (
    ("render", render_rows), ("samplers", sampler_rows), ("render", embree_rows),
    ("samplers", triangle_rows), ("quality", quality_rows), ("adaptive", adaptive_rows),
    ("export", export_rows), ("distributed", distributed_rows), ("memory", memory_rows),
    ("shader_nodes", shader_node_rows))

SETTINGS = ("res", "samples", "rounds", "seeds", "reference_samples", "repeats", "threads",
            "blender")


def section_note(name: str, s: Section | None) -> str:
    if s is None:
        return f"  {name}: not run (no {name}.json)"
    settings = ", ".join(f"{k} {s[k]}" for k in SETTINGS if k in s)
    load = " ".join(f"{x:.2f}" for x in s.get("load_average", []))
    return f"  {name}: {settings}; written {s.get('written', '?')}, load average {load}"


def summary(sections: dict[str, Section]) -> str:
    rows = [row for name, build in BUILDERS for row in build(sections.get(name))]
    notes = ["", "Sections (the ratios of each are taken within its one run):"]
    names = dict.fromkeys(name for name, _ in BUILDERS)
    notes += [section_note(name, sections.get(name)) for name in names]
    notes += [("Rows without a target are reported for context; the digit is the target's "
               "number in issue 15, or the issue's (16, 18).")]
    return format_table(rows, "Issue 15: every figure of `make bench`", notes)


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--results", type=Path, default=RESULTS)
    p.add_argument("--out", type=Path, default=REPO / "out" / "bench_summary.txt")
    args = p.parse_args()
    text = summary(read_sections(args.results))
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(text + "\n")
    print(text)
    print(f"written {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
