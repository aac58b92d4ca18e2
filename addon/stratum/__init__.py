"""Stratum: a Blender render engine backed by a native path tracer built to study sampling.

`import stratum` works without Blender (the CLI and the native binding do not need bpy);
register()/unregister() import the Blender modules lazily.
"""

from __future__ import annotations

from .version import __version__

# Blender 3.x reads bl_info without running this file (ast.literal_eval), so it holds literals
# only. Its "version" is written by `make package` from blender_manifest.toml, the one place the
# version lives; Blender 4.2+ reads the manifest itself and ignores bl_info for an extension.
bl_info = {
    "name": "Stratum",
    "author": "Stratum developers",
    "blender": (3, 4, 0),
    "location": "Render Properties > Render Engine > Stratum",
    "description": "Path tracer with selectable sampling strategies",
    "category": "Render",
}

__all__ = ["__version__", "bl_info", "register", "unregister"]

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
