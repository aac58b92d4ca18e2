"""The radiosity integrator through the Python API (issue 17): its solve's report in the
progress and per iteration (stratum_renderer_read_radiosity_iterations), and the claim-12 study
(scripts/study/radiosity.py) end to end on a coarse patching."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
from scripts.study import radiosity as study_radiosity


def test_progress_and_iterations_report_the_solve(native: Any) -> None:
    scene = study_radiosity.cornell_scene(native)
    try:
        for solver in study_radiosity.SOLVERS:
            with native.Renderer(scene, width=8, height=8, samples=2, integrator="radiosity",
                                 radiosity_patch_size=0.5, radiosity_rays=64,
                                 radiosity_solver=solver, radiosity_tolerance=1e-5) as r:
                r.start()
                while not r.wait(1000):
                    pass
                p = r.progress()
                history = r.radiosity_iterations()
                pixels = r.read_pixels()
            # The box's 26 quads (52 triangles), each split in n² patches of two sides.
            assert p.counters["radiosity.patches"] > 2 * 52
            assert p.counters["radiosity.bytes"] > 0 and p.counters["radiosity.seconds"] > 0
            assert history.shape == (p.counters["radiosity.iterations"], 4)
            delta_e, relative, residual, seconds = history.T
            assert np.all(delta_e >= 0)
            assert relative[-1] <= 1e-5 < relative[0], solver
            assert np.all(np.diff(seconds) >= 0)
            assert residual[-1] < 1e-3 * residual[0], solver
            assert np.isfinite(pixels).all() and pixels[..., :3].mean() > 0
        with native.Renderer(scene, width=8, height=8, samples=1) as r:
            r.start()
            while not r.wait(1000):
                pass
            assert r.radiosity_iterations().shape == (0, 4)
            assert r.progress().counters["radiosity.patches"] == 0
    finally:
        scene.close()


def test_study_writes_the_claim_12_page(native: Any, tmp_path: Path) -> None:
    study_radiosity.main(["--out", str(tmp_path), "--quick"])
    result = json.loads((tmp_path / "radiosity.json").read_text())
    assert set(result["solvers"]) == set(study_radiosity.SOLVERS)
    iterations = {s: len(r["residual"]) for s, r in result["solvers"].items()}
    # Stein-Rosenberg: Gauss-Seidel needs fewer sweeps than Jacobi on this non-negative system.
    assert iterations["gauss_seidel"] < iterations["jacobi"]
    page = (tmp_path / "radiosity.md").read_text()
    assert all(f"| {s} |" in page for s in study_radiosity.SOLVERS)
    assert (tmp_path / "figures" / "radiosity.png").stat().st_size > 0
