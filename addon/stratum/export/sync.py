"""SceneSync: one exporter for a whole scene and for what changed since (Cycles' BlenderSync).

    summary = export_scene(depsgraph, native_scene)   # once, into a scene the caller owns

    sync = SceneSync()                   # owns the native scenes it fills
    summary = sync.full(depsgraph)       # the whole scene, into a new native scene
    renderer = native.Renderer(sync.scene)
    ...                                  # the scene is edited in Blender
    result = sync.update(depsgraph)      # while depsgraph.updates is reported (updates.py)
    if result.needs_full:                # result.reason says why
        sync.full(depsgraph)             # a new native scene: make a new renderer from it
    elif result.edits:
        renderer.start()                 # from sample 0; only what changed is rebuilt

full(): every mesh is sent once per distinct evaluated geometry (and material assignment) and
placed by one instance per depsgraph object instance (objects, collection instances, particle and
geometry-nodes instances). Instances carry the object's ray visibility and holdout (Object >
Visibility in Cycles) and, with motion blur, the transforms at shutter open and close.
Collections excluded from the view layer or disabled for render never reach
depsgraph.object_instances, so nothing else is needed for them. Objects Stratum does not render
are reported once per kind (unsupported.py); transforms are checked before they reach the
native scene (placement.py).

update() sends what differs from what was sent as live edits (stratum.h "live edits"), which a
renderer made from the scene applies at its next start with the image a fresh full export of
the edited scene gives, bit for bit (object_sync.py: instances and lights):
  * object transforms, ray visibility and holdout: set_instance for every native instance the
    object placed, itself or as an instancer;
  * lights: set_light;
  * materials: set_material / set_closure_material, whatever their closures become, as long
    as their image textures stay as they were (materials.py);
  * the camera: set_camera; the world: set_background / set_environment.
It sends nothing and asks for a full export (needs_full, with the reason) for what the native
scene can only take by being built anew, or what a fresh export would send differently:
  * geometry: mesh edits, modifiers, material slots (Blender reports those as geometry updates);
  * objects added, removed, shown, hidden or instanced differently;
  * a light or an instance that starts or stops being rendered (a degenerate transform, a
    light turned off), an instance whose visibility and holdout change between "all rays, not
    held out" and anything else (a full export places those two kinds apart), and any
    instance change with motion blur on (its shutter transforms need other frames evaluated);
  * the motion blur settings; a material's image textures or their UV layer, or an image
    one textures with (textures are part of the native scene's structure);
  * the world losing its environment image (a native scene has no call to drop one);
  * the view layer's Filter or overrides (view_layer.py: Environment, Surfaces, material and
    world override, motion blur), which decide what a full export sends.
Until full() runs again after that, every update() asks for it.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from functools import partial
from typing import Any

import numpy as np

from .. import native
from .camera import convert_camera
from .common import (
    ExportCancelled,
    ExportError,
    ExportSummary,
    FullExportNeeded,
    comparable,
    instance_matrices,
    named_edit,
)
from .instances import (
    InstanceFlags,
    Placement,
    lightgroup_numbers,
    object_random_id,
    original_pointer,
    renderable,
)
from .light_linking import NO_LINKS, Links, linking_sets
from .lights import ConvertedLight, convert_light
from .materials import MaterialTable
from .motion import instance_key, shutter_settings, shutter_transforms
from .object_sync import ExportedObjects, RowSignature, object_edits
from .placements import LIGHT_ROW, UNSEEN, Geometry, place, row_template
from .unsupported import UnsupportedObjects
from .updates import Changes, IdUpdate, collect_updates, sort_updates
from .view_layer import ViewLayerFilter, view_layer_filter
from .world import (
    Environment,
    WorldProgram,
    convert_environment,
    convert_world,
    convert_world_program,
)


@dataclass
class UpdateResult:
    needs_full: bool = False
    reason: str = ""  # why a full export is needed, naming what changed
    edits: int = 0  # live edits sent; 0: the renderer's image is still the scene's
    warnings: list[str] = field(default_factory=list)


@dataclass
class _Exported:
    """What the last sync sent, for update() to compare with."""

    objects: ExportedObjects
    materials: MaterialTable
    camera: tuple[Any, ...]  # comparable(native.Camera)
    world: int  # original pointer of the scene's world
    background: tuple[float, float, float]
    environment: Environment | None
    shutter: tuple[bool, float, str]  # motion.shutter_settings
    world_program: tuple[Any, ...] | None = None  # WorldProgram.key()
    world_program_id: int | None = None
    layer: tuple[Any, ...] = ()  # ViewLayerFilter.key()
    linking: tuple[Any, ...] | None = None  # LinkingSets.key(), None without linking


class SceneSync:
    """The native scene of a depsgraph, kept in step with it. Each full() fills a new scene
    from new_scene() and closes the previous one (renderers made from that keep rendering
    what it held). require_camera=False (the viewport, which sets its own view's camera): a
    scene without an active camera is exported without one instead of being an error.
    viewport=True: the view layer's filter as Cycles' viewport applies it (view_layer.py)."""

    def __init__(self, new_scene: Callable[[], Any] = native.Scene,
                 require_camera: bool = True, viewport: bool = False) -> None:
        self._new_scene = new_scene
        self._require_camera = require_camera
        self._viewport = viewport
        self._scene: Any | None = None
        self._exported: _Exported | None = None
        self._stale = "nothing was exported yet"

    @property
    def scene(self) -> Any:
        if self._scene is None:
            raise RuntimeError("SceneSync.scene: nothing was exported yet (call full())")
        return self._scene

    def close(self) -> None:
        if self._scene is not None and hasattr(self._scene, "close"):
            self._scene.close()
        self._scene = None
        self._exported = None
        self._stale = "nothing was exported yet"

    def __enter__(self) -> SceneSync:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def full(self, depsgraph: Any, should_stop: Callable[[], bool] | None = None,
             frame_set: Callable[[int, float], None] | None = None) -> ExportSummary:
        """Exports the evaluated scene of `depsgraph` into a new native scene (self.scene).

        Raises ExportError (message names the object) for data that cannot be rendered and
        ExportCancelled if should_stop() becomes true. Unsupported features that have a
        fallback are collected in summary.warnings (one per material node / light / world /
        object). frame_set(frame, subframe) re-evaluates the depsgraph at another time
        (RenderEngine.frame_set during a render); it is needed for motion blur only."""
        self.close()
        start = time.perf_counter()
        self._scene = scene = self._new_scene()
        summary = ExportSummary()
        bl_scene = _evaluated_scene(depsgraph)
        layer = self._layer(depsgraph)
        world_scene = layer.world or bl_scene
        materials = MaterialTable(scene, summary, _evaluated(layer.material_override, depsgraph))
        motion = shutter_transforms(depsgraph, bl_scene, frame_set, summary.warn) \
            if layer.motion_blur else None

        try:
            # Blender clamps lens to >= 1 mm, so a zero focal length comes only from files
            # other tools wrote; the native side rejects it (and any other bad value) by name.
            camera = self._camera(bl_scene, depsgraph)
            if camera is not None:
                scene.set_camera(camera)
        except native.StratumError as exc:
            raise ExportError(f"Camera '{bl_scene.camera.name}': {exc}") from exc
        try:
            background = convert_world(world_scene, summary)
            scene.set_background(background)
            groups = lightgroup_numbers(getattr(depsgraph, "view_layer", None))
            scene.set_world_lightgroup(groups.get(getattr(world_scene.world, "lightgroup", ""), 0))
            environment = convert_environment(world_scene, summary)
            if environment is not None:
                scene.set_environment(environment.rgb, environment.strength,
                                      environment.rotation)
            world_program = convert_world_program(world_scene, summary)
            world_program_id = None
            if world_program is not None:
                world_program_id = _send_world_program(scene, world_program, None)
        except native.StratumError as exc:
            raise ExportError(f"World '{getattr(world_scene.world, 'name', '')}': {exc}") from exc

        exported = ExportedObjects(motion_blur=motion is not None)
        flags = InstanceFlags(getattr(depsgraph, "view_layer", None))
        unsupported = UnsupportedObjects()
        # Per geometry identity (original object, evaluated data): (mesh id, triangles);
        # LIGHT_ID for lights, -1 for nothing to draw.
        objects: dict[tuple[int, int], tuple[int, int]] = {}
        mesh_ids: dict[tuple[Any, ...], tuple[int, int]] = {}  # key -> (mesh id, triangles)
        # Per row signature (what is drawn, under which instancer): what its rows place, (mesh
        # id, object name, triangles, flags); LIGHT_ROW, or None for nothing to draw. 10 000
        # instances of one object read its name, geometry and flags once, not per row.
        templates: dict[RowSignature, Any] = {}
        placed: list[Placement] = []
        rows = exported.rows
        instancers: dict[int, int] = {}  # evaluated instancer pointer -> original pointer
        # Per placed row: (random_id, object colour RGBA), what Object Info reads.
        object_info: dict[int, tuple[int, tuple[float, ...]]] = {}
        # Light and shadow linking (Blender 4.0+): the sets of every placed row and lamp.
        link_sets = linking_sets(depsgraph)
        row_links: dict[int, Links] = {}
        light_links: dict[int, Links] = {}  # native light index -> links
        index = -1
        for index, instance in enumerate(depsgraph.object_instances):
            if should_stop is not None and index % 256 == 0 and should_stop():
                raise ExportCancelled("export cancelled")
            is_instance = instance.is_instance
            # instance.object is what is drawn: for an instance, a temporary object (valid
            # during this iteration only) that carries the instance's own data -- a
            # geometry-nodes instance of mesh data has no object of its own (instance_object
            # is its instancer).
            ob = instance.object
            # show_self is off for an instancer whose own geometry is hidden in renders (Cycles
            # skips those too: blender/object.cpp).
            if ob is None or not (is_instance or instance.show_self):
                rows.append(None)
                continue
            # instances.identity and object_sync.row_signature, inlined (this loop runs once
            # per instance); an instancer's original is looked up once.
            data = ob.data
            ident = (ob.original.as_pointer(), data.as_pointer() if data is not None else 0)
            parent = instance.parent if is_instance else None
            if parent is None:
                signature = (ident, 0)
            else:
                evaluated = parent.as_pointer()
                instancer = instancers.get(evaluated)
                if instancer is None:
                    instancer = instancers[evaluated] = original_pointer(parent)
                signature = (ident, instancer)
            rows.append(signature)
            template = templates.get(signature, UNSEEN)
            if template is UNSEEN:
                template = row_template(ob, ident, parent, Geometry(
                    objects, mesh_ids, depsgraph, scene, materials, unsupported, summary,
                    should_stop, layer.surfaces), flags)
                templates[signature] = template
            if template is LIGHT_ROW:
                light_flags = flags.get(ob, ident, parent)
                light = convert_light(ob, instance.matrix_world, light_flags.visibility, summary,
                                      light_flags.lightgroup)
                exported.lights[index] = _add_light(ob.name, light, scene, summary, exported)
                if light is not None:
                    exported.sent_lights.append(light.key())
                    if link_sets is not None and exported.lights[index] is not None:
                        light_links[exported.lights[index]] = link_sets.links(ob, parent)
            elif template is not None:
                moved = motion.get(instance_key(instance, ob)) if motion else None
                placed.append((index, *template, moved))
                # DepsgraphObjectInstance.random_id is a signed int; Cycles reads it unsigned.
                random_id = (instance.random_id & 0xFFFFFFFF) if is_instance else \
                    object_random_id(ob.name)
                object_info[index] = (random_id, tuple(ob.color))
                if link_sets is not None:
                    row_links[index] = link_sets.links(ob, parent)
        unsupported.report(summary)
        matrices = instance_matrices(depsgraph, index + 1)
        place(placed, renderable(placed, matrices, summary), matrices, scene, summary, exported)
        _send_object_info(scene, exported, object_info, summary.instances)
        if link_sets is not None:
            _send_links(scene, exported, row_links, light_links, summary)

        summary.textures = materials.textures.count
        self._exported = _Exported(exported, materials,
                                   comparable(camera) if camera is not None else (),
                                   original_pointer(world_scene.world), background, environment,
                                   shutter_settings(bl_scene),
                                   world_program.key() if world_program is not None else None,
                                   world_program_id, layer.key(),
                                   link_sets.key() if link_sets is not None else None)
        self._stale = ""
        summary.export_seconds = time.perf_counter() - start
        return summary

    def update(self, depsgraph: Any, updates: Iterable[IdUpdate] | None = None) -> UpdateResult:
        """Sends the changes `updates` (default: depsgraph.updates, see updates.py) report as
        live edits, or sends nothing and says a full export is needed (module docstring).
        Raises ExportError as full() would for data that cannot be rendered."""
        exported = self._exported
        if exported is None or self._stale:
            return UpdateResult(needs_full=True, reason=self._stale)
        changes = sort_updates(collect_updates(depsgraph) if updates is None else updates)
        summary = ExportSummary()
        # Stale until every edit is sent: what was sent is recorded as the edits are made.
        self._stale = "an earlier update failed"
        try:
            edits = self._edits(depsgraph, exported, changes, summary)
        except FullExportNeeded as exc:
            self._stale = str(exc)
            return UpdateResult(needs_full=True, reason=str(exc), warnings=summary.warnings)
        for edit in edits:
            edit()
        self._stale = ""
        return UpdateResult(edits=len(edits), warnings=summary.warnings)

    def _edits(self, depsgraph: Any, exported: _Exported, changes: Changes,
               summary: ExportSummary) -> list[Callable[[], None]]:
        if changes.geometry:
            raise FullExportNeeded(f"{changes.geometry}: its geometry changed")
        bl_scene = _evaluated_scene(depsgraph)
        if changes.scene and shutter_settings(bl_scene) != exported.shutter:
            raise FullExportNeeded(f"Scene '{bl_scene.name}': its motion blur settings changed")
        layer = self._layer(depsgraph)
        if layer.key() != exported.layer:
            raise FullExportNeeded("View layer: its filter or overrides changed")
        if changes.objects or changes.collections or changes.scene:
            link_sets = linking_sets(depsgraph)
            if (link_sets.key() if link_sets is not None else None) != exported.linking:
                raise FullExportNeeded("the light or shadow linking changed")
        scene = self.scene
        edits = object_edits(depsgraph, changes, exported.objects, scene, summary)
        edits += _material_edits(depsgraph, changes, exported.materials, summary)
        edits += _world_edits(layer.world or bl_scene, changes, exported, scene, summary)
        camera = self._camera(bl_scene, depsgraph)
        if camera is not None and comparable(camera) != exported.camera:
            exported.camera = comparable(camera)
            edits.append(named_edit(f"Camera '{bl_scene.camera.name}'",
                                    partial(scene.set_camera, camera)))
        return edits


    def _layer(self, depsgraph: Any) -> ViewLayerFilter:
        return view_layer_filter(getattr(depsgraph, "view_layer", None), self._viewport)

    def _camera(self, bl_scene: Any, depsgraph: Any) -> native.Camera | None:
        if bl_scene.camera is None and not self._require_camera:
            return None
        return convert_camera(bl_scene, depsgraph)


def export_scene(
    depsgraph: Any,
    scene: Any,
    should_stop: Callable[[], bool] | None = None,
    frame_set: Callable[[int, float], None] | None = None,
) -> ExportSummary:
    """Exports the evaluated scene of `depsgraph` into `scene` (a native.Scene, or a stand-in
    with its methods), which the caller owns: SceneSync.full, whose docstring says what is
    raised and reported."""
    return SceneSync(lambda: scene).full(depsgraph, should_stop, frame_set)


def _evaluated_scene(depsgraph: Any) -> Any:
    return depsgraph.scene_eval if hasattr(depsgraph, "scene_eval") else depsgraph.scene


def _evaluated(data: Any | None, depsgraph: Any) -> Any | None:
    """The depsgraph's evaluated copy of a data-block (as object slots hold them)."""
    if data is None or not hasattr(data, "evaluated_get"):
        return data
    return data.evaluated_get(depsgraph)


def _material_edits(depsgraph: Any, changes: Changes, materials: MaterialTable,
                    summary: ExportSummary) -> list[Callable[[], None]]:
    for pointer, image in changes.images.items():
        if any(pointer in sent.images for sent in materials.sent.values()):
            raise FullExportNeeded(f"Image '{image.name}': a material textures with it")
    edits = []
    for pointer, material in changes.materials.items():
        mat_id = materials.ids.get(pointer)
        if mat_id is None:
            continue  # not on anything exported; assigning it is a geometry update
        edit = materials.change(mat_id, material.evaluated_get(depsgraph), summary)
        if edit is not None:
            edits.append(edit)
    return edits


def _world_edits(bl_scene: Any, changes: Changes, exported: _Exported, scene: Any,
                 summary: ExportSummary) -> list[Callable[[], None]]:
    world = bl_scene.world
    pointer = original_pointer(world)
    if not (changes.worlds or pointer != exported.world
            or (changes.images and exported.environment is not None)):
        return []
    exported.world = pointer
    name = f"World '{getattr(world, 'name', '')}'"
    background = convert_world(bl_scene, summary)
    environment = convert_environment(bl_scene, summary)
    if environment is None and exported.environment is not None:
        raise FullExportNeeded(f"{name}: its environment image is gone")
    world_program = convert_world_program(bl_scene, summary)
    if (world_program is None) != (exported.world_program is None):
        raise FullExportNeeded(f"{name}: its Background is now driven by nodes, or no longer")
    edits = []
    if world_program is not None and world_program.key() != exported.world_program:
        exported.world_program = world_program.key()
        edits.append(named_edit(name, partial(_send_world_program, scene, world_program,
                                              exported.world_program_id)))
    if background != exported.background:
        exported.background = background
        edits.append(named_edit(name, partial(scene.set_background, background)))
    if environment is not None and not _same_environment(environment, exported.environment):
        exported.environment = environment
        edits.append(named_edit(name, partial(scene.set_environment, environment.rgb,
                                              environment.strength, environment.rotation)))
    return edits


def _send_object_info(scene: Any, exported: ExportedObjects,
                      object_info: dict[int, tuple[int, tuple[float, ...]]], count: int) -> None:
    """Object Info's Random (Cycles: random_id / 0xFFFFFFFF, in float) and Color of every native
    instance, in one call."""
    if count == 0:
        return
    random_ids = np.zeros(count, dtype=np.uint32)
    colors = np.ones((count, 4), dtype=np.float32)
    for row, native_index in zip(exported.instance_rows.tolist(), exported.indices, strict=True):
        if native_index >= 0:
            random_id, color = object_info[row]
            random_ids[native_index] = random_id
            colors[native_index] = color
    random = random_ids.astype(np.float32) * np.float32(1.0 / 0xFFFFFFFF)
    try:
        scene.set_instance_object_info(0, np.minimum(random, np.float32(1.0)), colors)
    except native.StratumError as exc:
        raise ExportError(f"Object Info: {exc}") from exc


def _send_links(scene: Any, exported: ExportedObjects, row_links: dict[int, Links],
               light_links: dict[int, Links], summary: ExportSummary) -> None:
    """The light and shadow linking sets of every native instance and lamp, one call each."""
    def columns(links: list[Links]) -> tuple[np.ndarray, ...]:
        return (np.array([x.receiver_light_set for x in links], dtype=np.uint8),
                np.array([x.blocker_shadow_set for x in links], dtype=np.uint8),
                np.array([x.light_set_membership for x in links], dtype=np.uint64),
                np.array([x.shadow_set_membership for x in links], dtype=np.uint64))

    instances = [NO_LINKS] * summary.instances
    for row, native_index in zip(exported.instance_rows.tolist(), exported.indices, strict=True):
        if native_index >= 0:
            instances[native_index] = row_links[row]
    lights = [light_links.get(i, NO_LINKS) for i in range(summary.lights)]
    try:
        if instances:
            scene.set_light_linking(False, 0, *columns(instances))
        if lights:
            scene.set_light_linking(True, 0, None, None, *columns(lights)[2:])
    except native.StratumError as exc:
        raise ExportError(f"Light linking: {exc}") from exc


def _send_world_program(scene: Any, world: WorldProgram, program_id: int | None) -> int:
    """Adds (or, given its id, replaces) the world's program and bakes it; returns its id."""
    if program_id is None:
        program_id = scene.add_shader_program(world.program)
    else:
        scene.set_shader_program(program_id, world.program)
    scene.set_background_program(program_id, world.register, world.width, world.height)
    return program_id


def _same_environment(a: Environment, b: Environment | None) -> bool:
    return b is not None and a.strength == b.strength and np.array_equal(a.rgb, b.rgb) \
        and np.array_equal(a.rotation, b.rotation)


def _add_light(name: str, light: ConvertedLight | None, scene: Any, summary: ExportSummary,
               exported: ExportedObjects) -> int | None:
    """The native index of `light` once added, with its program; None for no light."""
    if light is None:
        return None
    index = summary.lights
    try:
        scene.add_light(light.light)
        if light.program is not None:
            program_id = scene.add_shader_program(light.program.program)
            scene.set_light_program(index, program_id, light.program.register)
            exported.light_programs[index] = program_id
    except native.StratumError as exc:
        raise ExportError(f"Light '{name}': {exc}") from exc
    summary.lights += 1
    return index
