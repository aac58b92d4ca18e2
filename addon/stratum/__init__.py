"""Stratum: a Blender render engine backed by a native path tracer built to study sampling.

`import stratum` works without Blender (the CLI and the native binding do not need bpy);
register()/unregister() import the Blender modules lazily.
"""

from __future__ import annotations

bl_info = {
    "name": "Stratum",
    "author": "Stratum developers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Render Properties > Render Engine > Stratum",
    "description": "Path tracer with selectable sampling strategies",
    "category": "Render",
}

_registered = False


def register() -> None:
    """Registers properties, engine and panels (idempotent)."""
    global _registered
    if _registered:
        return
    from . import engine, properties, ui

    properties.register()
    engine.register()
    ui.register()
    _registered = True


def unregister() -> None:
    global _registered
    if not _registered:
        return
    from . import engine, properties, ui

    ui.unregister()
    engine.unregister()
    properties.unregister()
    _registered = False
