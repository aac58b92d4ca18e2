"""Image Texture (ShaderNodeTexImage) inside a program: when its output feeds other nodes.

The node is appended to `NodeCompiler.images` (once per node; the exporter maps the list to
native texture ids) and becomes a native `image` node with mode 0 = its index there and mode 1
= how Cycles treats its alpha (svm/image.h, scene/shader_nodes.cpp ImageTextureNode):

| mode 1 | when                                                      | Color                  |
|--------|-----------------------------------------------------------|------------------------|
| 0      | Non-Color data, or alpha mode Channel Packed or None      | as stored              |
| 1      | otherwise, the Alpha output not linked                    | multiplied by alpha    |
| 2      | otherwise, the Alpha output linked                        | divided back by alpha  |

An unlinked Vector is the "uv" renderer input. Flat projection only: Box, Sphere and Tube are
not supported (a warning; the socket's own value is used). The texture carries its
interpolation and extension (export/images.py warns about Cubic and Smart)."""

from __future__ import annotations

from typing import Any

from .compiler import NodeCompiler, Unsupported
from .pattern_textures import warn_texture_mapping
from .registry import translator

DATA_SPACES = frozenset({"Non-Color", "Raw", "Generic Data"})


def alpha_mode(node: Any) -> int:
    image = getattr(node, "image", None)
    settings = getattr(image, "colorspace_settings", None)
    is_data = bool(getattr(settings, "is_data", False)) or \
        str(getattr(settings, "name", "")) in DATA_SPACES
    if image is None or is_data or str(getattr(image, "alpha_mode", "STRAIGHT")) in (
            "CHANNEL_PACKED", "NONE"):
        return 0
    alpha = next((s for s in node.outputs if getattr(s, "identifier", s.name) == "Alpha"), None)
    return 2 if alpha is not None and getattr(alpha, "is_linked", False) else 1


@translator("ShaderNodeTexImage")
def image(c: NodeCompiler, node: Any) -> dict[str, int]:
    projection = str(getattr(node, "projection", "FLAT"))
    if projection != "FLAT":
        raise Unsupported(f"Image Texture '{node.name}': projection {projection} is not supported "
                          "in a node program")
    warn_texture_mapping(c, node)
    co = c.vector_or(node, "Vector", "uv")
    index = next((i for i, n in enumerate(c.images) if n is node), None)
    if index is None:
        index = len(c.images)
        c.images.append(node)
    color, alpha = c.builder.node("image", (index, alpha_mode(node)), (co,), (3, 1))
    return {"Color": color, "Alpha": alpha}
