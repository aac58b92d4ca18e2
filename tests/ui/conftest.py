"""Runs a scenario (tests/ui/scenario_*.py, driven by tests/ui/driver.py) in Blender 3.4 with
its real UI on a virtual X display (xvfb-run, Mesa's software OpenGL), and hands its findings
to the test. The scenario writes results.json, which is the verdict (a missing file means Blender died or
hung), and quits Blender itself: a non-zero exit code after that is a crash on the way out.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
from pathlib import Path
from typing import Any

import pytest

REPO = Path(__file__).resolve().parents[2]
UI = REPO / "tests" / "ui"
OUT = REPO / "out" / "ui"
BLENDER = os.environ.get("BLENDER", "blender")


def run_scenario(script: str, blend: Path, name: str, timeout: float = 600.0,
                 env: dict[str, str] | None = None,
                 screen: tuple[int, int] = (1280, 800)) -> dict[str, Any]:
    """Runs tests/ui/<script> on `blend` on a virtual screen of `screen` pixels; its output
    folder is out/ui/<name> (screenshots, results.json, blender.log). Fails with Blender's log
    when the scenario did not finish."""
    if shutil.which("xvfb-run") is None:
        pytest.fail("xvfb-run is missing: run scripts/setup.sh (Debian package xvfb)")
    out = OUT / name
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    command = ["xvfb-run", "-a", "-s", f"-screen 0 {screen[0]}x{screen[1]}x24", BLENDER, str(blend),
               "--factory-startup", "-noaudio", "--python", str(UI / script), "--", str(out)]
    environment = dict(os.environ, PYTHONPATH=os.pathsep.join([str(UI), str(REPO / "addon")]))
    environment.update(env or {})
    log = out / "blender.log"
    with log.open("w") as stream:
        try:
            finished = subprocess.run(command, stdout=stream, stderr=subprocess.STDOUT,
                                      env=environment, timeout=timeout, check=False)
        except subprocess.TimeoutExpired:
            pytest.fail(f"Blender's UI did not quit within {timeout:g} s; log: {log}")
    results = out / "results.json"
    if not results.exists():
        tail = "\n".join(log.read_text(errors="replace").splitlines()[-40:])
        pytest.fail(f"the scenario wrote no results (Blender crashed or hung):\n{tail}")
    found = json.loads(results.read_text())
    if finished.returncode != 0:
        tail = "\n".join(log.read_text(errors="replace").splitlines()[-40:])
        pytest.fail(f"Blender exited with {finished.returncode} after the scenario:\n{tail}")
    if found.get("error"):
        pytest.fail(f"scenario {script} failed:\n{found['error']}\nsteps:\n" +
                    "\n".join(found["steps"]))
    return found
