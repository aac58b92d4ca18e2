"""The inline scripts `stratum render` runs in Blender (blender_process.inline_script), run here
by plain Python against a stand-in `bpy` and `stratum`: the shared start applies the arguments,
the shared end gives the process the body's exit code. The real scripts run in Blender in
test_cli.py and test_distributed.py."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from stratum import cli
from stratum.cli import distributed
from stratum.cli.blender_process import ADDON_PARENT, inline_script, script_command

# A stand-in for Blender's module: one scene with the attributes the shared start sets.
FAKE_BPY = """
from types import SimpleNamespace
render = SimpleNamespace(engine="CYCLES", resolution_x=1920, resolution_y=1080,
                         resolution_percentage=50)
context = SimpleNamespace(scene=SimpleNamespace(render=render, stratum=SimpleNamespace()))
"""
FAKE_STRATUM = """
registered = False
def register():
    global registered
    registered = True
"""
# Prints what the start left behind, then succeeds.
REPORT_BODY = """
import json
print(json.dumps({"registered": stratum.registered, "render": vars(scene.render),
                  "stratum": vars(scene.stratum)}))
code = 0
"""


def _run(tmp_path: Path, body: str, overrides: dict[str, object],
         resolution: list[int] | None) -> subprocess.CompletedProcess[str]:
    (tmp_path / "bpy.py").write_text(FAKE_BPY)
    (tmp_path / "stratum").mkdir(exist_ok=True)
    (tmp_path / "stratum" / "__init__.py").write_text(FAKE_STRATUM)
    payload = {"addon_parent": str(tmp_path), "overrides": overrides, "resolution": resolution}
    return subprocess.run([sys.executable, "-c", inline_script(body), "--", json.dumps(payload)],
                          capture_output=True, text=True, check=False, timeout=60)


def test_the_start_registers_and_sets_the_scene(tmp_path: Path) -> None:
    proc = _run(tmp_path, REPORT_BODY, {"samples": 3, "sampler": "sobol"}, [40, 30])
    assert proc.returncode == 0, proc.stderr
    state = json.loads(proc.stdout)
    assert state == {"registered": True,
                     "render": {"engine": "STRATUM", "resolution_x": 40, "resolution_y": 30,
                                "resolution_percentage": 100},
                     "stratum": {"samples": 3, "sampler": "sobol"}}


def test_without_a_resolution_the_scene_keeps_its_own(tmp_path: Path) -> None:
    proc = _run(tmp_path, REPORT_BODY, {}, None)
    assert proc.returncode == 0, proc.stderr
    render = json.loads(proc.stdout)["render"]
    assert (render["resolution_x"], render["resolution_y"]) == (1920, 1080)
    assert render["resolution_percentage"] == 50


@pytest.mark.parametrize(("body", "message"), [
    ("raise ValueError('no scene file')", "ValueError: no scene file"),
    ("pass", ""),  # a body that never sets code = 0 fails
])
def test_the_end_exits_1_when_the_body_fails(tmp_path: Path, body: str, message: str) -> None:
    proc = _run(tmp_path, body, {}, None)
    assert proc.returncode == 1
    assert message in proc.stderr


@pytest.mark.parametrize("body", [cli._RENDER_SCRIPT, distributed._EXPORT_SCRIPT])
def test_the_command_carries_the_script_and_its_arguments(body: str) -> None:
    cmd = script_command("blender", Path("scene.blend"), body, {"seed": 2}, (8, 6),
                         output="out.png")
    assert cmd[:5] == ["blender", "-b", "--factory-startup", "scene.blend", "--python-expr"]
    compile(cmd[5], "inline script", "exec")
    assert cmd[6] == "--"
    assert json.loads(cmd[7]) == {"addon_parent": str(ADDON_PARENT), "overrides": {"seed": 2},
                                  "resolution": [8, 6], "output": "out.png"}
