"""SceneSync: the exporter of a whole scene (the shape of Cycles' BlenderSync).

    sync = SceneSync()                   # owns the native scenes it fills
    summary = sync.full(depsgraph)       # the whole scene, into a new native scene
    renderer = native.Renderer(sync.scene)

full(): every mesh is sent once per distinct evaluated geometry (and material assignment) and
placed by one instance per depsgraph object instance (objects, collection instances, particle and
geometry-nodes instances). Instances carry the object's ray visibility and holdout (Object >
Visibility in Cycles) and, with motion blur, the transforms at shutter open and close.
Collections excluded from the view layer or disabled for render never reach
depsgraph.object_instances, so nothing else is needed for them. Objects Stratum does not render
are reported once per kind (unsupported.py); transforms are checked before they reach the
native scene (stratum/placement.py).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

import numpy as np

from .. import native
from .camera import convert_camera
from .common import ExportCancelled, ExportError, ExportSummary, instance_matrices
from .geometry import LIGHT_ID, object_geometry
from .instances import InstanceFlags, Placement, identity, renderable
from .lights import convert_light
from .materials import MaterialTable
from .motion import instance_key, shutter_transforms
from .unsupported import UnsupportedObjects
from .world import convert_environment, convert_world


class SceneSync:
    """The native scene of a depsgraph. Each full() fills a new scene from new_scene() and
    closes the previous one (renderers made from that keep rendering what it held)."""

    def __init__(self, new_scene: Callable[[], Any] = native.Scene) -> None:
        self._new_scene = new_scene
        self._scene: Any | None = None

    @property
    def scene(self) -> Any:
        if self._scene is None:
            raise RuntimeError("SceneSync.scene: nothing was exported yet (call full())")
        return self._scene

    def close(self) -> None:
        if self._scene is not None and hasattr(self._scene, "close"):
            self._scene.close()
        self._scene = None

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
        materials = MaterialTable(scene, summary)
        motion = shutter_transforms(depsgraph, bl_scene, frame_set, summary.warn)

        try:
            # Blender clamps lens to >= 1 mm, so a zero focal length comes only from files
            # other tools wrote; the native side rejects it (and any other bad value) by name.
            scene.set_camera(convert_camera(bl_scene, depsgraph))
        except native.StratumError as exc:
            raise ExportError(f"Camera '{bl_scene.camera.name}': {exc}") from exc
        try:
            scene.set_background(convert_world(bl_scene, summary))
            environment = convert_environment(bl_scene, summary)
            if environment is not None:
                scene.set_environment(environment.rgb, environment.strength,
                                      environment.rotation)
        except native.StratumError as exc:
            raise ExportError(f"World '{getattr(bl_scene.world, 'name', '')}': {exc}") from exc

        flags = InstanceFlags(getattr(depsgraph, "view_layer", None))
        unsupported = UnsupportedObjects()
        # Per geometry identity (original object, evaluated data): (mesh id, triangles);
        # LIGHT_ID for lights, -1 for nothing to draw.
        objects: dict[tuple[int, int], tuple[int, int]] = {}
        mesh_ids: dict[tuple[Any, ...], tuple[int, int]] = {}  # key -> (mesh id, triangles)
        placed: list[Placement] = []
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
                continue
            ident = identity(ob)
            parent = instance.parent if is_instance else None
            found = objects.get(ident)
            if found is None:
                found = (-1, 0) if unsupported.skip(ob) else \
                    object_geometry(ob, depsgraph, scene, materials, mesh_ids, summary)
                objects[ident] = found
                # A big mesh takes a tenth of a second or more to read out of Blender: Esc is
                # honoured after each one, not only every 256 instances.
                if should_stop is not None and found[1] > 0 and should_stop():
                    raise ExportCancelled("export cancelled")
            mesh_id = found[0]
            if mesh_id == LIGHT_ID:
                _add_light(ob.name, convert_light(ob, instance.matrix_world,
                                                  flags.get(ob, ident, parent)[0], summary),
                           scene, summary)
            elif mesh_id >= 0:
                moved = motion.get(instance_key(instance, ob)) if motion else None
                visibility, holdout = flags.get(ob, ident, parent)
                placed.append((index, mesh_id, ob.name, found[1], visibility, holdout, moved))
        unsupported.report(summary)
        matrices = instance_matrices(depsgraph, index + 1)
        _place(placed, renderable(placed, matrices, summary), matrices, scene, summary)

        summary.textures = materials.textures.count
        summary.export_seconds = time.perf_counter() - start
        return summary


def _evaluated_scene(depsgraph: Any) -> Any:
    return depsgraph.scene_eval if hasattr(depsgraph, "scene_eval") else depsgraph.scene


def _place(placed: list[Placement], kept: list[bool], matrices: np.ndarray, scene: Any,
           summary: ExportSummary) -> None:
    """Sends the kept placements: one add_instance_ex each for those that move, are hidden
    from some rays or held out, in order, then the rest in bulk."""
    plain_ids: list[int] = []
    plain_rows: list[int] = []
    plain_positions: list[int] = []
    sent = 0
    for position, (p, keep) in enumerate(zip(placed, kept, strict=True)):
        if not keep:
            continue
        row, mesh_id, name, n_tri, visibility, holdout, moved = p
        if moved is None and visibility == native.VISIBLE_ALL and not holdout:
            plain_ids.append(mesh_id)
            plain_rows.append(row)
            plain_positions.append(position)
        else:
            start_m, end_m = moved if moved is not None else (matrices[row], None)
            summary.moving_instances += moved is not None
            try:
                scene.add_instance_ex(native.Instance(mesh_id, start_m, end_m, visibility,
                                                      holdout))
            except native.StratumError as exc:
                raise ExportError(f"Object '{name}': {exc}") from exc
            sent += 1
        summary.instanced_triangles += n_tri
        summary.object_instances[name] = summary.object_instances.get(name, 0) + 1
        summary.object_triangles[name] = n_tri
    try:
        scene.add_instances(np.asarray(plain_ids, dtype=np.uint32), matrices[plain_rows])
    except native.StratumError as exc:
        where = f"Object '{placed[plain_positions[exc.index]][2]}'" \
            if exc.index is not None else "Instances"
        raise ExportError(f"{where}: {exc}") from exc
    summary.instances = sent + len(plain_positions)


def _add_light(name: str, light: native.Light | None, scene: Any,
               summary: ExportSummary) -> None:
    if light is None:
        return
    try:
        scene.add_light(light)
    except native.StratumError as exc:
        raise ExportError(f"Light '{name}': {exc}") from exc
    summary.lights += 1
