"""Translators of Blender shader nodes into program nodes, by bl_idname.

A translator takes the compiler and a node and returns the registers of the node's outputs, by
socket identifier:

    @translator("ShaderNodeMath")
    def math(c: NodeCompiler, node) -> dict[str, int]: ...

Each family of nodes has its own module in this package; importing the package imports them
all, which fills TRANSLATORS."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

Translator = Callable[[Any, Any], dict[str, int]]
TRANSLATORS: dict[str, Translator] = {}


def translator(*bl_idnames: str) -> Callable[[Translator], Translator]:
    def register(fn: Translator) -> Translator:
        for name in bl_idnames:
            if name in TRANSLATORS:
                raise ValueError(f"two translators for {name}")
            TRANSLATORS[name] = fn
        return fn

    return register
