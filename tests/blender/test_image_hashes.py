"""Images unchanged across refactors (issue 13, acceptance 1): the SHA-256 of the linear
float32 RGBA pixels (what the linear EXR stores) of

* the bundled Cornell box at 32x32, 16 spp, for every sampler of the native registry x
  {path mis, path nee, path bsdf, light, ao, direct};
* every feature scene (scenes/features/*.blend) at 16x16, 4 spp, with its own settings;

each rendered with threads 1 and 2 (which must agree bit for bit), against the table recorded
for this Blender version in tests/blender/image_hashes/blender-<major>.<minor>.json. The table
was first recorded before the architecture change of issue 13; a change that must alter an
image re-records it in its own commit that says why:

    blender -b --factory-startup -noaudio --python tests/blender/test_image_hashes.py -- --write
    .venv/bin/python tests/blender/test_image_hashes.py --write
"""

from __future__ import annotations

import hashlib
import json
import sys
import tempfile
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parents[2]
TABLES = Path(__file__).resolve().parent / "image_hashes"
CORNELL = REPO / "scenes" / "cornell_box.blend"
FEATURES = sorted((REPO / "scenes" / "features").glob("*.blend"))
# (integrator, light_sampling): the path tracer's three estimators, then the other integrators.
ESTIMATORS = [("path", "mis"), ("path", "nee"), ("path", "bsdf"), ("light", None), ("ao", None),
              ("direct", None)]
THREADS = (1, 2)


def _table_path(bpy: Any) -> Path:
    major, minor = bpy.app.version[:2]
    return TABLES / f"blender-{major}.{minor}.json"


def _render_digest(bpy: Any, path: Path) -> str:
    """Renders the open scene to a 32-bit EXR and returns the SHA-256 of its RGBA pixels (as
    Blender's Image.pixels holds them: rows bottom first)."""
    from exr_file import read_image

    scene = bpy.context.scene
    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_mode = "RGBA"
    settings.color_depth = "32"
    scene.render.filepath = str(path)
    scene.render.use_file_extension = False
    path.unlink(missing_ok=True)
    bpy.ops.render.render(write_still=True)
    return hashlib.sha256(read_image(path).tobytes()).hexdigest()


def _open(bpy: Any, blend: Path, size: int, samples: int) -> Any:
    bpy.ops.wm.open_mainfile(filepath=str(blend))
    scene = bpy.context.scene
    scene.render.engine = "STRATUM"
    r = scene.render
    r.resolution_x, r.resolution_y, r.resolution_percentage = size, size, 100
    r.use_border = False
    scene.stratum.samples = samples
    return scene


def _threads_digest(bpy: Any, scene: Any, out: Path, name: str) -> str:
    """One digest for threads 1 and 2, or an AssertionError naming both."""
    digests = []
    for threads in THREADS:
        scene.stratum.threads = threads
        digests.append(_render_digest(bpy, out / f"{name}-t{threads}.exr"))
    assert len(set(digests)) == 1, f"{name}: threads {THREADS} gave {digests}"
    return digests[0]


def image_hashes(bpy: Any) -> dict[str, str]:
    """Renders every case and returns {case name: digest}."""
    from stratum import native

    samplers = [e.name for e in native.registry("sampler")]
    hashes: dict[str, str] = {}
    with tempfile.TemporaryDirectory(prefix="stratum-hashes-") as tmp:
        out = Path(tmp)
        for sampler in samplers:
            for integrator, light_sampling in ESTIMATORS:
                scene = _open(bpy, CORNELL, 32, 16)
                scene.stratum.sampler = sampler
                scene.stratum.integrator = integrator
                if light_sampling is not None:
                    scene.stratum.light_sampling = light_sampling
                name = f"cornell_box/{sampler}/{integrator}" + (
                    f"-{light_sampling}" if light_sampling else "")
                hashes[name] = _threads_digest(bpy, scene, out, name.replace("/", "_"))
        for blend in FEATURES:
            scene = _open(bpy, blend, 16, 4)
            name = f"features/{blend.stem}"
            hashes[name] = _threads_digest(bpy, scene, out, name.replace("/", "_"))
    return hashes


def test_images_equal_the_recorded_table(stratum_addon: Any, library: Any) -> None:
    import bpy

    table = _table_path(bpy)
    assert table.is_file(), f"no image table for this Blender: record {table.name} (module doc)"
    recorded = json.loads(table.read_text())
    ours = image_hashes(bpy)
    assert sorted(ours) == sorted(recorded), (
        f"cases differ: new {sorted(set(ours) - set(recorded))}, "
        f"gone {sorted(set(recorded) - set(ours))}")
    changed = [name for name in recorded if ours[name] != recorded[name]]
    assert not changed, f"{len(changed)} of {len(recorded)} images changed: {changed}"


def _write_table() -> int:
    # Run as a script, Blender puts neither the add-on nor this folder (exr_file) on the path.
    sys.path[:0] = [str(REPO / "addon"), str(Path(__file__).resolve().parent)]
    import bpy
    import stratum

    stratum.register()
    try:
        hashes = image_hashes(bpy)
    finally:
        stratum.unregister()
    table = _table_path(bpy)
    table.parent.mkdir(exist_ok=True)
    table.write_text(json.dumps(hashes, indent=1, sort_keys=True) + "\n")
    print(f"wrote {len(hashes)} image hashes to {table}")
    return 0


if __name__ == "__main__":
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    if args != ["--write"]:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    import os

    code = 1
    try:
        code = _write_table()
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)
