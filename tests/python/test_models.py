"""The light types and closure models the library lists by name (stratum_model_entry) are the
enumerators of the C header, value for value: a registry line (lights/light_registry.cpp,
bsdf/bsdf.cpp) that disagrees with include/stratum/*.h, or a value only one of them has,
fails here. The add-on looks every value up by name, so this is the only place that reads both.

Shader node types have no enumerators: each node's file files its value and name
(shading/node_registry.h), and docs/shader_nodes.md holds a row per node, naming its native
type (with its value where the table gives one). A node the library lists without a row, or a
row whose value disagrees with the listing, fails here; so does a name or value listed twice."""

from __future__ import annotations

import ctypes
import re
from pathlib import Path
from typing import Any

import pytest

# The C ABI: stratum/stratum.h includes the parts the enumerations live in (scene.h today).
REPO = Path(__file__).resolve().parents[2]
HEADERS = sorted((REPO / "native" / "include" / "stratum").glob("*.h"))
SHADER_NODES_DOC = REPO / "docs" / "shader_nodes.md"


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


def _listed_nodes(native: Any) -> list[tuple[str, int]]:
    """The raw listing, duplicates kept (node_types() is a dict)."""
    lib = native.load_library()
    nodes = []
    for index in range(lib.stratum_model_count(native.abi.MODEL_SHADER_NODE)):
        name, value = ctypes.c_char_p(), ctypes.c_int32()
        assert lib.stratum_model_entry(native.abi.MODEL_SHADER_NODE, index, ctypes.byref(name),
                                       ctypes.byref(value)) == native.OK
        nodes.append(((name.value or b"").decode(), value.value))
    return nodes


def test_node_types_are_listed_once_each(native: Any) -> None:
    nodes = _listed_nodes(native)
    assert len(nodes) >= 36
    names = [name for name, _ in nodes]
    values = [value for _, value in nodes]
    assert len(set(names)) == len(names), f"a node name is listed twice: {sorted(names)}"
    assert values == sorted(set(values)), f"values not listed once each, in order: {values}"
    assert native.node_types() == dict(nodes)


def test_every_node_type_has_its_row_in_the_docs(native: Any) -> None:
    """Each listed node is named as a native type (`name`) in a table row of
    docs/shader_nodes.md; a value given beside it, `name` (N), is the listed one."""
    rows = [line for line in SHADER_NODES_DOC.read_text().splitlines() if line.startswith("|")]
    documented: dict[str, set[int | None]] = {}
    for row in rows:
        for name, value in re.findall(r"\| `(\w+)`(?: \((\d+)\))? (?=\|)", row):
            documented.setdefault(name, set()).add(int(value) if value else None)
    for name, value in native.node_types().items():
        assert name in documented, f"docs/shader_nodes.md has no row naming node type `{name}`"
        assert documented[name] <= {value, None}, (
            f"docs/shader_nodes.md gives `{name}` the value(s) {documented[name]}; the library "
            f"lists {value}")


def test_unknown_names_are_refused_with_the_known_ones(native: Any) -> None:
    with pytest.raises(ValueError, match="'no_such_lamp'.*area_ellipse"):
        native.light_type("no_such_lamp")
    with pytest.raises(ValueError, match="'no_such_closure'.*principled_v2"):
        native.closure_model("no_such_closure")
    with pytest.raises(ValueError, match="'no_such_node'.*vector_math"):
        native.node_type("no_such_node")


def test_descriptions_default_to_diffuse_and_point(native: Any) -> None:
    assert native.Material().model == native.closure_model("diffuse")
    assert native.Light().type == native.light_type("point")


def test_shader_inputs_are_the_header_enumerators(native: Any) -> None:
    """abi.SHADER_INPUTS mirrors StratumShaderInput (the renderer's input registers, a fixed
    layout hosts compile programs against): the same names and first registers, widths that fit
    before the next input, and the same register count."""
    header = {name.replace("_", ""): value
              for name, value in header_enum("StratumShaderInput", "STRATUM_INPUT_").items()}
    mirror = {name.replace("_", ""): first for name, (first, _) in native.SHADER_INPUTS.items()}
    assert mirror == header
    text = "\n".join(h.read_text() for h in HEADERS)
    count = re.search(r"STRATUM_SHADER_INPUT_REGISTERS = (\d+)", text)
    assert count and int(count.group(1)) == native.SHADER_INPUT_REGISTERS
    spans = sorted(native.SHADER_INPUTS.values())
    for (first, width), (following, _) in zip(spans, [*spans[1:], (native.SHADER_INPUT_REGISTERS, 0)]):
        assert first + width <= following, f"input at {first} ({width} wide) overlaps {following}"
