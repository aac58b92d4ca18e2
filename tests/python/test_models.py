"""The light types and closure models the library lists by name (stratum_model_entry) are the
enumerators of the C header, value for value: a registry line (lights/light_registry.cpp,
bsdf/bsdf.cpp) that disagrees with include/stratum/*.h, or a value only one of them has,
fails here. The add-on looks every value up by name, so this is the only place that reads both."""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import pytest

# The C ABI: stratum/stratum.h includes the parts the enumerations live in (scene.h today).
HEADERS = sorted((Path(__file__).resolve().parents[2] / "native" / "include" / "stratum").glob("*.h"))


def header_enum(type_name: str, prefix: str) -> dict[str, int]:
    """The enumerators of `typedef enum type_name {...}` as {name without prefix, lower case:
    value}."""
    text = "\n".join(h.read_text() for h in HEADERS)
    body = re.search(r"typedef enum " + type_name + r" \{(.*?)\} " + type_name + ";", text, re.DOTALL)
    assert body, f"{type_name} not found in native/include/stratum/*.h"
    body_text = re.sub(r"/\*.*?\*/", "", body.group(1), flags=re.DOTALL)
    return {name.lower(): int(value)
            for name, value in re.findall(prefix + r"(\w+)\s*=\s*(\d+)", body_text)}


def test_light_types_are_the_header_enumerators(native: Any) -> None:
    expected = header_enum("StratumLightType", "STRATUM_LIGHT_")
    assert len(expected) >= 6
    assert native.light_types() == expected


def test_closure_models_are_the_header_enumerators(native: Any) -> None:
    expected = header_enum("StratumMaterialModel", "STRATUM_MATERIAL_")
    assert len(expected) >= 8
    assert native.closure_models() == expected


def test_unknown_names_are_refused_with_the_known_ones(native: Any) -> None:
    with pytest.raises(ValueError, match="'no_such_lamp'.*area_ellipse"):
        native.light_type("no_such_lamp")
    with pytest.raises(ValueError, match="'no_such_closure'.*principled_v2"):
        native.closure_model("no_such_closure")


def test_descriptions_default_to_diffuse_and_point(native: Any) -> None:
    assert native.Material().model == native.closure_model("diffuse")
    assert native.Light().type == native.light_type("point")
