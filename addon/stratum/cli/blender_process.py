"""Finding Blender and the command line that runs it in the background.

Shared by `stratum render` (cli/__init__.py, and distributed.py for --scheduler) and `stratum
compare` (compare/runner.py), so all find the same Blender ($STRATUM_BLENDER or `blender`) and
register the add-on from the same checkout (ADDON_PARENT), and none has to import another to
do so.
`script_command` is the whole command for a script passed inline (`--python-expr`): the scripts
of cli/__init__.py and distributed.py share its start (arguments, add-on, scene settings) and
its end.
"""

from __future__ import annotations

import json
import os
import shutil
import textwrap
from collections.abc import Sequence
from pathlib import Path
from typing import Any

ADDON_PARENT = Path(__file__).resolve().parents[2]  # the folder that holds stratum/
NOT_FOUND_MESSAGE = "Blender not found (set STRATUM_BLENDER)"


def blender_executable() -> str | None:
    """$STRATUM_BLENDER or `blender`, found on PATH or as a file; None when there is none."""
    exe = os.environ.get("STRATUM_BLENDER", "blender")
    return shutil.which(exe) or (exe if os.path.isfile(exe) else None)


def background_command(blender: str, scene: Path, *arguments: str,
                       audio: bool = True) -> list[str]:
    """Runs `blender` without a window on the factory settings, opening `scene`, then
    `arguments` (e.g. "--python", SCRIPT, "--", ...). audio=False passes -noaudio, ahead of the
    scene like every option that sets Blender up."""
    setup = [] if audio else ["-noaudio"]
    return [blender, "-b", "--factory-startup", *setup, str(scene), *arguments]


# The start of every inline script: its arguments are the JSON after "--"; the add-on is
# registered from args["addon_parent"] and renders the opened scene, with args["overrides"]
# set on scene.stratum (on scene.cycles for a Light Paths setting the scene takes from Cycles:
# light_path_source.py) and args["resolution"] (WxH at 100 %) when given.
_SCRIPT_START = r"""
import json, os, sys, traceback
args = json.loads(sys.argv[sys.argv.index("--") + 1])
sys.path.insert(0, args["addon_parent"])
code = 1
try:
    import bpy
    import stratum
    from stratum.engine_id import ENGINE_ID
    stratum.register()
    scene = bpy.context.scene
    scene.render.engine = ENGINE_ID
    from stratum.light_path_source import light_path_holder
    for name, value in args["overrides"].items():
        setattr(*light_path_holder(scene, name), value)
    if args.get("resolution"):
        scene.render.resolution_x, scene.render.resolution_y = args["resolution"]
        scene.render.resolution_percentage = 100
"""
# ... and its end: an exception is printed and exits 1. os._exit gives Blender's process the
# script's code (Blender's own exit would give 0 whatever the script found); it skips Python's
# shutdown, hence the flushes.
_SCRIPT_END = r"""
except Exception:
    traceback.print_exc()
    code = 1
sys.stdout.flush()
sys.stderr.flush()
os._exit(code)
"""

# The scene.stratum settings `stratum render` takes from its options of the same names.
OVERRIDDEN_SETTINGS = ("samples", "seed", "max_bounces", "sampler")


def overrides_from_options(options: Any) -> dict[str, Any]:
    """{setting: value} of the OVERRIDDEN_SETTINGS that the parsed command line gives (not
    None), in that order."""
    return {name: getattr(options, name) for name in OVERRIDDEN_SETTINGS
            if getattr(options, name) is not None}


def inline_script(body: str) -> str:
    """`body` (top-level code) between the shared start and end: it runs after the start (and
    finds `args`, `bpy`, `stratum` and `scene` set), and the process exits with the `code` it
    sets (0 on success; it starts at 1)."""
    return _SCRIPT_START + textwrap.indent(textwrap.dedent(body), "    ") + _SCRIPT_END


def script_command(blender: str, scene: Path, body: str, overrides: dict[str, Any],
                   resolution: Sequence[int] | None, **arguments: Any) -> list[str]:
    """Runs inline_script(body) in Blender in the background on `scene`; `arguments` (JSON
    values) join addon_parent, overrides and resolution in the script's `args`."""
    script = inline_script(body)
    payload = {"addon_parent": str(ADDON_PARENT), "overrides": overrides,
               "resolution": list(resolution) if resolution else None, **arguments}
    return background_command(blender, scene, "--python-expr", script, "--",
                              json.dumps(payload))
