"""`make study`: the sampler study of issue 4, regenerated from scratch into out/study/.

Every part is one `stratum compare` run into out/study/<name>/ (renders, results.json,
results.csv, report.html, figures/); compare skips configurations it has already rendered, so
re-running after an interruption only renders what is missing. Then this script reads every
results.json and writes out/study/summary.md (the headline tables: MSE ratios vs `lcg`, the
coursework's "Standard", slopes, FLIP at low spp, the AO table) and a few figures of its own
into out/study/figures/ (the AO image tables of the article, image grids with magnified
crops). docs/study.md discusses the numbers.

The runs (the source documents' experiments, with more samplers, seeds and spp):

* cornell: scenes/cornell_box.blend, every sampler, 1..128 spp (powers of two), 4 seeds,
  128x128, reference = mean of 4 sobol renders at 1024 spp (coursework: 8, 64, 128 spp);
* wolf: scenes/wolf.blend (215k triangles), every sampler, 1, 2, 4, 8 spp, 4 seeds, 320x240,
  reference 4 x 256 spp (coursework: 1, 2, 8 spp);
* ao_<hemisphere>: scenes/ao_study.blend with integrator ao, each hemisphere distribution of
  the article (uniform_angles, uniform, cosine) x {random ("pseudo-random"), fibonacci (random
  per-pixel shift = rotation about the normal), fibonacci_static (one shift for every pixel)}
  at 8, 16, 32 rays (= spp, one AO ray per sample), 4 seeds. The three runs share one
  reference (rendered by the cosine run; every estimator is unbiased, so it is the same image);
* est_small, est_large, est_glossy: the estimator ladder of issue 6 (bsdf, nee by area and by
  solid angle, mis-balance / power / max, mis-power by area, light, direct) on the Cornell box with a small light, a large light and glossy
  surfaces (estimators.py); out/study/estimators.md has their tables (MSE at
  equal samples and at equal time) and the textbook's claims checked against them;
* lights_hall: scenes/many_lights_hall.blend (1,000 lamps), light_selection tree, power,
  uniform and mixed at equal time (lights.py); out/study/lights.md, which also
  shows Cycles' light tree (out/bench/quality_lights.json) and auto's threshold
  (out/study/auto_lights.json) when `make study` has measured them.
* adaptive_<scene>_<sampler>: the Cornell box and Wolf, sobol, zsobol and random, fixed and
  adaptive sampling at equal time (adaptive.py); out/study/adaptive.md, which also
  shows Cycles' adaptive sampling (out/bench/adaptive.json) when `make bench` has measured it.
* radiosity: not a compare run: `make study` runs radiosity.py first (the three
  radiosity solvers on the diffuse Cornell box, residual against iterations and time, claim 12
  of the textbook) into out/study/radiosity.json; the summary writes out/study/radiosity.md and
  its figure from it.
* guiding: scenes/guiding_room.blend, Stratum's path tracer with and without path guiding and
  Cycles' path guiding (the bpy wheel) at equal time; not a `compare` run: guiding.py
  renders it in its own process (after the compare runs) into out/study/guiding.md.

    .venv/bin/python -m scripts.study.run [--out out/study] [--jobs 2] [--only cornell,wolf]
                                          [--quick] [--dry-run] [--summary-only]
                                          [--docs docs/study]

--quick runs the same study at toy sizes (to test the pipeline in a minute or two).

This module plans and runs the parts and holds the command line; the summary is summary.py,
the figures figures.py (the parts are in scripts/study/, beside this module).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from scripts import REPO
from scripts.study import adaptive, estimators, lights
from scripts.study.figures import export_docs, make_figures
from scripts.study.summary import AO_HEMISPHERES, AO_SAMPLERS, write_summary

AO_REFERENCE_RUN = "ao_cosine"
GUIDING = "guiding"  # guiding.py's part: not a compare Run


@dataclass
class Run:
    name: str
    scene: str
    samplers: str
    spp: list[int]
    seeds: int
    resolution: str | None = None
    reference_spp: int | None = None
    extra: list[str] = field(default_factory=list)
    reference_from: str | None = None  # the name of a run whose reference.exr this one reuses

    def command(self, out: Path, jobs: int) -> list[str]:
        cmd = [sys.executable, "-m", "stratum.cli", "compare", str(REPO / self.scene),
               "--samplers", self.samplers, "--spp", ",".join(str(s) for s in self.spp),
               "--seeds", str(self.seeds), "--out", str(out / self.name), "--jobs", str(jobs)]
        if self.resolution:
            cmd += ["--resolution", self.resolution]
        if self.reference_from is not None:
            cmd += ["--reference", str(out / self.reference_from / "renders" / "reference.exr")]
        elif self.reference_spp is not None:
            cmd += ["--reference-spp", str(self.reference_spp)]
        return cmd + self.extra


def plan_runs(quick: bool) -> list[Run]:
    if quick:
        cornell = Run("cornell", "scenes/cornell_box.blend", "lcg,halton,sobol,bluenoise",
                      [1, 2, 4], 2, "32x32", 32)
        wolf = Run("wolf", "scenes/wolf.blend", "lcg,halton,sobol,bluenoise", [1, 2], 2, "80x60",
                   16)
        ao_spp, ao_seeds, ao_res, ao_ref = [8, 16], 2, "64x48", 64
    else:
        cornell = Run("cornell", "scenes/cornell_box.blend", "all",
                      [1, 2, 4, 8, 16, 32, 64, 128], 4, "128x128", 1024)
        wolf = Run("wolf", "scenes/wolf.blend", "all", [1, 2, 4, 8], 4, None, 256)
        ao_spp, ao_seeds, ao_res, ao_ref = [8, 16, 32], 4, None, 1024
    runs = [cornell, wolf]
    # The cosine run first: it renders the reference the other two reuse.
    for hemisphere in sorted(AO_HEMISPHERES, key=lambda h: h != "cosine"):
        name = f"ao_{hemisphere}"
        runs.append(Run(name, "scenes/ao_study.blend", ",".join(AO_SAMPLERS), ao_spp, ao_seeds,
                        ao_res, ao_ref, ["--integrator", "ao", "--hemisphere", hemisphere],
                        None if name == AO_REFERENCE_RUN else AO_REFERENCE_RUN))
    return (runs + estimators.plan_runs(quick, Run) + lights.plan_runs(quick, Run)
            + adaptive.plan_runs(quick, Run))


# ---- running ---------------------------------------------------------------------------------


def run_all(runs: list[Run], out: Path, jobs: int, dry_run: bool) -> list[dict[str, Any]]:
    log: list[dict[str, Any]] = []
    for run in runs:
        cmd = run.command(out, jobs)
        print("study:", " ".join(cmd), flush=True)
        if dry_run:
            continue
        start = time.monotonic()
        # This checkout's add-on, not whichever one the venv has installed (editable).
        path = os.pathsep.join(p for p in (str(REPO / "addon"), os.environ.get("PYTHONPATH"))
                               if p)
        code = subprocess.call(cmd, cwd=REPO, env={**os.environ, "PYTHONPATH": path})
        seconds = time.monotonic() - start
        print(f"study: {run.name} finished in {seconds / 60:.1f} min (exit {code})", flush=True)
        log.append({"name": run.name, "command": cmd, "seconds": seconds, "exit_code": code})
        if code != 0:
            raise SystemExit(f"study: `stratum compare` failed for {run.name} (exit {code})")
    return log


def run_guiding(out: Path, quick: bool, dry_run: bool) -> list[dict[str, Any]]:
    """guiding.py in its own process (it needs bpy: the venv's wheel)."""
    cmd = [sys.executable, "-m", "scripts.study.guiding", "--out", str(out)]
    cmd += ["--quick"] if quick else []
    print("study:", " ".join(cmd), flush=True)
    if dry_run:
        return []
    start = time.monotonic()
    path = os.pathsep.join(p for p in (str(REPO / "addon"), os.environ.get("PYTHONPATH")) if p)
    code = subprocess.call(cmd, cwd=REPO, env={**os.environ, "PYTHONPATH": path})
    seconds = time.monotonic() - start
    print(f"study: {GUIDING} finished in {seconds / 60:.1f} min (exit {code})", flush=True)
    if code != 0:
        raise SystemExit(f"study: scripts.study.guiding failed (exit {code})")
    return [{"name": GUIDING, "command": cmd, "seconds": seconds, "exit_code": code}]


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--out", default=str(REPO / "out" / "study"))
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--only", help="comma-separated run names (cornell, wolf, ao_cosine, "
                   "est_small, est_large, est_glossy, ..., guiding)")
    p.add_argument("--quick", action="store_true", help="toy sizes, to test the pipeline")
    p.add_argument("--dry-run", action="store_true", help="print the commands only")
    p.add_argument("--summary-only", action="store_true",
                   help="no rendering: rebuild summary.md and the figures from results.json")
    p.add_argument("--docs", metavar="DIR",
                   help="also copy the figures docs/study.md shows into DIR (e.g. docs/study)")
    args = p.parse_args(argv)
    out = Path(args.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    runs = plan_runs(args.quick)
    if args.only:
        wanted = set(args.only.split(","))
        unknown = wanted - {r.name for r in runs} - {GUIDING}
        if unknown:
            p.error(f"unknown run(s) {sorted(unknown)}; runs: {[r.name for r in runs]}")
        runs = [r for r in runs if r.name in wanted]
    with_guiding = not args.only or GUIDING in args.only.split(",")
    log_path = out / "runs.json"
    previous = json.loads(log_path.read_text()) if log_path.is_file() else []
    if not args.summary_only:
        log = run_all(runs, out, args.jobs, args.dry_run)
        if with_guiding:
            log += run_guiding(out, args.quick, args.dry_run)
        if args.dry_run:
            return 0
        done = {r["name"] for r in log}
        log = [r for r in previous if r["name"] not in done] + log
        log_path.write_text(json.dumps(log, indent=1))
    else:
        log = previous
    write_summary(out, log)
    make_figures(out)
    if args.docs:
        export_docs(out, Path(args.docs))
    return 0


if __name__ == "__main__":
    sys.exit(main())
