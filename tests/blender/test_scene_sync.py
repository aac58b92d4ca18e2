"""SceneSync: a change made in Blender after a full export is sent as live edits, and a renderer
made before the change then renders, bit for bit, what a fresh full export of the changed scene
renders; changes edits cannot express ask for a full export.

depsgraph.updates is filled only while an evaluation is reported: Depsgraph.update() has
emptied it again by the time it returns (Blender 3.4 and 5.0 alike), so the changes are kept by
a depsgraph_update_post handler (recorded_updates), as collect_updates' records, or update()
runs inside the handler itself (as a RenderEngine's view_update would).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

import bpy
import numpy as np
import pytest
from stratum.export.sync import SceneSync
from stratum.export.updates import IdUpdate, collect_updates

SETTINGS = {"width": 24, "height": 16, "samples": 8, "seed": 11, "threads": 2,
            "max_bounces": 3}


def _principled(name: str, color: tuple[float, float, float]) -> Any:
    material = bpy.data.materials.new(name)
    if material.node_tree is None:  # 5.0 makes the tree itself (use_nodes is deprecated)
        material.use_nodes = True
    material.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (*color, 1)
    return material


def _build(scene_builder: Callable[[], Any]) -> Any:
    """Camera, two cubes of their own materials, a point light and a grey world."""
    b = scene_builder()
    b.camera((0.0, -8.0, 0.5))
    b.mesh_object("Left", location=(-1.3, 0.0, 0.0), material=_principled("Red", (0.8, 0.2, 0.1)))
    b.mesh_object("Right", location=(1.3, 0.0, 0.0), material=_principled("Blue", (0.1, 0.3, 0.8)))
    b.point_light()
    b.world((0.05, 0.06, 0.08))
    return b


def _render(renderer: Any) -> np.ndarray:
    renderer.start()
    deadline = time.monotonic() + 120
    while not renderer.wait(100):
        assert time.monotonic() < deadline, "render did not finish"
    return renderer.read_pixels().copy()


def _fresh_render(library: Any, depsgraph: Any) -> np.ndarray:
    """The image of a new full export of the depsgraph, by a new renderer."""
    with SceneSync() as sync:
        sync.full(depsgraph)
        with library.Renderer(sync.scene, **SETTINGS) as renderer:
            return _render(renderer)


@contextmanager
def recorded_updates() -> Iterator[list[IdUpdate]]:
    """The depsgraph updates of the evaluations made inside the block."""
    updates: list[IdUpdate] = []

    def keep(scene: Any, depsgraph: Any) -> None:
        updates.extend(collect_updates(depsgraph))

    handlers = bpy.app.handlers.depsgraph_update_post
    handlers.append(keep)
    try:
        yield updates
    finally:
        handlers.remove(keep)


def _evaluated() -> Any:
    depsgraph = bpy.context.evaluated_depsgraph_get()
    depsgraph.update()
    return depsgraph


def _edit_in_blender(edit: Callable[[], None]) -> tuple[Any, list[IdUpdate]]:
    with recorded_updates() as updates:
        edit()
        depsgraph = _evaluated()
    return depsgraph, updates


def _move_object() -> None:
    bpy.data.objects["Left"].location = (-1.0, 0.5, 0.4)


def _recolour_material() -> None:
    bsdf = bpy.data.materials["Red"].node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (0.2, 0.8, 0.2, 1.0)


def _dim_light() -> None:
    bpy.data.lights["Light"].energy = 150.0


def _move_camera() -> None:
    camera = bpy.data.objects["Camera"]
    camera.location = (0.6, -7.0, 1.0)
    camera.rotation_euler = (math.pi / 2 - 0.05, 0.0, 0.08)


def _recolour_world() -> None:
    world = bpy.data.worlds["World"]
    world.color = (0.3, 0.2, 0.1)
    background = world.node_tree.nodes.get("Background") if world.node_tree else None
    if background is not None:
        background.inputs["Color"].default_value = (0.3, 0.2, 0.1, 1.0)


EDITS: dict[str, Callable[[], None]] = {
    "move an object": _move_object,
    "change a material's base colour": _recolour_material,
    "change a light's energy": _dim_light,
    "move the camera": _move_camera,
    "change the world colour": _recolour_world,
}


def _render_edit(library: Any, b: Any, edit: Callable[[], None],
                 edits: int) -> tuple[np.ndarray, np.ndarray]:
    """Sends the scene `b` built, renders it, makes `edit` in Blender and sends the update: it
    must go as `edits` live edits, and the render after it must equal a fresh full export of
    the edited scene bit for bit. Returns the renders before and after."""
    with SceneSync() as sync:
        sync.full(b.depsgraph())
        with library.Renderer(sync.scene, **SETTINGS) as renderer:
            before = _render(renderer)
            depsgraph, updates = _edit_in_blender(edit)
            assert updates, "no depsgraph update was reported"
            result = sync.update(depsgraph, updates)
            assert not result.needs_full, result.reason
            assert result.edits == edits
            after = _render(renderer)
    assert np.array_equal(after, _fresh_render(library, depsgraph))
    return before, after


@pytest.mark.parametrize("edit", list(EDITS))
def test_an_edit_renders_as_a_fresh_full_export(scene_builder: Any, library: Any,
                                                edit: str) -> None:
    before, after = _render_edit(library, _build(scene_builder), EDITS[edit], edits=1)
    assert not np.array_equal(after, before)


def test_moving_an_instancer_edits_every_instance_it_placed(scene_builder: Any,
                                                            library: Any) -> None:
    b = _build(scene_builder)
    props = bpy.data.collections.new("Props")
    for name, x in (("PropA", -0.6), ("PropB", 0.6)):
        ob = bpy.data.objects.new(name, b.mesh_data(name))
        ob.location = (x, 0.0, 1.2)
        ob.scale = (0.3, 0.3, 0.3)
        props.objects.link(ob)
    instancer = bpy.data.objects.new("Instancer", None)
    instancer.instance_type = "COLLECTION"
    instancer.instance_collection = props
    b.link(instancer)
    _render_edit(library, b, lambda: setattr(instancer, "location", (0.0, -1.0, -0.6)), edits=2)


def test_ray_visibility_and_holdout_are_edits_of_instances_seen_by_some_rays(
        scene_builder: Any, library: Any) -> None:
    b = _build(scene_builder)
    left = bpy.data.objects["Left"]
    left.visible_shadow = False  # sent by itself, before the instances every ray sees
    before, after = _render_edit(library, b, lambda: setattr(left, "is_holdout", True), edits=1)
    assert not np.array_equal(after, before)


def _index_passes(library: Any, scene: Any, renderer: Any = None) -> np.ndarray:
    """IndexOB and IndexMA (height, width, 2) of a render of `scene`, by `renderer` or a new
    one."""
    if renderer is None:
        with library.Renderer(scene, **SETTINGS, passes="IndexOB,IndexMA") as fresh:
            return _index_passes(library, scene, fresh)
    _render(renderer)
    return np.concatenate([renderer.read_pass("IndexOB"), renderer.read_pass("IndexMA")], axis=-1)


def test_pass_index_edits_reach_the_index_passes(scene_builder: Any, library: Any) -> None:
    b = _build(scene_builder)
    left = bpy.data.objects["Left"]
    left.pass_index = 2  # sent by itself, before the instances every ray sees

    def edit() -> None:
        left.pass_index = 5
        bpy.data.materials["Blue"].pass_index = 8

    with SceneSync() as sync:
        sync.full(b.depsgraph())
        with library.Renderer(sync.scene, **SETTINGS, passes="IndexOB,IndexMA") as renderer:
            before = _index_passes(library, sync.scene, renderer)
            depsgraph, updates = _edit_in_blender(edit)
            result = sync.update(depsgraph, updates)
            assert not result.needs_full, result.reason
            assert result.edits == 2
            after = _index_passes(library, sync.scene, renderer)
    # Both cubes are in view: Left (object 2, then 5; material 0) and Right (object 0;
    # material 0, then 8), around them the world (0).
    assert set(np.unique(before[..., 0]).tolist()) == {0.0, 2.0}
    assert set(np.unique(before[..., 1]).tolist()) == {0.0}
    assert set(np.unique(after[..., 0]).tolist()) == {0.0, 5.0}
    assert set(np.unique(after[..., 1]).tolist()) == {0.0, 8.0}
    with SceneSync() as sync:
        sync.full(depsgraph)
        assert np.array_equal(after, _index_passes(library, sync.scene))


def test_update_inside_the_depsgraph_handler_reads_depsgraph_updates(scene_builder: Any,
                                                                      library: Any) -> None:
    b = _build(scene_builder)
    results = []
    with SceneSync() as sync:
        sync.full(b.depsgraph())

        def sync_now(scene: Any, depsgraph: Any) -> None:
            results.append(sync.update(depsgraph))

        bpy.app.handlers.depsgraph_update_post.append(sync_now)
        try:
            _move_object()
            depsgraph = _evaluated()
        finally:
            bpy.app.handlers.depsgraph_update_post.remove(sync_now)
        assert [r.edits for r in results if r.edits] == [1]
        assert not any(r.needs_full for r in results)
        with library.Renderer(sync.scene, **SETTINGS) as renderer:
            after = _render(renderer)
    assert np.array_equal(after, _fresh_render(library, depsgraph))


def _light_falloff_on_the_light() -> None:
    """The light's Emission Strength from a Light Falloff (Linear, Strength 20) named Falloff."""
    light = bpy.data.lights["Light"]
    light.use_nodes = True
    nt = light.node_tree
    emission = next(n for n in nt.nodes if n.bl_idname == "ShaderNodeEmission")
    falloff = nt.nodes.new("ShaderNodeLightFalloff")
    falloff.name = "Falloff"
    falloff.inputs["Strength"].default_value = 20.0
    nt.links.new(falloff.outputs["Linear"], emission.inputs["Strength"])


def test_a_lamp_program_edit_renders_as_a_fresh_full_export(scene_builder: Any,
                                                            library: Any) -> None:
    """A lamp whose program (its Light Falloff) changes: the program is replaced in place."""
    b = _build(scene_builder)
    _light_falloff_on_the_light()
    falloff = bpy.data.lights["Light"].node_tree.nodes["Falloff"]
    before, after = _render_edit(
        library, b, lambda: setattr(falloff.inputs["Strength"], "default_value", 60.0), edits=1)
    assert not np.array_equal(after, before)


def _move_a_vertex() -> None:
    mesh = bpy.data.objects["Left"].data
    mesh.vertices[0].co = (-1.5, -1.5, -1.5)
    mesh.update()


@pytest.mark.parametrize(("edit", "reason"), [
    (_move_a_vertex, "Left"),
    (lambda: bpy.context.scene.collection.objects.unlink(bpy.data.objects["Right"]),
     "objects were"),
    (lambda: setattr(bpy.data.lights["Light"], "energy", -1.0), "Light 'Light'"),
    # A lamp program is added to the scene's structure only by a full export.
    (_light_falloff_on_the_light, "Light 'Light': its nodes now depend on the distance"),
    # A full export sends instances every ray sees, not held out, after all others.
    (lambda: setattr(bpy.data.objects["Right"], "visible_glossy", False), "Object 'Right'"),
    # The view layer's Filter and overrides change what a full export sends (view_layer.py).
    (lambda: setattr(bpy.context.view_layer, "use_sky", False), "View layer"),
    (lambda: setattr(bpy.context.view_layer, "material_override", bpy.data.materials["Red"]),
     "View layer"),
])
def test_what_edits_cannot_express_asks_for_a_full_export(scene_builder: Any, library: Any,
                                                          edit: Callable[[], None],
                                                          reason: str) -> None:
    b = _build(scene_builder)
    with SceneSync() as sync:
        sync.full(b.depsgraph())
        depsgraph, updates = _edit_in_blender(edit)
        result = sync.update(depsgraph, updates)
        assert result.needs_full and reason in result.reason and result.edits == 0
        # Until full() runs again, whatever is reported.
        assert sync.update(depsgraph, []).needs_full
        sync.full(depsgraph)
        again = sync.update(depsgraph, [])
        assert not again.needs_full and again.edits == 0


def test_an_update_without_changes_sends_nothing(scene_builder: Any, library: Any) -> None:
    b = _build(scene_builder)
    with SceneSync() as sync:
        sync.full(b.depsgraph())
        depsgraph, updates = _edit_in_blender(
            lambda: setattr(bpy.data.objects["Left"], "location", (-1.3, 0.0, 0.0)))
        result = sync.update(depsgraph, updates)
    assert not result.needs_full and result.edits == 0
