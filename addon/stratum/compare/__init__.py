"""`stratum compare`: render a scene with several estimators, samplers, sample counts and seeds
through Blender, compare every render with a reference, and write results.json, results.csv and
the report (stratum.compare.report.write_report).

Estimators (--integrator, a list of specs such as `path:light_sampling=bsdf`; estimators.py)
are an axis like samplers: configurations are estimator x sampler x spp x seed. Each
(estimator, sampler) pair is one series of the tables and plots, named by the estimator's label
when several estimators are compared with one sampler, by the sampler when one estimator is
compared with several samplers (the sampler study), and `label/sampler` when both vary.

Flow: validate every argument (nothing is written before that succeeds) -> open the scene in
Blender once to read its resolution and Stratum settings -> plan configurations and skip the
ones already rendered (plan.py: cache key = scene sha256 + settings + seed) -> render the rest
in batches (runner.py: local Blender processes or a Dask cluster) -> reference = mean of the
reference renders, with its noise floor (or the given EXR) -> metrics per render, 95 %
intervals over seeds, log-log slopes (metrics.py) -> results.json / results.csv -> report.

Times: "seconds" is the wall time of Blender's render call (export + BVH + path tracing) in a
process that may share the CPU with --jobs - 1 others; "trace_seconds" is the path tracing
alone. Both depend on --jobs and --threads; images do not (bit-identical for any thread count).

Modules by job: options.py (add_arguments, validation into Options), command.py (run_compare),
results.py (results.json / results.csv), plan.py, runner.py and blender_batch.py (rendering),
metrics.py, estimators.py, exr.py, and the report (report.py and the modules it names).
`from stratum.compare import add_arguments, run_compare` stays light: no numpy, Dask, OpenEXR
or FLIP is imported before a comparison runs.
"""

from __future__ import annotations

from .command import run_compare
from .options import (
    DEFAULT_REFERENCE_RENDERS,
    DEFAULT_SEEDS,
    DEFAULT_SPP,
    Options,
    UsageError,
    add_arguments,
)
from .results import CSV_COLUMNS, METRICS, compute_results, series_name

__all__ = ["CSV_COLUMNS", "DEFAULT_REFERENCE_RENDERS", "DEFAULT_SEEDS", "DEFAULT_SPP", "METRICS",
           "Options", "UsageError", "add_arguments", "compute_results", "run_compare",
           "series_name"]
