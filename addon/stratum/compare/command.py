"""`stratum compare` itself (run_compare): the flow of the package docstring, from validated
options to results.json, results.csv and the report; one line on stderr for whatever fails."""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path
from typing import Any

from ..cli.blender_process import NOT_FOUND_MESSAGE, blender_executable
from . import plan as planning
from .options import Options, UsageError
from .plan import Config, SceneSettings
from .results import compute_results, write_results


def _fail(message: str, code: int) -> int:
    print(f"stratum compare: {message}", file=sys.stderr)
    return code


def run_compare(args: argparse.Namespace) -> int:
    from . import runner

    try:
        opts = Options(args)
        if blender_executable() is None:
            raise UsageError(NOT_FOUND_MESSAGE)
        probe = runner.probe_scene(opts.scene)
        resolution = opts.resolution or (int(probe["resolution"][0]),
                                         int(probe["resolution"][1]))
        opts.check_against(resolution)
    except UsageError as exc:
        return _fail(str(exc), 2)
    except runner.BatchError as exc:
        return _fail(f"cannot open {opts.scene} in Blender: {exc}", 2)

    try:
        estimators, reference_estimator = opts.estimators(probe)
    except UsageError as exc:
        return _fail(str(exc), 2)
    settings = SceneSettings(
        scene_sha256=planning.sha256_file(opts.scene), resolution=resolution,
        hemisphere=opts.hemisphere or str(probe["hemisphere"]),
        max_bounces=(opts.max_bounces if opts.max_bounces is not None
                     else int(probe["max_bounces"])))
    tests, refs = planning.plan(settings, estimators, opts.samplers, opts.spp, opts.seeds,
                                reference_estimator, opts.reference_sampler,
                                opts.reference_spp, opts.reference_seeds)
    out = opts.out
    try:
        (out / planning.REFERENCE_DIR).mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        return _fail(f"cannot create {out}: {exc.strerror}", 1)
    runner.remove_stale_temporaries(out)
    every = refs + tests
    pending = [c for c in every if planning.read_sidecar(out, c) is None]
    progress = runner.ProgressBar(pending, already_done=len(every) - len(pending))
    if not pending:
        print(f"stratum compare: all {len(every)} configurations already rendered",
              file=sys.stderr)
    else:
        if len(pending) < len(every):
            print(f"stratum compare: resuming: {len(every) - len(pending)} of {len(every)} "
                  "configurations already rendered", file=sys.stderr)
        progress.show()
        try:
            if opts.scheduler:
                _run_on_cluster(opts, out, settings, pending, progress)
            else:
                jobs = opts.jobs or 1
                threads = (opts.threads if opts.threads is not None
                           else max(1, (os.cpu_count() or 1) // jobs))
                batches = planning.split_batches(pending, jobs)
                runner.run_local(opts.scene, batches, settings, out, jobs, threads, progress)
        except runner.BatchError as exc:
            return _fail(str(exc), 1)
        except KeyboardInterrupt:
            return _fail("interrupted (finished configurations are kept; run again to "
                         "resume)", 130)

    try:
        results = compute_results(opts, out, settings, tests, refs, estimators,
                                  reference_estimator)
    except Exception as exc:  # noqa: BLE001 - one line, not a traceback
        return _fail(f"cannot compute the results: {type(exc).__name__}: {exc}", 1)
    write_results(out, results)
    print(f"stratum compare: wrote {out / 'results.json'} and {out / 'results.csv'}")
    return _report(out, results)


def _run_on_cluster(opts: Options, out: Path, settings: SceneSettings, pending: list[Config],
                    progress: Any) -> None:
    from . import runner

    try:
        from distributed import Client
    except ImportError as exc:
        raise runner.BatchError(f"--scheduler needs dask distributed ({exc})") from None
    try:
        client = Client(opts.scheduler, timeout="20s")
    except Exception as exc:  # noqa: BLE001 - connection errors of any kind
        raise runner.BatchError(f"cannot connect to the Dask scheduler {opts.scheduler}: "
                                f"{exc}") from None
    try:
        count = opts.jobs or max(1, sum(client.nthreads().values()))
        batches = planning.split_batches(pending, count)
        progress.current = f"{len(batches)} batches on {opts.scheduler}"
        runner.run_dask(opts.scene, batches, settings, out, client, opts.threads, progress)
    finally:
        client.close()


def _report(out: Path, results: dict[str, Any]) -> int:
    try:
        from .report import write_report
    except ModuleNotFoundError as exc:
        if exc.name == f"{__package__}.report":
            return _fail("the report module stratum/compare/report.py is missing, so no report "
                         f"was made (results.json and results.csv are in {out})", 1)
        return _fail(f"the report needs a missing module: {exc}", 1)
    path = write_report(out, results)
    print(f"stratum compare: wrote {path}")
    return 0
