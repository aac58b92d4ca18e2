"""The light types, closure models and shader node types the library registers, by name:
`light_type("spot")` is the StratumLightType value STRATUM_LIGHT_SPOT, `closure_model("glass")`
the StratumMaterialModel value STRATUM_MATERIAL_GLASS, `node_type("vector_math")` the
StratumShaderNode type of Vector Math. The add-on mirrors none of these numbers, so a model or
node added to the library (its registry entry carries its name) needs no change here.

The lists are static in the library: read once (on first use) and kept.
"""

from __future__ import annotations

import ctypes
import functools

from .abi import MODEL_CLOSURE, MODEL_LIGHT, MODEL_SHADER_NODE
from .library import _check, load_library


@functools.cache
def _models(kind: int) -> dict[str, int]:
    lib = load_library()
    models: dict[str, int] = {}
    for index in range(lib.stratum_model_count(kind)):
        name, value = ctypes.c_char_p(), ctypes.c_int32()
        _check(lib, lib.stratum_model_entry(kind, index, ctypes.byref(name), ctypes.byref(value)),
               "stratum_model_entry")
        models[(name.value or b"").decode()] = value.value
    return models


def light_types() -> dict[str, int]:
    """Every light type: name ("area_ellipse") → StratumLightType value, in value order."""
    return dict(_models(MODEL_LIGHT))


def closure_models() -> dict[str, int]:
    """Every closure model: name ("principled_v2") → StratumMaterialModel value."""
    return dict(_models(MODEL_CLOSURE))


def _value(kind: int, what: str, name: str) -> int:
    models = _models(kind)
    if name not in models:
        raise ValueError(f"unknown {what} {name!r}; the library has {', '.join(models)}")
    return models[name]


def light_type(name: str) -> int:
    """The StratumLightType value of light type `name` (ValueError naming the known ones)."""
    return _value(MODEL_LIGHT, "light type", name)


def closure_model(name: str) -> int:
    """The StratumMaterialModel value of closure model `name` (ValueError naming the known
    ones)."""
    return _value(MODEL_CLOSURE, "closure model", name)


def node_types() -> dict[str, int]:
    """Every shader node type: name ("vector_math", as docs/shader_nodes.md names it) → its
    StratumShaderNode type, in value order."""
    return dict(_models(MODEL_SHADER_NODE))


def node_type(name: str) -> int:
    """The StratumShaderNode type of node `name` (ValueError naming the known ones)."""
    return _value(MODEL_SHADER_NODE, "shader node type", name)
