"""Node-graph flattening (stratum.shaders.surface) on plain stand-ins for Blender nodes: the
weights Cycles gives nested Mix/Add shaders, the Principled socket generations, textures."""

from __future__ import annotations

from typing import Any

import pytest
from stratum import native
from stratum.shaders.surface import flatten_surface

V3 = (3, 4, 1)
V5 = (5, 0, 1)


class Socket:
    def __init__(self, name: str, default_value: Any = None) -> None:
        self.name = name
        self.default_value = default_value
        self.links: list[Any] = []

    @property
    def is_linked(self) -> bool:
        return bool(self.links)


class Link:
    def __init__(self, from_node: Any, from_socket: Socket) -> None:
        self.from_node = from_node
        self.from_socket = from_socket
        self.is_muted = False
        self.is_valid = True


class Sockets(list):
    def get(self, name: str) -> Socket | None:
        return next((s for s in self if s.name == name), None)

    def __getitem__(self, key: Any) -> Any:
        if isinstance(key, str):
            found = self.get(key)
            if found is None:
                raise KeyError(key)
            return found
        return super().__getitem__(key)


class Node:
    def __init__(self, bl_idname: str, name: str, inputs: dict[str, Any] | list[tuple[str, Any]],
                 outputs: tuple[str, ...] = ("BSDF",), **props: Any) -> None:
        self.bl_idname = bl_idname
        self.name = name
        items = inputs.items() if isinstance(inputs, dict) else inputs
        self.inputs = Sockets(Socket(k, v) for k, v in items)
        self.outputs = Sockets(Socket(k) for k in outputs)
        self.mute = False
        for key, value in props.items():
            setattr(self, key, value)


def link(src: Node, output: str, dst: Node, input_: str | int) -> None:
    socket = dst.inputs[input_]
    socket.links = [Link(src, src.outputs[output])]


def output_with(node: Node, socket: str = "BSDF") -> Socket:
    surface = Socket("Surface")
    surface.links = [Link(node, node.outputs[socket])]
    return surface


def diffuse(name: str, color: tuple[float, float, float] = (0.5, 0.5, 0.5)) -> Node:
    return Node("ShaderNodeBsdfDiffuse", name,
                {"Color": (*color, 1.0), "Roughness": 0.0, "Normal": (0, 0, 0)})


def mix(name: str, fac: float) -> Node:
    return Node("ShaderNodeMixShader", name, [("Fac", fac), ("Shader", None), ("Shader", None)],
                ("Shader",))


def add(name: str) -> Node:
    return Node("ShaderNodeAddShader", name, [("Shader", None), ("Shader", None)], ("Shader",))


def image(name: str) -> Node:
    return Node("ShaderNodeTexImage", name, {"Vector": (0, 0, 0)}, ("Color", "Alpha"))


def principled_v1(**values: Any) -> Node:
    inputs = {"Base Color": (0.8, 0.8, 0.8, 1.0), "Subsurface": 0.0, "Metallic": 0.0,
              "Specular": 0.5, "Specular Tint": 0.0, "Roughness": 0.5, "Anisotropic": 0.0,
              "Sheen": 0.0, "Clearcoat": 0.0, "Clearcoat Roughness": 0.03, "IOR": 1.45,
              "Transmission": 0.0, "Transmission Roughness": 0.0, "Emission": (0, 0, 0, 1),
              "Emission Strength": 1.0, "Alpha": 1.0, "Normal": (0, 0, 0)}
    inputs.update(values)
    return Node("ShaderNodeBsdfPrincipled", "Principled BSDF", inputs, distribution="GGX")


def principled_v2(**values: Any) -> Node:
    inputs = {"Base Color": (0.8, 0.8, 0.8, 1.0), "Metallic": 0.0, "Roughness": 0.5,
              "IOR": 1.5, "Alpha": 1.0, "Normal": (0, 0, 0), "Diffuse Roughness": 0.0,
              "Subsurface Weight": 0.0, "Specular IOR Level": 0.5, "Anisotropic": 0.0,
              "Transmission Weight": 0.0, "Coat Weight": 0.0, "Coat Roughness": 0.03,
              "Coat IOR": 1.5, "Coat Tint": (1, 1, 1, 1), "Sheen Weight": 0.0,
              "Emission Color": (1, 1, 1, 1), "Emission Strength": 0.0,
              "Thin Film Thickness": 0.0}
    inputs.update(values)
    return Node("ShaderNodeBsdfPrincipled", "Principled BSDF", inputs, distribution="MULTI_GGX")


def flatten(surface: Socket, version: tuple[int, int, int] = V5) -> tuple[Any, list[str]]:
    warnings: list[str] = []
    closures = flatten_surface(surface, version, lambda node, msg: warnings.append(msg)).closures
    return closures, warnings


def test_nested_mix_and_add_weights() -> None:
    # Add(Mix(A, B, 0.25), Mix(C, Mix(D, E, 0.5), 0.8)):
    # A 0.75, B 0.25, C 0.2, D 0.8*0.5 = 0.4, E 0.4 -- Cycles' closure weights.
    a, b, c, d, e = (diffuse(n) for n in "ABCDE")
    m1, m2, m3, top = mix("M1", 0.25), mix("M2", 0.8), mix("M3", 0.5), add("Add")
    link(a, "BSDF", m1, 1)
    link(b, "BSDF", m1, 2)
    link(d, "BSDF", m3, 1)
    link(e, "BSDF", m3, 2)
    link(c, "BSDF", m2, 1)
    link(m3, "Shader", m2, 2)
    link(m1, "Shader", top, 0)
    link(m2, "Shader", top, 1)
    closures, warnings = flatten(output_with(top, "Shader"))
    assert warnings == []
    weights = [cl.weight[0] for cl in closures]
    assert weights == pytest.approx([0.75, 0.25, 0.2, 0.4, 0.4])
    assert all(cl.material.model == native.closure_model("diffuse") for cl in closures)


def test_add_of_same_input_twice_doubles_and_zero_weights_are_dropped() -> None:
    a, b = diffuse("A"), diffuse("B")
    m, top = mix("Mix", 1.0), add("Add")
    link(a, "BSDF", m, 1)  # weight 0: dropped as Cycles does
    link(b, "BSDF", m, 2)
    link(m, "Shader", top, 0)
    link(m, "Shader", top, 1)
    closures, _ = flatten(output_with(top, "Shader"))
    # Both paths reach B: one closure with the summed weight renders the same as two.
    assert [cl.weight for cl in closures] == [(2.0, 2.0, 2.0)]


def test_deep_mix_chain_flattens_without_recursion() -> None:
    below = diffuse("Bottom")
    output = "BSDF"
    for i in range(5000):
        m = mix(f"Mix{i}", 0.0)
        link(below, output, m, 1)
        below, output = m, "Shader"
    closures, warnings = flatten(output_with(below, "Shader"))
    assert warnings == []
    assert [cl.weight for cl in closures] == [(1.0, 1.0, 1.0)]


def test_shared_inputs_are_walked_once_per_node() -> None:
    # Each Add Shader takes the one below on both inputs: 2^60 paths to the bottom BSDF, whose
    # weight is 2^60 (exact in floating point); a walk per path would never end.
    below = diffuse("Bottom")
    output = "BSDF"
    for i in range(60):
        a = add(f"Add{i}")
        link(below, output, a, 0)
        link(below, output, a, 1)
        below, output = a, "Shader"
    closures, _ = flatten(output_with(below, "Shader"))
    assert [cl.weight for cl in closures] == [(2.0**60, 2.0**60, 2.0**60)]


def test_tree_closures_keep_depth_first_order_and_path_products() -> None:
    a, b, c = diffuse("A"), diffuse("B"), diffuse("C")
    inner, top = mix("Inner", 0.25), mix("Top", 0.5)
    link(a, "BSDF", inner, 1)
    link(b, "BSDF", inner, 2)
    link(inner, "Shader", top, 1)
    link(c, "BSDF", top, 2)
    closures, _ = flatten(output_with(top, "Shader"))
    assert [cl.weight[0] for cl in closures] == [0.5 * 0.75, 0.5 * 0.25, 0.5]


def test_a_cycle_is_cut_with_a_warning() -> None:
    first, second, leaf = mix("First", 0.5), mix("Second", 0.5), diffuse("Leaf")
    link(second, "Shader", first, 1)
    link(first, "Shader", second, 1)
    link(leaf, "BSDF", second, 2)
    closures, warnings = flatten(output_with(first, "Shader"))
    assert [cl.weight for cl in closures] == [(0.25, 0.25, 0.25)]
    assert any("cycle" in w and "'First'" in w for w in warnings)


def test_principled_v1_mapping() -> None:
    node = principled_v1(**{"Base Color": (0.2, 0.4, 0.6, 1.0), "Metallic": 0.3,
                            "Roughness": 0.7, "Specular": 0.6, "IOR": 1.33,
                            "Transmission": 0.9, "Clearcoat": 0.5,
                            "Clearcoat Roughness": 0.1, "Emission": (1.0, 0.5, 0.0, 1.0),
                            "Emission Strength": 2.0})
    closures, warnings = flatten(output_with(node), V3)
    assert warnings == []
    (cl,) = closures
    m = cl.material
    assert m.model == native.closure_model("principled_v1")
    assert m.base_color == pytest.approx((0.2, 0.4, 0.6))
    assert (m.metallic, m.roughness, m.specular, m.ior) == pytest.approx((0.3, 0.7, 0.6, 1.33))
    assert (m.transmission, m.coat, m.coat_roughness) == pytest.approx((0.9, 0.5, 0.1))
    assert m.emission == pytest.approx((2.0, 1.0, 0.0))
    assert m.distribution == native.MICROFACET_GGX


def test_principled_v2_mapping() -> None:
    node = principled_v2(**{"Specular IOR Level": 0.8, "Transmission Weight": 0.4,
                            "Coat Weight": 1.0, "Coat Roughness": 0.2, "Coat IOR": 1.6,
                            "Coat Tint": (0.9, 0.8, 0.7, 1.0),
                            "Emission Color": (0.0, 1.0, 0.0, 1.0), "Emission Strength": 3.0})
    closures, warnings = flatten(output_with(node), V5)
    assert warnings == []
    m = closures[0].material
    assert m.model == native.closure_model("principled_v2")
    assert (m.specular, m.transmission, m.coat, m.coat_roughness, m.coat_ior) == \
        pytest.approx((0.8, 0.4, 1.0, 0.2, 1.6))
    assert m.coat_tint == pytest.approx((0.9, 0.8, 0.7))
    assert m.emission == pytest.approx((0.0, 3.0, 0.0))
    assert m.distribution == native.MICROFACET_MULTISCATTER_GGX


def test_principled_alpha_is_transparent_mix() -> None:
    closures, _ = flatten(output_with(principled_v2(Alpha=0.3)))
    assert [cl.material.model for cl in closures] == [native.closure_model("transparent"),
                                                      native.closure_model("principled_v2")]
    assert closures[0].weight[0] == pytest.approx(0.7)
    assert closures[0].material.base_color == (1.0, 1.0, 1.0)
    assert closures[1].weight[0] == pytest.approx(0.3)


def test_image_alpha_cutout_binds_weights() -> None:
    node, tex = principled_v2(), image("Leaf")
    link(tex, "Alpha", node, "Alpha")
    link(tex, "Color", node, "Base Color")
    closures, warnings = flatten(output_with(node))
    assert warnings == []
    transparent, principled = closures
    (w,) = transparent.bindings
    assert (w.param, w.channel, w.scale, w.offset) == (native.PARAM_WEIGHT, 3, -1.0, 1.0)
    params = {(b.param, b.channel, b.scale, b.offset) for b in principled.bindings}
    assert params == {(native.PARAM_WEIGHT, 3, 1.0, 0.0), (native.PARAM_BASE_COLOR, -1, 1.0, 0.0)}
    assert all(b.image.node is tex for b in principled.bindings)


def test_mix_fac_from_image() -> None:
    a, b, m, tex = diffuse("A"), diffuse("B"), mix("Mix", 0.5), image("Mask")
    link(a, "BSDF", m, 1)
    link(b, "BSDF", m, 2)
    link(tex, "Color", m, 0)
    closures, _ = flatten(output_with(m, "Shader"))
    assert [cl.weight for cl in closures] == [(1.0, 1.0, 1.0)] * 2
    assert [(x.bindings[0].scale, x.bindings[0].offset) for x in closures] == [(-1.0, 1.0),
                                                                              (1.0, 0.0)]


def test_textures_and_normal_map_and_uv_map() -> None:
    node = principled_v1()
    rough, normal_tex, uv = image("Rough"), image("NormalTex"), Node(
        "ShaderNodeUVMap", "UV Map", {}, ("UV",), uv_map="Second")
    nmap = Node("ShaderNodeNormalMap", "Normal Map", {"Strength": 0.5, "Color": (0.5, 0.5, 1, 1)},
                ("Normal",), space="TANGENT")
    link(uv, "UV", rough, "Vector")
    link(uv, "UV", normal_tex, "Vector")
    link(rough, "Color", node, "Roughness")
    link(normal_tex, "Color", nmap, "Color")
    link(nmap, "Normal", node, "Normal")
    warnings: list[str] = []
    flat = flatten_surface(output_with(node), V3, lambda n, m: warnings.append(m))
    closures, uv_map = flat.closures, flat.uv_map
    assert uv_map == "Second" and warnings == []
    by_param = {b.param: b for b in closures[0].bindings}
    assert by_param[native.PARAM_ROUGHNESS].image.node is rough
    assert by_param[native.PARAM_NORMAL].scale == pytest.approx(0.5)


def test_unsupported_node_warns_once_per_node_and_falls_back() -> None:
    node = principled_v2(**{"Base Color": (0.1, 0.2, 0.3, 1.0), "Roughness": 0.25})
    noise = Node("ShaderNodeTexNoise", "Noise", {}, ("Fac", "Color"))
    link(noise, "Color", node, "Base Color")
    link(noise, "Fac", node, "Roughness")
    closures, warnings = flatten(output_with(node))
    assert len(warnings) == 1 and "'Noise'" in warnings[0]
    assert closures[0].material.base_color == pytest.approx((0.1, 0.2, 0.3))
    assert closures[0].material.roughness == pytest.approx(0.25)
    assert closures[0].bindings == []
    toon = Node("ShaderNodeBsdfToon", "Toon", {}, ("BSDF",))
    closures, warnings = flatten(output_with(toon), V3)
    assert len(warnings) == 1 and "'Toon'" in warnings[0]
    assert closures[0].material.model == native.closure_model("principled_v1")


def test_other_bsdfs() -> None:
    glossy = Node("ShaderNodeBsdfAnisotropic", "Glossy", {"Color": (1, 0.5, 0.25, 1),
                  "Roughness": 0.2, "Anisotropy": 0.0}, distribution="MULTI_GGX")
    glass = Node("ShaderNodeBsdfGlass", "Glass", {"Color": (1, 1, 1, 1), "Roughness": 0.0,
                 "IOR": 1.45}, distribution="BECKMANN")
    emit = Node("ShaderNodeEmission", "Emit", {"Color": (1, 0.5, 0, 1), "Strength": 4.0},
                ("Emission",))
    hold = Node("ShaderNodeHoldout", "Hold", {}, ("Holdout",))
    transparent = Node("ShaderNodeBsdfTransparent", "T", {"Color": (0.5, 0.5, 0.5, 1)})
    expected = [(glossy, native.closure_model("glossy")), (glass, native.closure_model("glass")),
                (emit, native.closure_model("emission")), (hold, native.closure_model("holdout")),
                (transparent, native.closure_model("transparent"))]
    for node, model in expected:
        closures, warnings = flatten(output_with(node, node.outputs[0].name))
        assert warnings == [], node.name
        assert closures[0].material.model == model
    closures, _ = flatten(output_with(glossy))
    assert closures[0].material.distribution == native.MICROFACET_MULTISCATTER_GGX
    assert closures[0].material.roughness == pytest.approx(0.2)
    closures, _ = flatten(output_with(emit, "Emission"))
    assert closures[0].material.emission == pytest.approx((4.0, 2.0, 0.0))
    closures, _ = flatten(output_with(glass))
    assert closures[0].material.ior == pytest.approx(1.45)


def test_image_on_emission_or_transmission_goes_through_the_node_program() -> None:
    # The native contract refuses image bindings of emission and transmission (emissive
    # triangles are light-sampled with a constant): the program drives them instead, and the
    # constant emission is 0 so that the triangles are not lights of the wrong radiance.
    node, glow, clear = principled_v2(**{"Emission Strength": 2.0,
                                         "Emission Color": (1.0, 0.5, 0.0, 1.0)}), \
        image("Glow"), image("Clear")
    link(glow, "Color", node, "Emission Color")
    link(clear, "Color", node, "Transmission Weight")
    warnings: list[str] = []
    flat = flatten_surface(output_with(node), V5, lambda n, msg: warnings.append(msg))
    closure = flat.closures[0]
    assert warnings == []
    assert closure.bindings == []
    assert sorted(p.param for p in closure.programs) == ["emission", "transmission"]
    assert closure.material.emission == (0.0, 0.0, 0.0)
    assert [n.name for n in flat.program_images] == ["Clear", "Glow"]
    assert flat.program is not None
    image_nodes = [n for n in flat.program.nodes if n.type == native.node_type("image")]
    assert sorted(n.modes[0] for n in image_nodes) == [0, 1]


def test_normal_map_strength_outside_unit_range_warns_in_4x_only() -> None:
    for version, expected in ((V3, 0), (V5, 1)):
        node, tex = principled_v2(), image("Bumps")
        nmap = Node("ShaderNodeNormalMap", "Normal Map", {"Strength": 2.0,
                    "Color": (0.5, 0.5, 1, 1)}, ("Normal",), space="TANGENT")
        link(tex, "Color", nmap, "Color")
        link(nmap, "Normal", node, "Normal")
        closures, warnings = flatten(output_with(node), version)
        assert len(warnings) == expected
        assert closures[0].bindings[0].scale == pytest.approx(2.0)


NAN = float("nan")


def test_invalid_socket_values_warn_once_per_socket() -> None:
    """Each bad socket of a node is its own warning (the once-per-node rule of unsupported
    links must not swallow the second); the values become Cycles' clamps."""
    node = principled_v2(**{"Roughness": NAN, "Metallic": NAN, "IOR": -1.0,
                            "Base Color": (NAN, 0.5, 2.0, 1.0)})
    noise = Node("ShaderNodeTexNoise", "Noise", {}, ("Fac", "Color"))
    link(noise, "Fac", node, "Coat Weight")
    closures, warnings = flatten(output_with(node))
    assert len(warnings) == 5, warnings  # Roughness, Metallic, IOR, Base Color, the Noise link
    for socket in ("'Roughness'", "'Metallic'", "'IOR'", "'Base Color'", "'Noise'"):
        assert sum(socket in w for w in warnings) == 1, socket
    material = closures[0].material
    assert (material.roughness, material.metallic, material.ior) == (0.0, 0.0, 1e-5)
    assert material.base_color == (0.0, 0.5, 1.0)


def test_a_texture_driven_socket_value_is_not_read_so_not_warned() -> None:
    node = principled_v1(Roughness=NAN)
    link(image("Rough"), "Color", node, "Roughness")
    closures, warnings = flatten(output_with(node), V3)
    assert warnings == []
    assert closures[0].bindings[0].param == native.PARAM_ROUGHNESS
    assert closures[0].material.roughness == 0.0  # a valid placeholder for the ABI


def test_volume_shader_on_a_surface_adds_no_closure() -> None:
    scatter = Node("ShaderNodeVolumeScatter", "Volume Scatter",
                   {"Color": (1, 1, 1, 1), "Density": 1.0}, ("Volume",))
    closures, warnings = flatten(output_with(scatter, "Volume"))
    assert closures == [] and len(warnings) == 1 and "'Volume Scatter'" in warnings[0]


def test_a_script_node_adds_no_closure_as_cycles_without_osl() -> None:
    """Cycles without OSL makes no node of a Script: a Mix Shader's input it feeds is unlinked
    (its share adds nothing), and so is a Material Output's Surface."""
    script = Node("ShaderNodeScript", "Script", {}, ("BSDF",))
    blend = mix("Mix", 0.25)
    link(script, "BSDF", blend, 1)
    link(diffuse("Diffuse", (0.8, 0.8, 0.8)), "BSDF", blend, 2)
    closures, warnings = flatten(output_with(blend, "Shader"))
    assert [c.weight for c in closures] == [(0.25, 0.25, 0.25)]
    assert len(warnings) == 1 and "Script 'Script': OSL scripts are not supported" in warnings[0]
    closures, _ = flatten(output_with(script))
    assert closures == []
