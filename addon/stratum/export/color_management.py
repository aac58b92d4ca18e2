"""Image colour spaces the native library cannot convert, converted with Blender's own OpenColorIO.

The native library links the system's OpenColorIO (Debian 12: 2.1.2), which reads the configs
of Blender 3.x and 4.x (`ocio_profile_version: 2` in 3.4, 4.2 and 4.5) but refuses Blender
5.0's (2.4); for such a config it converts only its built-in names (sRGB, Linear, Linear
Rec.709, Non-Color, Raw; see native/src/texture/color_conversion.h) and rejects the others
(ACEScg, Linear Rec.2020, AgX Log, ...). Blender 5.0 ships PyOpenColorIO built against its own
OpenColorIO, which reads its config: with it the exporter converts such images itself, as
Blender would, and hands the native side scene-linear pixels. Where the native side reads the
config (Debian's 3.4, which ships no PyOpenColorIO, the 4.2 and 4.5 wheels) no image needs it.

| question                                  | answered by                                       |
|-------------------------------------------|---------------------------------------------------|
| does the native side convert this space?  | a one-texel probe texture in a scratch native     |
|                                           | scene, per (config, colour space), cached: the C  |
|                                           | ABI reports ERROR_INVALID_ARGUMENT for a space it |
|                                           | cannot convert and names no OCIO version          |
| is PyOpenColorIO there?                   | `import PyOpenColorIO`, else the copy under       |
|                                           | Blender's own python/lib/pythonX.Y/site-packages  |
|                                           | (the bpy wheel does not put it on sys.path)       |
| the conversion                            | config.getProcessor(space, scene_linear role),    |
|                                           | as the native side does with a readable config    |
"""

from __future__ import annotations

import importlib.util
import os
import sys
from functools import cache, lru_cache
from typing import Any

import bpy
import numpy as np

from .. import native

MODULE_NAME = "PyOpenColorIO"


@lru_cache(maxsize=1)
def blender_pyopencolorio() -> Any | None:
    """Blender's PyOpenColorIO module, or None when this Blender ships none (Debian's 3.4).

    An installed Blender has its bundled site-packages on sys.path; the bpy wheel keeps it in
    bpy/<version>/python/lib/pythonX.Y/site-packages without adding it, so only that one
    package is loaded from there (the rest of that directory is not put on sys.path)."""
    try:
        import PyOpenColorIO

        return PyOpenColorIO
    except ImportError:
        pass
    python_dir = f"python{sys.version_info.major}.{sys.version_info.minor}"
    for kind in ("LOCAL", "SYSTEM"):
        root = bpy.utils.resource_path(kind)
        if not root:
            continue
        package = os.path.join(root, "python", "lib", python_dir, "site-packages", MODULE_NAME)
        init = os.path.join(package, "__init__.py")
        if not os.path.isfile(init):
            continue
        spec = importlib.util.spec_from_file_location(MODULE_NAME, init,
                                                      submodule_search_locations=[package])
        if spec is None or spec.loader is None:
            continue
        module = importlib.util.module_from_spec(spec)
        sys.modules[MODULE_NAME] = module  # its __init__ imports its extension relatively
        try:
            spec.loader.exec_module(module)
        except ImportError:
            del sys.modules[MODULE_NAME]
            continue
        return module
    return None


@cache
def native_converts(config_path: str | None, color_space: str) -> bool:
    """Whether stratum_scene_add_texture converts `color_space` with `config_path` itself."""
    probe = native.Texture(pixels=np.full((1, 1, 4), 0.5, dtype=np.float32),
                           color_space=color_space, ocio_config=config_path)
    with native.Scene() as scratch:
        try:
            scratch.add_texture(probe)
        except native.StratumError as exc:
            if exc.status == native.ERROR_INVALID_ARGUMENT:
                return False
            raise
    return True


class SceneLinearConversion:
    """One colour space of Blender's config to its scene_linear role, with PyOpenColorIO."""

    def __init__(self, processor: Any, is_data: bool) -> None:
        self._processor = processor  # a CPU processor, or None for data (no conversion)
        self.is_data = is_data

    def apply(self, rgba: np.ndarray) -> np.ndarray:
        """Straight-alpha (..., 4) float32 RGBA, converted in place; alpha is left as it is."""
        if self._processor is not None:
            self._processor.applyRGBA(rgba.reshape(-1))
        return rgba


@cache
def _python_conversion(config_path: str, color_space: str) -> SceneLinearConversion | None:
    ocio = blender_pyopencolorio()
    if ocio is None:
        return None
    try:
        config = ocio.Config.CreateFromFile(config_path)
    except ocio.Exception:
        return None
    source = config.getColorSpace(color_space)
    if source is None:
        return None
    linear = config.getColorSpace(ocio.ROLE_SCENE_LINEAR)
    if source.isData() or (linear is not None and linear.getName() == source.getName()):
        return SceneLinearConversion(None, source.isData())
    processor = config.getProcessor(source.getName(), ocio.ROLE_SCENE_LINEAR)
    return SceneLinearConversion(processor.getDefaultCPUProcessor(), False)


def conversion_for(config_path: str | None, color_space: str) -> SceneLinearConversion | None:
    """The Python conversion to use for an image in `color_space`: None when the native side
    converts it itself (always so in Blender 3.4), or when neither side can (the caller warns
    and falls back)."""
    if config_path is None or blender_pyopencolorio() is None:
        return None
    if native_converts(config_path, color_space):
        return None
    return _python_conversion(config_path, color_space)
