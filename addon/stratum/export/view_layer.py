"""What the view layer being rendered changes of its scene, read as Cycles reads it
(intern/cycles/blender/sync.cpp BlenderSync::sync_view_layer, the same in 3.4 and 5.0):

* Filter > Environment (use_sky) off: the world emits nothing to any ray, seen or lighting (Cycles'
  Background::get_shader gives its empty shader); the film's alpha stays as with a black world.
* Filter > Surfaces (use_solid) off: no mesh geometry (meshes, curves and text, which Stratum
  renders as meshes); lights stay.
* Override > Material (material_override): every material slot of every geometry object, and
  objects without slots, render with it; lights and the world keep theirs.
* Override > World (world_override, Blender 5.0; absent in 3.4): the world the layer renders
  with, in place of scene.world (Cycles' mist settings stay the scene world's).
* Filter > Motion Blur (use_motion_blur): motion blur needs it and the scene's, in F12 renders
  only; Cycles' viewport renders no motion blur.

These are Blender's own view-layer settings, not Cycles' Light Paths: they always apply,
whatever scene.stratum.light_paths says. The layer's samples (View Layer > Use > Samples with
scene.cycles.use_layer_samples) are a render setting: engine/frame.py layer_samples.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class LayerWorld:
    """The world a view layer renders with (None: none, black): what world.py reads of a
    scene (its `world`)."""

    world: Any | None


@dataclass(frozen=True)
class ViewLayerFilter:
    """What a view layer changes of the export (module docstring)."""

    surfaces: bool = True
    material_override: Any | None = None
    world: LayerWorld | None = None  # None: the scene's own world
    motion_blur: bool = True

    def key(self) -> tuple[Any, ...]:
        """What a live update compares: a change of any of it needs a full export."""
        return (self.surfaces, _pointer(self.material_override),
                None if self.world is None else _pointer(self.world.world), self.motion_blur)


def view_layer_filter(view_layer: Any | None, viewport: bool = False) -> ViewLayerFilter:
    """The filter of `view_layer` (None, as for a depsgraph without one: no change), for an F12
    render or, with `viewport`, for the Rendered viewport (no motion blur, as Cycles)."""
    if view_layer is None:
        return ViewLayerFilter(motion_blur=not viewport)
    world = None
    if not getattr(view_layer, "use_sky", True):
        world = LayerWorld(None)
    else:
        override = getattr(view_layer, "world_override", None)
        if override is not None:
            world = LayerWorld(override)
    return ViewLayerFilter(
        surfaces=bool(getattr(view_layer, "use_solid", True)),
        material_override=getattr(view_layer, "material_override", None),
        world=world,
        motion_blur=not viewport and bool(getattr(view_layer, "use_motion_blur", True)))


def _pointer(data: Any | None) -> int:
    if data is None:
        return 0
    original = getattr(data, "original", None) or data
    return int(original.as_pointer())
