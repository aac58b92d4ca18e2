"""The pure half of the benchmark scripts (no bpy): each section's JSON in out/bench/, the
noise measure of the equal-time section, and the rows of the summary table."""

from __future__ import annotations

import json
import os
import time
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from scripts import REPO

RESULTS = REPO / "out" / "bench"


def write_section(name: str, data: dict[str, Any], directory: Path = RESULTS) -> Path:
    """Writes one section's figures to <directory>/<name>.json with the load average and time
    of writing, which the summary quotes."""
    directory.mkdir(parents=True, exist_ok=True)
    path = directory / f"{name}.json"
    record = {"section": name, "written": time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime()),
              "load_average": list(os.getloadavg()), **data}
    path.write_text(json.dumps(record, indent=1, sort_keys=True) + "\n")
    return path


def read_sections(directory: Path = RESULTS) -> dict[str, dict[str, Any]]:
    """Every section's JSON in `directory`, by section name."""
    if not directory.is_dir():
        return {}
    return {p.stem: json.loads(p.read_text()) for p in sorted(directory.glob("*.json"))}


def vm_hwm_kib(status: str) -> int:
    """VmHWM (peak resident set size, KiB) from the text of /proc/<pid>/status."""
    for line in status.splitlines():
        if line.startswith("VmHWM:"):
            fields = line.split()
            if len(fields) != 3 or fields[2] != "kB":
                raise ValueError(f"unexpected VmHWM line: {line!r}")
            return int(fields[1])
    raise ValueError("no VmHWM line in the status text")


# ---- noise of an image against its renderer's own reference -----------------------------------


def mse(image: np.ndarray, reference: np.ndarray) -> float:
    """Mean over pixels and channels of the squared difference."""
    if image.shape != reference.shape:
        raise ValueError(f"mse: shapes differ, {image.shape} vs {reference.shape}")
    d = np.asarray(image, dtype=np.float64) - np.asarray(reference, dtype=np.float64)
    return float(np.mean(d * d))


def reference_noise(half_a: np.ndarray, half_b: np.ndarray) -> float:
    """The mean per-pixel variance of the reference (half_a + half_b) / 2, from two halves
    rendered with independent seeds: E(a - b)^2 = 2 Var(half) and Var(reference) = Var(half)/2,
    so Var(reference) = E(a - b)^2 / 4."""
    return mse(half_a, half_b) / 4.0


def noise_mse(image: np.ndarray, half_a: np.ndarray, half_b: np.ndarray) -> float:
    """The image's own noise: its MSE against the reference (the mean of two independent
    halves) less the reference's variance. For an image independent of the reference and an
    unbiased renderer, E(image - reference)^2 = Var(image) + Var(reference) per pixel, so the
    difference estimates Var(image) without the reference's own noise (at 2048 against 64
    samples about 1/32 of the result for plain Monte Carlo)."""
    reference = (np.asarray(half_a, dtype=np.float64) + np.asarray(half_b, dtype=np.float64)) / 2
    return mse(image, reference) - reference_noise(half_a, half_b)


def noise_mse_seconds(run: dict[str, Any]) -> float | None:
    """A run's noise MSE x seconds (None when either is missing): for an unbiased renderer MSE
    falls as 1/time, so the ratio of two runs' products is their MSE ratio at equal time (exactly
    for plain Monte Carlo; low-discrepancy samplers' MSE falls faster, favouring the longer)."""
    if "noise_mse" not in run or "seconds" not in run:
        return None
    return run["noise_mse"] * run["seconds"]


# ---- the summary table ---------------------------------------------------------------------------


@dataclass(frozen=True)
class Row:
    """One figure: what it is, its target as text and as a test on the measured value (None:
    reported without a target), the value, and the unit the value is shown with."""

    figure: str
    target: str
    value: float | None
    limit: float | None = None  # met when value <= limit ...
    at_least: float | None = None  # ... and value >= at_least
    unit: str = "x"

    def met(self) -> str:
        if self.limit is None and self.at_least is None:
            return ""
        if self.value is None:
            return "n/a"
        ok = (self.limit is None or self.value <= self.limit) and (
            self.at_least is None or self.value >= self.at_least)
        return "met" if ok else "NOT met"

    def measured(self) -> str:
        if self.value is None:
            return "n/a"
        if self.unit == "x":
            return f"{self.value:.2f}x"
        if self.unit == "yes/no":
            return "yes" if self.value else "no"
        return f"{self.value:.3g} {self.unit}".rstrip()


def ratio(a: float | None, b: float | None) -> float | None:
    """a / b, None when either is missing or b is 0."""
    if a is None or b is None or b == 0:
        return None
    return a / b


def format_table(rows: Sequence[Row], title: str, notes: Iterable[str] = ()) -> str:
    """The rows as a fixed-width table under `title`, then `notes`, one a line."""
    w_fig = max([len(r.figure) for r in rows] + [6])
    w_tgt = max([len(r.target) for r in rows] + [6])
    w_val = max([len(r.measured()) for r in rows] + [8])
    head = f"{'figure':{w_fig}s}  {'target':{w_tgt}s}  {'measured':>{w_val}s}  result"
    lines = [title, "", head, "-" * len(head)]
    for r in rows:
        lines.append(f"{r.figure:{w_fig}s}  {r.target:{w_tgt}s}  {r.measured():>{w_val}s}  "
                     f"{r.met()}".rstrip())
    results = [r.met() for r in rows]
    lines += ["", (f"Targets: {results.count('met')} met, {results.count('NOT met')} not met, "
                   f"{results.count('n/a')} not measured.")]
    lines += list(notes)
    return "\n".join(lines)
