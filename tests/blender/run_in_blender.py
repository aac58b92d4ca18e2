"""Runs pytest inside Blender and exits Blender with pytest's exit code.

    blender -b --factory-startup --python tests/blender/run_in_blender.py -- tests/blender -q
    .venv-bpy-4.5/bin/python tests/blender/run_in_blender.py -- tests/blender/test_x.py -q

Blender's --python does not propagate sys.exit() codes reliably, so the exit code is passed
to os._exit after flushing the streams. The LTS wheels' smoke matrix (make test-wheels) runs
through here for the same exit: a bpy 4.5 process was seen to hang at exit after a render, in
bpy's own delayed-close thread with no Stratum code on any stack, and os._exit skips the
interpreter's shutdown where it waits.
"""

import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def main() -> int:
    if "--" in sys.argv:
        args = sys.argv[sys.argv.index("--") + 1 :]
    else:
        args = [str(ROOT / "tests" / "blender")]
    addon_dir = str(ROOT / "addon")
    if addon_dir not in sys.path:
        sys.path.insert(0, addon_dir)
    try:
        import pytest
    except ImportError:
        print("run_in_blender: pytest is not importable in Blender's Python "
              "(install python3-pytest)", file=sys.stderr)
        return 4
    # Blender's argv is not pytest's: pass the arguments explicitly.
    return int(pytest.main(["-p", "no:cacheprovider", *args]))


if __name__ == "__main__":
    code = 1
    try:
        code = main()
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)
