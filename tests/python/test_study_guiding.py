"""The path-guiding study (scripts/study/guiding.py, guiding_page.py): its pure parts on
synthetic numbers (the guiding tree's memory, equal time, the page's ratios and verdicts, the
reference comparison), and its --quick run end to end under the bpy wheel. No timing is
asserted."""

from __future__ import annotations

import importlib.util
import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from scripts.study import guiding as study_guiding
from scripts.study import guiding_page as study_guiding_page
from stratum.native import Progress

REPO = Path(__file__).resolve().parents[2]


def _progress(**counters: float) -> Progress:
    return Progress(done=True, cancelled=False, samples_done=1, samples_total=1, update_serial=1,
                    rays=0.0, build_seconds=0.0, render_seconds=0.0, fraction_done=1.0,
                    samples_in_progress=1, samples_average=1.0, counters=counters)


def test_memory_comes_from_the_progress_or_the_log_line() -> None:
    progress = _progress(**{"guiding.nodes": 1234.0, "guiding.bytes": 3 * 2**20})
    assert study_guiding_page.guiding_memory(progress, "") == {"nodes": 1234.0, "mib": 3.0}
    # A library without the guiding counters (or with them still zero): the last log line.
    log = ("guiding tree: 10 nodes, 0.01 MiB after pass 1\n"
           "guiding tree: 1,024 nodes, 0.75 MiB after pass 2\n")
    for p in (_progress(), _progress(**{"guiding.nodes": 0.0, "guiding.bytes": 0.0})):
        assert study_guiding_page.guiding_memory(p, log) == {"nodes": 1024.0, "mib": 0.75}
    assert study_guiding_page.guiding_memory(_progress(), "Fra:1 nothing") is None


def _record(costs: dict[str, tuple[float, float] | None]) -> dict[str, Any]:
    """A measure() record whose series s has noise MSE = v/N and time c·N at 64 and 256 spp for
    costs[s] = (v, c) (MSE·time = v·c at every spp), or is unavailable for None."""
    series: dict[str, Any] = {}
    for label, cost in costs.items():
        renderer = "Cycles" if label.startswith("cycles") else "Stratum"
        if cost is None:
            series[label] = {"renderer": renderer, "runs": [],
                             "unavailable": "not available (the library has no use_guiding)"}
            continue
        v, c = cost
        series[label] = {"renderer": renderer, "runs": [
            {"seed": seed, "spp": n, "seconds": c * n, "noise_mse": v / n,
             "mse_vs_own_reference": v / n + 0.01, "mse_vs_stratum_reference": v / n + 0.02}
            for seed in (1, 2) for n in (64, 256)]}
    series["guided mis"].setdefault("memory", {"nodes": 4096.0, "mib": 1.5})
    return {"scene": "scenes/guiding_room.blend", "width": 96, "height": 72, "spp": [64, 256],
            "seeds": [1, 2], "reference_spp": 2048, "load_average": [1.0, 1.0, 1.0],
            "blender": "5.0.1", "cycles_guiding": True, "series": series,
            "references": {"stratum_mean": [0.1, 0.1, 0.1], "cycles_mean": [0.1, 0.1, 0.1],
                           "mse_between": 1e-4, "noise_sum": 1e-4,
                           "worst_block": {"block": 12, "compared": 48, "of": 48,
                                           "worst": 0.02, "mean": 0.01}}}


def test_equal_time_ratios_and_verdicts() -> None:
    """On MSE = v/N, t = c·N the equal-time MSE is v·c/T at the budget T = the smallest of the
    series' largest times (bsdf's 0.25 x 256 = 64 s), so every ratio is the ratio of v·c."""
    costs = {"bsdf": (40.0, 0.25), "mis": (4.0, 0.5), "guided mis": (1.0, 0.8),
             "guided bsdf": (2.0, 0.6), "cycles": (5.0, 0.5), "cycles guided": (3.0, 0.7)}
    data = _record(costs)
    numbers = study_guiding_page.analyse(data)
    assert numbers["budget"] == pytest.approx(64.0)
    for label, (v, c) in costs.items():
        assert numbers["equal_time"][label]["mse"] == pytest.approx(v * c / 64.0)
    assert study_guiding_page.ratio(numbers, "guided mis", "mis") == pytest.approx(0.8 / 2.0)
    assert study_guiding_page.ratio(numbers, "cycles guided", "cycles") == pytest.approx(2.1 / 2.5)
    data["references"]["cycles_vs_stratum"] = study_guiding_page.cycles_against_stratum_reference(data)
    assert data["references"]["cycles_vs_stratum"]["cycles"] == {
        "spp": 256, "own": pytest.approx(5.0 / 256 + 0.01),
        "stratum": pytest.approx(5.0 / 256 + 0.02)}
    text = study_guiding_page.page(data, numbers)
    assert "- Stratum guided mis / Stratum mis: 0.4 (met: target <= 0.5)" in text
    # 0.8 against Cycles guided's 2.1: met; the guided bsdf row shows its memory column empty.
    assert "- Stratum guided mis / Cycles guided: 0.381 (met: target <= 1)" in text
    assert "- Cycles guided / Cycles unguided: 0.84" in text
    assert "| guided mis | Stratum |" in text and "4096 nodes, 1.50 MiB |" in text


def test_unavailable_guiding_is_marked_not_measured() -> None:
    """Without use_guiding in the library the guided rows say so and the targets are not
    measured; the other series keep their numbers, and no memory column is drawn."""
    data = _record({"bsdf": (40.0, 0.25), "mis": (4.0, 0.5), "guided mis": None,
                    "guided bsdf": None, "cycles": (5.0, 0.5), "cycles guided": (6.0, 0.5)})
    data["series"]["guided mis"].pop("memory")
    numbers = study_guiding_page.analyse(data)
    assert set(numbers["equal_time"]) == {"bsdf", "mis", "cycles", "cycles guided"}
    data["references"]["cycles_vs_stratum"] = study_guiding_page.cycles_against_stratum_reference(data)
    text = study_guiding_page.page(data, numbers)
    row = next(line for line in text.splitlines() if line.startswith("| guided mis |"))
    assert "not available (the library has no use_guiding)" in row
    assert "guiding tree" not in text
    assert "- Stratum guided mis / Stratum mis: not measured" in text
    assert "- Stratum guided mis / Cycles guided: not measured" in text
    assert "- Cycles guided / Cycles unguided: 1.2" in text
    assert "- Stratum bsdf / Stratum mis: 5" in text


def test_a_series_with_a_zero_time_is_left_out_of_equal_time() -> None:
    """Cycles' time by subtraction can be 0 at toy sizes, and log(0) has no place in the
    log-log interpolation: that series is listed as unmeasurable, the others keep their
    equal-time numbers (the budget is then the smallest largest time among them)."""
    data = _record({"bsdf": (40.0, 0.25), "mis": (4.0, 0.5), "guided mis": None,
                    "guided bsdf": None, "cycles": (5.0, 0.5), "cycles guided": (6.0, 0.5)})
    data["series"]["guided mis"].pop("memory")
    for run in data["series"]["cycles guided"]["runs"]:
        if run["spp"] == 64:
            run["seconds"] = 0.0
    numbers = study_guiding_page.analyse(data)
    assert numbers["unmeasurable"] == ["cycles guided"]
    assert set(numbers["equal_time"]) == {"bsdf", "mis", "cycles"}
    assert numbers["equal_time"]["mis"]["mse"] == pytest.approx(4.0 * 0.5 / 64.0)
    data["references"]["cycles_vs_stratum"] = study_guiding_page.cycles_against_stratum_reference(
        data)
    row = next(line for line in study_guiding_page.page(data, numbers).splitlines()
               if line.startswith("| cycles guided |"))
    assert "not measurable (a mean time or noise MSE <= 0)" in row


def test_worst_block_compares_bright_blocks_only() -> None:
    """Two 24x24 images, four 12 px blocks: one block 3 % brighter in Stratum, one dark (below
    DARK) block 50 % brighter, which is not compared."""
    cycles = np.full((24, 24, 3), 0.2)
    cycles[12:, 12:] = 0.001
    stratum = cycles.copy()
    stratum[:12, :12] *= 1.03
    stratum[12:, 12:] *= 1.5
    worst = study_guiding_page.worst_block(stratum, cycles, block=12)
    assert worst["compared"] == 9 and worst["of"] == 12
    assert worst["worst"] == pytest.approx(0.03)
    assert worst["mean"] == pytest.approx(0.03 * 3 / 9)


@pytest.mark.skipif(importlib.util.find_spec("bpy") is None, reason="needs the bpy wheel")
def test_quick_run_writes_the_page(tmp_path: Path) -> None:
    """`python -m scripts.study.guiding --quick` (32x24, 8 and 32 spp, one seed) end to end:
    every series has a row; the Stratum and Cycles unguided series are measured; the guided
    Stratum series are measured exactly when the library has use_guiding."""
    out = tmp_path / "study"
    proc = subprocess.run([sys.executable, "-m", "scripts.study.guiding", "--quick",
                           "--out", str(out)], cwd=REPO, check=False, capture_output=True,
                          text=True, timeout=600,
                          env={**os.environ, "PYTHONPATH": str(REPO / "addon")})
    assert proc.returncode == 0, proc.stderr[-3000:]
    text = (out / "guiding.md").read_text()
    data = json.loads((out / "guiding.json").read_text())
    for label in study_guiding.STRATUM_SERIES | study_guiding.CYCLES_SERIES:
        assert f"| {label} |" in text
    measured = set(data["analysis"]["equal_time"])
    # Cycles' time by subtraction may come out as 0 at this toy size (analyse's doc).
    timed = measured | set(data["analysis"]["unmeasurable"])
    assert {"bsdf", "mis"} <= measured and "cycles" in timed
    guided = {"guided mis", "guided bsdf"}
    assert (guided <= measured) if data["stratum_guiding"] else not (guided & timed)
    assert ("cycles guided" in timed) == data["cycles_guiding"]
    assert (out / "figures" / "guiding_mse.png").is_file()
