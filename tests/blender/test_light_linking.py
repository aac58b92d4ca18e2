"""Light linking and shadow linking (Blender 4.0+) against Cycles, and their absence in 3.x.

Light linking: a floor with spheres A (left) and B (right) under a point light whose receiver
collection includes A only. Direct light alone (max_bounces 0) leaves everything but A exactly
black in Stratum (B and the floor receive exactly 0 from it); with bounces and a dimmer unlinked
fill lamp, the image agrees with Cycles' (agreement.py: image means within 2% and 16 x 16
blocks within 5% per channel, after the noise gate).

Shadow linking: a sun over a floor and a black occluder the camera does not see, the
occluder excluded from the sun's blocker collection. Direct light alone, the floor equals the
render without the occluder pixel for pixel (same seed: the shadow rays ignore it and nothing
else changes). With an area lamp above the occluder sharing the blocker collection (the lamp is
also found by scattered rays, through Cycles' dedicated light pass) and bounces, the image
agrees with Cycles'.

In Blender 3.x the properties do not exist: the export reads none (linking_sets is None) and
renders as before.
"""

from __future__ import annotations

import functools
from pathlib import Path

import bpy
import numpy as np
import pytest

from agreement import (
    OUT,
    Renders,
    add_diffuse_floor,
    assert_agreement,
    configure_cycles,
    configure_stratum,
    new_scene,
    render_exr,
    render_two_seeds,
    stratum_available,
)

RES = 32
BLOCK = 16
SPP_PER_SEED = 512
BOUNCES = 3
LINK_OUT = OUT / "light_linking"
HAS_LINKING = bpy.app.version >= (4, 0, 0)


def _black_material(name: str) -> bpy.types.Material:
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    nodes["Principled BSDF"].inputs["Roughness"].default_value = 1.0
    return mat


def _top_camera(scene: bpy.types.Scene) -> None:
    cam = bpy.data.cameras.new("cam")
    cam.type = "ORTHO"
    cam.ortho_scale = 4.0
    camera = bpy.data.objects.new("cam", cam)
    camera.location = (0.0, 0.0, 5.0)
    scene.collection.objects.link(camera)
    scene.camera = camera


def _link_collection(name: str, objects: list[bpy.types.Object], state: str) -> bpy.types.Collection:
    collection = bpy.data.collections.new(name)
    for ob in objects:
        collection.objects.link(ob)
    for entry in collection.collection_objects:
        entry.light_linking.link_state = state
    return collection


def _spheres_scene() -> bpy.types.Scene:
    """Floor, sphere A at x = -1, sphere B at x = +1, a point light above the middle lighting A
    only; a top view, A in the left half of the image and B in the right."""
    scene = new_scene(RES)
    add_diffuse_floor(scene, 2.0)
    spheres = []
    for name, x in (("A", -1.0), ("B", 1.0)):
        bpy.ops.mesh.primitive_uv_sphere_add(radius=0.6, location=(x, 0.0, 0.6), segments=24,
                                             ring_count=12)
        sphere = bpy.context.active_object
        sphere.name = name
        sphere.data.materials.append(bpy.data.materials["floor"])
        spheres.append(sphere)
    lamp = bpy.data.lights.new("lamp", "POINT")
    lamp.energy = 300.0
    lamp.shadow_soft_size = 0.0
    light = bpy.data.objects.new("lamp", lamp)
    light.location = (0.0, -0.5, 2.5)
    scene.collection.objects.link(light)
    if HAS_LINKING:
        light.light_linking.receiver_collection = _link_collection("receivers", spheres[:1],
                                                                   "INCLUDE")
    # A dimmer lamp lighting everything, so that B and the floor are bright enough to compare
    # (B too bright would show the first lamp's light on it).
    fill = bpy.data.lights.new("fill", "POINT")
    fill.energy = 100.0
    fill.shadow_soft_size = 0.0
    fill_ob = bpy.data.objects.new("fill", fill)
    fill_ob.location = (1.5, 1.5, 3.0)
    scene.collection.objects.link(fill_ob)
    scene.world = None  # black for both renderers
    _top_camera(scene)
    return scene


def _sun_scene(occluder: bool = True, area: bool = False) -> bpy.types.Scene:
    """Floor under a sun tilted 20 degrees; a black square above its middle (unseen by the
    camera) excluded from the sun's blocker collection; with `area`, also a square area lamp
    above the square, sharing that blocker collection (found by scattered rays too: Cycles'
    dedicated light pass)."""
    scene = new_scene(RES)
    add_diffuse_floor(scene, 2.0)
    sun = bpy.data.lights.new("sun", "SUN")
    sun.energy = 0.3 if area else 3.0
    sun.angle = 0.1
    sun_ob = bpy.data.objects.new("sun", sun)
    sun_ob.rotation_euler = (0.35, 0.0, 0.0)
    scene.collection.objects.link(sun_ob)
    if occluder:
        bpy.ops.mesh.primitive_plane_add(size=1.5, location=(0.0, 0.0, 1.0))
        plane = bpy.context.active_object
        plane.name = "occluder"
        plane.data.materials.append(_black_material("black"))
        plane.visible_camera = False
        if HAS_LINKING:
            sun_ob.light_linking.blocker_collection = _link_collection("blockers", [plane],
                                                                       "EXCLUDE")
    if area:
        lamp = bpy.data.lights.new("area", "AREA")
        # Large and near: scattered rays find it often, so its light on the floor depends on
        # the dedicated pass (without it the floor's mean here is 34% darker: measured).
        lamp.energy = 400.0
        lamp.size = 3.0
        area_ob = bpy.data.objects.new("area", lamp)
        area_ob.location = (0.0, 0.0, 1.6)
        scene.collection.objects.link(area_ob)
        if HAS_LINKING and occluder:
            area_ob.light_linking.blocker_collection = bpy.data.collections["blockers"]
    scene.world = None  # black for both renderers
    _top_camera(scene)
    return scene


def _stratum(scene: bpy.types.Scene, seed: int, bounces: int = BOUNCES,
             samples: int = SPP_PER_SEED) -> None:
    configure_stratum(scene, seed, samples=samples, max_bounces=bounces)


def _cycles(scene: bpy.types.Scene, seed: int) -> None:
    configure_cycles(scene, seed, samples=SPP_PER_SEED, max_bounces=BOUNCES)


def _agree(name: str, build) -> None:
    out: Path = LINK_OUT / name
    cycles: Renders = render_two_seeds("cycles", _cycles, out, build, res=RES, block=BLOCK)
    stratum: Renders = render_two_seeds("stratum", _stratum, out, build, res=RES, block=BLOCK)
    compared = cycles.block_mean() > 0.01
    assert compared.any()
    assert_agreement(cycles, stratum, compared, f"{name} (max_bounces {BOUNCES})", out)


@pytest.mark.skipif(not HAS_LINKING, reason="light linking exists from Blender 4.0 on")
def test_light_linking_lights_only_the_included_receiver(library) -> None:
    reason = stratum_available()
    if reason:
        pytest.skip(reason)
    scene = _spheres_scene()
    bpy.data.objects["fill"].hide_render = True
    _stratum(scene, 1, bounces=0, samples=4)
    image, _ = render_exr(scene, LINK_OUT / "spheres_direct.exr", RES)
    half = RES // 2
    # Rows bottom to top, columns left to right: B and the floor's right half get nothing.
    assert np.count_nonzero(image[:, half + 1:]) == 0
    assert image[:, :half].max() > 0.05
    _agree("spheres", _spheres_scene)


@pytest.mark.skipif(not HAS_LINKING, reason="shadow linking exists from Blender 4.0 on")
def test_shadow_linking_ignores_the_excluded_occluder(library) -> None:
    reason = stratum_available()
    if reason:
        pytest.skip(reason)
    images = []
    for occluder in (True, False):
        scene = _sun_scene(occluder)
        _stratum(scene, 1, bounces=0, samples=4)
        image, _ = render_exr(scene, LINK_OUT / f"sun_direct_{occluder}.exr", RES)
        images.append(image)
    assert images[1].min() > 0.05
    np.testing.assert_array_equal(images[0], images[1])
    _agree("sun_area", functools.partial(_sun_scene, area=True))


@pytest.mark.skipif(HAS_LINKING, reason="Blender 3.x has no light linking")
def test_no_linking_is_read_before_blender_4(library) -> None:
    from stratum.export.light_linking import linking_sets

    scene = _sun_scene()
    assert not hasattr(bpy.types.Object, "light_linking")
    assert linking_sets(bpy.context.evaluated_depsgraph_get()) is None
    reason = stratum_available()
    if reason:
        pytest.skip(reason)
    _stratum(scene, 1, bounces=0, samples=1)
    image, _ = render_exr(scene, LINK_OUT / "no_linking.exr", RES)
    assert image.max() > 0.05


@pytest.mark.skipif(not HAS_LINKING, reason="light linking exists from Blender 4.0 on")
def test_a_linking_edit_asks_for_a_full_export(library) -> None:
    from stratum.export.sync import SceneSync
    from stratum.export.updates import IdUpdate

    _spheres_scene()
    lamp = bpy.data.objects["lamp"]
    with SceneSync() as sync:
        sync.full(bpy.context.evaluated_depsgraph_get())
        unchanged = sync.update(bpy.context.evaluated_depsgraph_get(),
                                [IdUpdate(lamp, True, False, False)])
        assert not unchanged.needs_full, unchanged.reason
        bpy.data.collections["receivers"].collection_objects[0].light_linking.link_state = \
            "EXCLUDE"
        depsgraph = bpy.context.evaluated_depsgraph_get()
        depsgraph.update()
        result = sync.update(depsgraph, [IdUpdate(lamp, True, False, False)])
        assert result.needs_full and "linking changed" in result.reason
