"""The path-guiding scene of issue 17 (scenes/guiding_room.blend, built by
scenes/make_guiding_room.py) is what the guiding study needs: a closed room whose only light is
the emitter at the top of the light well, Lambert surfaces, a black world, and a camera that
sees no directly lit point, so that everything in view is lit by bounces. Runs in both Blenders
(no rendering)."""

from __future__ import annotations

from pathlib import Path

import pytest

bpy = pytest.importorskip("bpy")

REPO = Path(__file__).resolve().parents[2]
ROOM = REPO / "scenes" / "guiding_room.blend"


def _open() -> None:
    bpy.ops.wm.open_mainfile(filepath=str(ROOM), load_ui=False)


def _world_corners(name: str) -> list[tuple[float, float, float]]:
    obj = bpy.data.objects[name]
    return [tuple(obj.matrix_world @ v.co) for v in obj.data.vertices]


def _shader_types(material: bpy.types.Material) -> set[str]:
    return {n.type for n in material.node_tree.nodes if n.type != "OUTPUT_MATERIAL"}


def test_only_the_emitter_lights_lambert_surfaces() -> None:
    _open()
    assert not [o for o in bpy.data.objects if o.type == "LIGHT"]
    world = bpy.context.scene.world
    background = next(n for n in world.node_tree.nodes if n.type == "BACKGROUND")
    assert tuple(background.inputs["Color"].default_value)[:3] == (0.0, 0.0, 0.0)
    for obj in (o for o in bpy.data.objects if o.type == "MESH"):
        (material,) = obj.data.materials
        expected = {"EMISSION"} if obj.name == "Emitter" else {"BSDF_DIFFUSE"}
        assert _shader_types(material) == expected, obj.name
    # The file is small: it renders at 64-160 px in tests and studies.
    assert bpy.context.scene.render.resolution_x <= 160
    assert ROOM.stat().st_size < 200_000


def test_the_ceiling_is_closed_but_for_the_opening_under_the_emitter() -> None:
    """The four ceiling quads cover the ceiling less exactly the emitter's footprint."""
    _open()
    emitter = _world_corners("Emitter")
    xs, ys = [p[0] for p in emitter], [p[1] for p in emitter]
    opening = (max(xs) - min(xs)) * (max(ys) - min(ys))
    floor = _world_corners("Floor")
    room_area = ((max(p[0] for p in floor) - min(p[0] for p in floor))
                 * (max(p[1] for p in floor) - min(p[1] for p in floor)))
    ceiling = [o for o in bpy.data.objects if o.name.startswith("Ceiling")]
    assert len(ceiling) == 4
    assert sum(o.data.polygons[0].area for o in ceiling) == pytest.approx(room_area - opening)


def test_the_camera_sees_no_directly_lit_point() -> None:
    """Every point the emitter lights directly is within reach of a straight line from the
    emitter through the opening: below the opening at depth d, at most d * opening / well
    beyond the opening's edges (x and y alike). Points on a grid over that region of the floor
    and of the two walls next to the opening must all project outside the camera's frame."""
    from bpy_extras.object_utils import world_to_camera_view
    from mathutils import Vector

    _open()
    scene = bpy.context.scene
    emitter = _world_corners("Emitter")
    top = emitter[0][2]
    ceiling = _world_corners("CeilingFront")[0][2]
    x0, x1 = min(p[0] for p in emitter), max(p[0] for p in emitter)
    y0, y1 = min(p[1] for p in emitter), max(p[1] for p in emitter)
    spread = (x1 - x0) / (top - ceiling)  # horizontal reach per metre below the ceiling
    floor = _world_corners("Floor")
    fx0, fx1 = min(p[0] for p in floor), max(p[0] for p in floor)
    fy0, fy1 = min(p[1] for p in floor), max(p[1] for p in floor)
    reach = ceiling * spread
    steps = [i / 20 for i in range(21)]
    points = []
    for u in steps:
        for v in steps:
            x = max(fx0, x0 - reach) + u * (min(fx1, x1 + reach) - max(fx0, x0 - reach))
            y = max(fy0, y0 - reach) + v * (min(fy1, y1 + reach) - max(fy0, y0 - reach))
            points.append((x, y, 0.0))
            z = v * ceiling
            side = (ceiling - z) * spread  # reach at height z
            if fx1 <= x1 + side:  # the right wall is lit at this height
                points.append((fx1, y, z))
            if fy0 >= y0 - side:  # the front wall
                points.append((x, fy0, z))
    assert len(points) > 441  # the walls next to the opening are lit too
    for p in points:
        view = world_to_camera_view(scene, scene.camera, Vector(p))
        inside = 0.0 <= view.x <= 1.0 and 0.0 <= view.y <= 1.0 and view.z > 0.0
        assert not inside, f"the camera sees the directly lit point {p} at {tuple(view)}"
