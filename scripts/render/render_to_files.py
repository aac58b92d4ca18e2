"""Renders the open scene with its render engine and writes OUT.png (view transform applied,
as Blender saves display images) and OUT.exr (linear, 32-bit float).

Usage: blender -b SCENE.blend -E STRATUM --python scripts/run_in_blender.py -- \
           scripts.render.render_to_files OUT
"""

import sys

import bpy


def main() -> None:
    out = sys.argv[sys.argv.index("--") + 1]
    scene = bpy.context.scene
    bpy.ops.render.render()
    result = bpy.data.images["Render Result"]
    settings = scene.render.image_settings
    settings.file_format = "PNG"
    settings.color_mode = "RGBA"
    settings.color_depth = "8"
    result.save_render(filepath=f"{out}.png", scene=scene)
    settings.file_format = "OPEN_EXR"
    settings.color_depth = "32"
    result.save_render(filepath=f"{out}.exr", scene=scene)


if __name__ == "__main__":
    try:
        main()
    except Exception as error:  # noqa: BLE001 - report any failure as a non-zero exit of Blender
        print(f"render_to_files: {error}", file=sys.stderr)
        sys.exit(1)
