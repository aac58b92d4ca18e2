"""Reading what `stratum compare` wrote for a run of the study: out/study/<run>/results.json and
its summary rows (mean, 95 % interval per series or sampler, spp and metric), and the number
format every page of the study prints them in. Every part of the study reads runs through
these; none of them draws or writes a page."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any


def load_results(out: Path, name: str) -> dict[str, Any] | None:
    path = out / name / "results.json"
    return json.loads(path.read_text()) if path.is_file() else None


def summary_row(results: dict[str, Any], sampler: str, spp: int,
                metric: str) -> dict[str, Any] | None:
    """The results.json summary row of metric over the seeds of (sampler, spp), if measured."""
    for row in results["summary"]:
        if row["sampler"] == sampler and row["spp"] == spp and row["metric"] == metric:
            return row
    return None


def mean_of(results: dict[str, Any], sampler: str, spp: int, metric: str) -> float | None:
    row = summary_row(results, sampler, spp, metric)
    return float(row["mean"]) if row is not None else None


def ci_of(results: dict[str, Any], sampler: str, spp: int,
          metric: str) -> tuple[float, float] | None:
    row = summary_row(results, sampler, spp, metric)
    return (float(row["ci95_low"]), float(row["ci95_high"])) if row is not None else None


def series_means(results: dict[str, Any], metric: str) -> dict[tuple[str, int], float]:
    """(series, spp) -> the mean of metric over the seeds, for every summary row of metric."""
    return {(row["series"], int(row["spp"])): float(row["mean"])
            for row in results["summary"] if row["metric"] == metric}


def fmt(x: float | None, digits: int = 3) -> str:
    """x to `digits` significant digits; '-' when not measured or not finite."""
    if x is None or not math.isfinite(x):
        return "-"
    return f"{x:.{digits}g}"
