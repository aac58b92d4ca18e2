"""Finding Blender and the command line that runs it in the background.

Shared by `stratum render` (cli.py) and `stratum compare` (compare/runner.py), so both find the
same Blender ($STRATUM_BLENDER or `blender`) and register the add-on from the same checkout
(ADDON_PARENT), and neither has to import the other to do so.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

ADDON_PARENT = Path(__file__).resolve().parent.parent  # the folder that holds stratum/
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
