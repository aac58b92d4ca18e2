"""The Rendered viewport as a user drives it, in Blender 3.4's UI (tests/ui/test_viewport.py).

On the bundled Cornell box: a 3D view in Rendered shading, camera view fitted to the region,
until the drawn image stops changing; its camera frame against an F12 render of the same camera
(channel means, both after the display transform); then an orbit, an object moved, a material
colour and a light power changed: each changes the drawn image the way it should and the image
settles again. Solid shading at the end must leave no viewport render running.

Findings go to results.json (driver.py): per step the means of the camera frame or the region.
The engine is Stratum unless STRATUM_UI_ENGINE names another (how the harness itself was
checked against Cycles' viewport).
"""

from __future__ import annotations

import os
from collections.abc import Iterator

import bpy
import numpy as np
from bpy_extras.view3d_utils import location_3d_to_region_2d
from driver import Scenario, ScenarioFailed

ENGINE = os.environ.get("STRATUM_UI_ENGINE", "STRATUM")
PREVIEW_SAMPLES = 16
STABLE_SECONDS = 2.0  # unchanged screenshots this long: the viewport has converged


def camera_frame_box(s: Scenario) -> tuple[int, int, int, int]:
    """(x0, y0, x1, y1) of the camera frame in the 3D view's pixels (bottom-left origin),
    shrunk by 3 pixels so that the frame's edge is not counted."""
    _, area, region = s.view3d()
    scene = bpy.context.scene
    camera = scene.camera
    corners = [camera.matrix_world @ v for v in camera.data.view_frame(scene=scene)]
    points = [location_3d_to_region_2d(region, s.space().region_3d, c) for c in corners]
    if any(p is None for p in points):
        raise ScenarioFailed("the camera frame is not in the 3D view")
    dx, dy = region.x - area.x, region.y - area.y
    xs = [p.x + dx for p in points]
    ys = [p.y + dy for p in points]
    return (int(min(xs)) + 3, int(min(ys)) + 3, int(max(xs)) - 3, int(max(ys)) - 3)


def means(image: np.ndarray, box: tuple[int, int, int, int] | None = None) -> list[float]:
    if box is not None:
        x0, y0, x1, y1 = box
        image = image[y0:y1, x0:x1]
    return [float(v) for v in image[..., :3].reshape(-1, 3).mean(axis=0)]


def settle(s: Scenario, name: str, timeout: float = 240.0) -> Iterator[float]:
    """Yields until two screenshots STABLE_SECONDS apart are identical; the last one is kept
    in s.results[name + "_shot"] (its path) and returned through s.last."""
    previous = s.screenshot(name)
    waited = 0.0
    while True:
        yield STABLE_SECONDS
        waited += STABLE_SECONDS
        current = s.screenshot(name)
        if np.array_equal(current, previous):
            s.last = current
            s.log(f"{name}: settled after {waited:.0f} s")
            return
        if waited > timeout:
            raise ScenarioFailed(f"{name}: the viewport still changed after {timeout:g} s")
        previous = current


def steps(s: Scenario) -> Iterator[float]:
    import stratum

    stratum.register()
    scene = bpy.context.scene
    scene.render.engine = ENGINE
    if ENGINE == "STRATUM":
        scene.stratum.preview_samples = PREVIEW_SAMPLES
    elif ENGINE == "CYCLES":
        scene.cycles.preview_samples = PREVIEW_SAMPLES
    s.plain_view()
    space = s.space()
    space.region_3d.view_perspective = "CAMERA"
    yield 0.5
    with s.override():
        bpy.ops.view3d.view_center_camera()
    space.shading.type = "RENDERED"
    yield 1.0
    yield from settle(s, "camera")
    box = camera_frame_box(s)
    s.results["camera_box"] = box
    s.results["viewport_means"] = means(s.last, box)

    # F12 of the same camera, saved through the same view transform as the viewport draws,
    # with the viewport's sample count (a mean over the frame converges long before a pixel).
    if ENGINE == "STRATUM":
        scene.stratum.samples = PREVIEW_SAMPLES
    elif ENGINE == "CYCLES":
        scene.cycles.samples = PREVIEW_SAMPLES
    scene.render.resolution_percentage = 50
    path = s.out / "f12.png"
    scene.render.filepath = str(path)
    scene.render.image_settings.file_format = "PNG"
    scene.render.image_settings.color_mode = "RGB"
    with s.override():
        bpy.ops.render.render(write_still=True)
    from driver import load_png

    s.results["f12_means"] = means(load_png(path))
    yield 0.5

    # Orbit: leave the camera view and turn the view around the vertical axis.
    space.region_3d.view_perspective = "PERSP"
    yield 0.5
    before = s.screenshot("before_orbit")
    from mathutils import Quaternion

    space.region_3d.view_rotation = Quaternion((0, 0, 1), 0.3) @ space.region_3d.view_rotation
    yield from settle(s, "orbit")
    s.results["orbit_changed"] = float(np.abs(s.last - before).mean())
    space.region_3d.view_perspective = "CAMERA"
    yield from settle(s, "camera_again")
    reference = means(s.last, box)

    # A light power edit: brighter everywhere.
    lamps = [ob for ob in scene.objects if ob.type == "LIGHT"]
    if lamps:
        lamps[0].data.energy *= 2.0
        edit = "light"
    else:
        emissive = next(m for m in bpy.data.materials if m.node_tree and any(
            n.type == "EMISSION" for n in m.node_tree.nodes))
        node = next(n for n in emissive.node_tree.nodes if n.type == "EMISSION")
        node.inputs["Strength"].default_value *= 2.0
        edit = "emission"
    yield from settle(s, "brighter")
    s.results["brighter"] = {"edit": edit, "before": reference, "after": means(s.last, box)}
    reference = means(s.last, box)

    # A material colour edit: every material with a Principled BSDF goes pure green.
    for material in bpy.data.materials:
        if material.node_tree is None:
            continue
        for node in material.node_tree.nodes:
            if node.type == "BSDF_PRINCIPLED":
                node.inputs["Base Color"].default_value = (0.05, 0.8, 0.05, 1.0)
            elif node.type == "BSDF_DIFFUSE":
                node.inputs["Color"].default_value = (0.05, 0.8, 0.05, 1.0)
    yield from settle(s, "green")
    s.results["green"] = {"before": reference, "after": means(s.last, box)}
    reference = means(s.last, box)

    # An object moved out of the camera's sight changes the image: the largest one that is
    # not part of the room (its walls are the largest) nor the lamp.
    inside = [ob for ob in scene.objects if ob.type == "MESH" and ob.dimensions.length < 2.0
              and ob.name != "LightQuad"]
    moved = max(inside, key=lambda ob: ob.dimensions.length)
    moved.location.z += 100.0
    yield from settle(s, "moved")
    s.results["moved"] = {"object": moved.name,
                          "changed": float(np.abs(np.array(means(s.last, box)) -
                                                  np.array(reference)).sum())}

    space.shading.type = "SOLID"
    yield 1.0
    if ENGINE == "STRATUM":
        from stratum.engine import viewport_session

        s.results["sessions_after_solid"] = viewport_session.running_sessions()


if __name__ == "__main__":
    Scenario.main(steps)
