"""Captures a .blend's render geometry as a native scene file (stratum_scene_save), for
profiling and bug reports with `build/stratum-native render` (no Blender in the loop).

    blender -b SCENE.blend --factory-startup --python scripts/run_in_blender.py -- \
        scripts.render.capture_scene OUT.json

Prints the add-on's render settings of the scene as name=value words on the last line, which
stratum-native takes as they are.
"""

from __future__ import annotations

import sys
from pathlib import Path

import bpy
import stratum
from stratum import native
from stratum.engine.frame import renderer_settings
from stratum.export.render_geometry import use_render_geometry
from stratum.export.sync import export_scene


def main() -> int:
    out = Path(sys.argv[sys.argv.index("--") + 1])
    stratum.register()
    scene = bpy.context.scene
    use_render_geometry(scene)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    with native.Scene() as captured:
        summary = export_scene(depsgraph, captured)
        captured.save(str(out))
    print(f"captured {summary.triangles} triangles, {summary.instances} instances into {out}",
          file=sys.stderr)
    settings = renderer_settings(scene)
    print("SETTINGS " + " ".join(f"{k}={v}" for k, v in settings.items()))
    return 0


if __name__ == "__main__":
    code = main()
    sys.stdout.flush()
    sys.exit(code)
