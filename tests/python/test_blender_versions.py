"""stratum.blender_versions is the one place that knows what differs between Blender versions:
no other module of the add-on orders versions (read from the source with ast, so the
Blender-only modules are covered too), bpy.app.version is only handed to it, and each answer
changes at the release the module's docstrings name."""

from __future__ import annotations

import ast
from pathlib import Path
from types import SimpleNamespace

import pytest
from stratum import blender_versions as bv

PACKAGE = Path(__file__).resolve().parents[2] / "addon" / "stratum"
ORDERING = (ast.Lt, ast.LtE, ast.Gt, ast.GtE)


def _is_release(node: ast.expr) -> bool:
    """A tuple literal of 2 or 3 ints, as (4, 1) or (4, 1, 0)."""
    return isinstance(node, ast.Tuple) and 2 <= len(node.elts) <= 3 and all(
        isinstance(e, ast.Constant) and type(e.value) is int for e in node.elts)


def _mentions_version(node: ast.expr) -> bool:
    return any((isinstance(n, ast.Name) and "version" in n.id)
               or (isinstance(n, ast.Attribute) and "version" in n.attr) for n in ast.walk(node))


def _is_app_version(node: ast.AST) -> bool:
    return isinstance(node, ast.Attribute) and node.attr == "version" \
        and isinstance(node.value, ast.Attribute) and node.value.attr == "app"


def version_checks(tree: ast.AST) -> list[int]:
    """Lines that order versions: a comparison (<, <=, >, >=) with a release tuple or with
    something named *version*."""
    return [node.lineno for node in ast.walk(tree) if isinstance(node, ast.Compare)
            and any(isinstance(op, ORDERING) for op in node.ops)
            and any(_is_release(x) or _mentions_version(x) for x in [node.left, *node.comparators])]


def app_version_reads(tree: ast.AST) -> list[int]:
    """Lines that read bpy.app.version other than as a call's argument (e.g. tuple(...), or a
    blender_versions question), where it would be looked at rather than handed on."""
    handed_on = {id(arg) for call in ast.walk(tree) if isinstance(call, ast.Call)
                 for arg in call.args}
    return [node.lineno for node in ast.walk(tree)
            if _is_app_version(node) and id(node) not in handed_on]


def _modules() -> list[Path]:
    return [p for p in sorted(PACKAGE.rglob("*.py")) if p.name != "blender_versions.py"]


def test_the_checks_find_what_they_look_for() -> None:
    tree = ast.parse("a = bpy.app.version >= (4, 1, 0)\nb = v < (3, 5)\nc = version[0] > 3\n"
                     "d = f(bpy.app.version)\ne = shape == (4, 4)\nf = x > 2\n")
    assert version_checks(tree) == [1, 2, 3]
    assert app_version_reads(tree) == [1]


def test_no_module_but_blender_versions_compares_versions() -> None:
    found = [f"{path.relative_to(PACKAGE)}:{line}" for path in _modules()
             for line in version_checks(ast.parse(path.read_text(encoding="utf-8")))]
    assert not found, "version comparisons outside stratum/blender_versions.py: " + \
        ", ".join(found)


def test_bpy_app_version_is_only_handed_on() -> None:
    found = [f"{path.relative_to(PACKAGE)}:{line}" for path in _modules()
             for line in app_version_reads(ast.parse(path.read_text(encoding="utf-8")))]
    assert not found, "bpy.app.version read outside a call: " + ", ".join(found)


@pytest.mark.parametrize(("question", "before", "at"), [
    (bv.panorama_in_cycles_settings, True, False),
    (bv.cast_shadow_in_cycles_settings, True, False),
    (bv.principled_v2, False, True),
    (bv.normal_map_scales_strength, False, True),
    (bv.spot_light_model, "spot_v1", "spot"),
    (bv.vector_transform_revision, 0, 1),
])
def test_what_changed_in_4_0(question, before, at) -> None:
    assert question((3, 6, 9)) == before
    assert question((4, 0, 0)) == at == question((5, 0, 1))


def test_area_light_power_of_3x_is_pi_over_4() -> None:
    assert bv.area_light_power_scale((3, 4, 1)) == pytest.approx(0.7853981633974483)
    assert bv.area_light_power_scale((4, 0, 0)) == 1.0


@pytest.mark.parametrize(("question", "release"), [
    (bv.flat_pass_pixels, (4, 1)), (bv.ramp_table_has_end_entry, (4, 1)),
    (bv.has_bump_map_correction, (4, 2)), (bv.conty_bump_shadowing, (4, 5)),
    (bv.node_trees_always_used, (5, 0)), (bv.wireframe_at_bump_offsets, (4, 4)),
    (bv.light_falloff_revision, (4, 4)),
])
def test_what_changed_later(question, release: tuple[int, int]) -> None:
    major, minor = release
    assert not question((major, minor - 1, 9))
    assert question((major, minor, 0))


def test_colour_configurations_of_3x_4x_and_5_0() -> None:
    assert [bv.color_config(v) for v in ((3, 6, 9), (4, 0, 0), (4, 5, 9), (5, 0, 0))] == \
        [0, 1, 1, 2]


def test_brick_hue_and_voronoi_lacunarity_boundaries() -> None:
    assert [bv.brick_generation(v) for v in ((3, 4, 1), (3, 5, 0))] == [0, 1]
    assert [bv.hue_wraps_with_fmod(v) for v in ((4, 2, 3), (4, 3, 0))] == [True, False]
    assert [bv.voronoi_lacunarity_from_smoothness(v) for v in (
        (3, 6, 0), (4, 0, 0), (4, 2, 9), (4, 3, 0))] == [False, True, True, False]


def test_pass_names_follow_5_0() -> None:
    assert bv.render_pass_name("Emit", (4, 5, 0)) == "Emit"
    assert bv.render_pass_name("Emit", (5, 0, 0)) == "Emission"
    assert bv.render_pass_name("Depth", (5, 0, 0)) == "Depth"


def test_a_principled_node_with_4_0_sockets_is_v2_in_any_version() -> None:
    v2_node = SimpleNamespace(inputs={bv.PRINCIPLED_V2.specular: object()})
    v1_node = SimpleNamespace(inputs={bv.PRINCIPLED_V1.specular: object()})
    assert bv.principled_v2((3, 4, 1), v2_node)
    assert not bv.principled_v2((3, 4, 1), v1_node)
    assert bv.principled_v2((4, 2, 0), v1_node)


def test_data_api_questions_read_the_object() -> None:
    assert bv.has_corner_normals(SimpleNamespace(corner_normals=()))
    assert not bv.has_corner_normals(SimpleNamespace(use_auto_smooth=False))
    assert bv.has_normals_domain(SimpleNamespace(normals_domain="POINT"))
    assert bv.uv_layer_has_uv_vectors(SimpleNamespace(uv=()))
    assert not bv.uv_layer_has_uv_vectors(SimpleNamespace(data=()))
