"""Runs a module of this repository inside Blender, as `python -m` runs it under the bpy wheel:

    blender -b --factory-startup -noaudio --python scripts/run_in_blender.py -- MODULE [ARGS]

for example `... -- scripts.bench.speed --only export`. Blender's Python does not know this
checkout: --python does not put a script's folder on sys.path, and an official Blender ignores
PYTHONPATH (unless --python-use-system-env). So this is the one place that puts the repository
(the `scripts` package, the test helpers of tests/) and addon/ (this checkout's `stratum`) on
sys.path; nothing it runs changes sys.path again. The module sees ARGS after "--" in
sys.argv, where a script passed to --python finds its own.

A module that fails (an exception, or sys.exit with a non-zero status) makes Blender exit with
status 1 or that status. In background mode Blender always leaves when the module returns,
with its status, through os._exit after flushing (Blender's --python does not pass a script's
sys.exit status on reliably); with its UI, a module that returned normally leaves Blender
running, so the timers it registered can drive the UI.
"""

import os
import runpy
import sys
import traceback
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent


def exit_status(code: object) -> int:
    """The process status of sys.exit(code): 0 for None, an int as is, 1 for anything else
    (which sys.exit prints)."""
    if code is None:
        return 0
    if isinstance(code, int):
        return code
    print(code, file=sys.stderr)
    return 1


def run(argv: list[str]) -> int:
    """Runs the module argv names after "--" as __main__ with the arguments after it; returns
    its exit status."""
    if "--" not in argv or len(argv) == argv.index("--") + 1:
        print("run_in_blender: usage: blender ... --python scripts/run_in_blender.py -- MODULE "
              "[ARGS]", file=sys.stderr)
        return 2
    start = argv.index("--") + 1
    module = argv[start]
    del argv[start]
    for folder in (REPO / "addon", REPO):
        if str(folder) not in sys.path:
            sys.path.insert(0, str(folder))
    try:
        # alter_sys=False keeps sys.argv[0] Blender's, which the benchmarks test for.
        runpy.run_module(module, run_name="__main__", alter_sys=False)
    except SystemExit as exc:
        return exit_status(exc.code)
    except Exception:  # noqa: BLE001 - reported, status 1
        traceback.print_exc()
        return 1
    return 0


def main() -> None:
    import bpy

    status = run(sys.argv)
    if status != 0 or bpy.app.background:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(status)


if __name__ == "__main__":
    main()
