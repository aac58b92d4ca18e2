"""Stratum against Cycles on a spot light: a plane under a spot, in the running Blender; and
lamps whose node tree holds a Light Falloff.

Runs in Blender 3.4 (`blender -b --factory-startup --python tests/blender/run_in_blender.py --
tests/blender/test_light_agreement.py`) and under the bpy wheel (`.venv/bin/python -m pytest
tests/blender/test_light_agreement.py`). The rendering, EXR reading and noise estimates are those
of agreement.py (imported; test_cycles_agreement.py's docstring has the statistics).

Scene: a 6 m diffuse plane (Diffuse BSDF, 0.8), a spot light of 1000 W 2 m above it pointing
down, spot_size 60 degrees, blend 0.5, radius 0 (a radius is a disk facing the shading point,
covered by test_feature_agreement.py's lights scene), black world, max_bounces 0 (direct light
only), a camera 5 m up looking down whose view (3.2 m) holds the whole cone (edge radius 2 tan 30 = 1.15 m) and a
dark rim. RES x RES = 32 x 32, Blackman-Harris 1.5 px in both renderers, two seeds each.

Asserted per RGB channel (agreement.assert_agreement): image means within 2%, and 8 x 8 block
means within 5% (agreement.py's IMAGE_TOL, BLOCK_TOL) for every block whose Cycles mean is at
least LIT_FRACTION of the brightest block (the lit ones; the corner blocks hold only the cone's
rim and are left out).

Statistical reasoning. With one delta light and NEE, a pixel's samples differ only by where the
pixel filter puts them on the plane: the noise is the spread of the irradiance over a ~3-pixel
footprint, largest in the blend band. Measured with 2 x 64 spp: 4 sigma of a block difference
up to 3.7% of the block, too close to 5%; hence 2 x SPP_PER_SEED = 2048 spp, which measured
(both Blenders) 4 sigma <= 1.0% for every lit block and ~0.01% for the image means, so a
deviation beyond the 2% / 5% tolerances is a difference of models, not noise. The test asserts
that with the measured sigmas first (4 sigma below half of each tolerance). Measured agreement:
image means within 0.004%, blocks within 0.26% in 3.4.1 and in 5.0.1. What it catches: the
Cycles 3.x cos factor (the 3.4 image mean is 5% below 5.0's; up to 13% at the cone edge), blend,
cone angle and unit errors. Cost: four renders of 32 x 32 x 1024 one-bounce paths, ~3 s.

Light Falloff in a lamp (FALLOFF_LAMPS): the same floor and camera under a point lamp (Linear
output), a spot (Constant, smoothed) and a 1 m area lamp (Linear, smoothed), each 2 m up, whose
Emission Strength is the Light Falloff's output: Cycles evaluates the lamp's tree with the
ray length the distance from the lit point to the point on the lamp, which makes a point lamp's
irradiance fall as 1/d (Linear) or not at all (Constant) instead of 1/d². Stratum runs the tree
as the lamp's program (Scene.set_light_program). Same statistics and tolerances as the spot;
the point lamp's and the spot's centre pixel is first checked against the closed form with the
falloff, so that the tree is seen to change Cycles' image as documented.
"""

from __future__ import annotations

import functools
import math

import bpy
import pytest

from agreement import (
    OUT,
    Renders,
    add_camera,
    add_diffuse_floor,
    assert_agreement,
    configure_cycles,
    configure_stratum,
    new_scene,
    render_two_seeds,
    stratum_available,
)

RES = 32
BLOCK = 8
SPP_PER_SEED = 1024
LIT_FRACTION = 0.05
POWER = 1000.0
HEIGHT = 2.0
SPOT_SIZE = math.radians(60.0)
SPOT_BLEND = 0.5
SPOT_OUT = OUT.parent / (OUT.name + "-spot")
SPOT_NODES_OUT = OUT.parent / (OUT.name + "-spot-nodes")
FALLOFF_OUT = OUT.parent / (OUT.name + "-falloff")
# Per case: the lamp's type, the Light Falloff output on its Emission Strength, the node's
# Strength and Smooth (Strength chosen so that the lamp lights the floor about as the plain spot).
FALLOFF_LAMPS = {
    "point-linear": ("POINT", "Linear", 0.5, 0.0),
    "spot-constant-smooth": ("SPOT", "Constant", 0.15, 2.0),
    "area-linear-smooth": ("AREA", "Linear", 0.5, 1.0),
}
POWERS = {"Quadratic": 0, "Linear": 1, "Constant": 2}


def _spot_scene(with_nodes: bool = False) -> bpy.types.Scene:
    scene = _empty_scene()
    spot = bpy.data.lights.new("spot", "SPOT")
    spot.energy = POWER
    spot.spot_size = SPOT_SIZE
    spot.spot_blend = SPOT_BLEND
    spot.shadow_soft_size = 0.0
    if with_nodes:
        _light_nodes(spot)
    _place_lamp(scene, spot)
    return scene


def _empty_scene() -> bpy.types.Scene:
    """The diffuse floor seen by the camera; world black; no lamp yet."""
    scene = new_scene(RES)
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0, 0, 0, 1)
    world.color = (0.0, 0.0, 0.0)
    scene.world = world
    add_diffuse_floor(scene, 3.0)
    add_camera(scene, 36.0 * 5.0 / 3.2, (0.0, 0.0, 5.0))  # 3.2 m wide at the plane, 5 m below
    return scene


def _place_lamp(scene: bpy.types.Scene, lamp: bpy.types.Light) -> None:
    light = bpy.data.objects.new(lamp.name, lamp)
    light.location = (0.0, 0.0, HEIGHT)  # no rotation: points down local -Z
    scene.collection.objects.link(light)


def _light_nodes(spot: bpy.types.Light) -> None:
    """The light's node tree: Emission Color from a Blackbody at 3000 K, Strength 1.25 x 2 from a
    Math node (issue 18: Cycles multiplies the lamp by them)."""
    spot.use_nodes = True
    nt = spot.node_tree
    emission = next(n for n in nt.nodes if n.bl_idname == "ShaderNodeEmission")
    blackbody = nt.nodes.new("ShaderNodeBlackbody")
    blackbody.inputs["Temperature"].default_value = 3000.0
    times = nt.nodes.new("ShaderNodeMath")
    times.operation = "MULTIPLY"
    times.inputs[0].default_value = 1.25
    times.inputs[1].default_value = 2.0
    nt.links.new(blackbody.outputs[0], emission.inputs["Color"])
    nt.links.new(times.outputs[0], emission.inputs["Strength"])


# Direct light only (max_bounces 0), with the shared peer settings of the Cornell-box test.
_configure_cycles = functools.partial(configure_cycles, samples=SPP_PER_SEED, max_bounces=0)
_configure_stratum = functools.partial(configure_stratum, samples=SPP_PER_SEED, max_bounces=0)


def _render_two_seeds(name: str, configure) -> Renders:
    return render_two_seeds(name, configure, SPOT_OUT, _spot_scene, res=RES, block=BLOCK)


@pytest.fixture(scope="module")
def cycles_spot() -> Renders:
    return _render_two_seeds("cycles", _configure_cycles)


@pytest.fixture(scope="module")
def stratum_spot(library) -> Renders:
    reason = stratum_available()
    if reason:
        pytest.skip(reason)
    return _render_two_seeds("stratum", _configure_stratum)


def test_spot_light_agrees_with_cycles(cycles_spot: Renders, stratum_spot: Renders) -> None:
    c, s = cycles_spot, stratum_spot
    # The centre pixel is the point light's radiance 0.8/π · P/(4π h²) in both Blenders.
    centre = 0.8 / math.pi * POWER / (4.0 * math.pi * HEIGHT**2)
    mid = c.mean[RES // 2 - 1:RES // 2 + 1, RES // 2 - 1:RES // 2 + 1].mean(axis=(0, 1))
    assert mid == pytest.approx([centre] * 3, rel=0.01), f"Cycles centre {mid}, expected {centre}"

    cb = c.block_mean()
    lit = cb >= LIT_FRACTION * cb.max()
    assert lit.sum() >= 3 * 12, f"too few lit blocks: {lit.sum() // 3}"
    assert_agreement(c, s, lit, "spot light", SPOT_OUT)


@pytest.fixture(scope="module")
def cycles_spot_nodes() -> Renders:
    return render_two_seeds("cycles", _configure_cycles, SPOT_NODES_OUT,
                            functools.partial(_spot_scene, True), res=RES, block=BLOCK)


@pytest.fixture(scope="module")
def stratum_spot_nodes(library) -> Renders:
    reason = stratum_available()
    if reason:
        pytest.skip(reason)
    return render_two_seeds("stratum", _configure_stratum, SPOT_NODES_OUT,
                            functools.partial(_spot_scene, True), res=RES, block=BLOCK)


def test_light_node_tree_scales_the_light_as_in_cycles(cycles_spot: Renders, cycles_spot_nodes: Renders,
                                                       stratum_spot_nodes: Renders) -> None:
    """A lamp's node tree (Blackbody colour, Strength from a Math node) multiplies what it emits in
    Cycles; Stratum folds it into the lamp's colour. The node tree must change Cycles' image (so
    the comparison is not of two unlit-by-nodes renders) and Stratum must agree with it."""
    plain = cycles_spot.mean.mean(axis=(0, 1))
    lit = cycles_spot_nodes.mean.mean(axis=(0, 1))
    assert lit[0] > 1.5 * plain[0] and lit[2] < lit[0], f"nodes did not change Cycles: {plain} {lit}"
    cb = cycles_spot_nodes.block_mean()
    lit_blocks = cb >= LIT_FRACTION * cb.max()
    assert_agreement(cycles_spot_nodes, stratum_spot_nodes, lit_blocks, "spot light with nodes",
                     SPOT_NODES_OUT)


def _falloff_scene(name: str) -> bpy.types.Scene:
    """The floor under FALLOFF_LAMPS[name]: its Emission Strength from a Light Falloff."""
    kind, output, strength, smooth = FALLOFF_LAMPS[name]
    scene = _empty_scene()
    lamp = bpy.data.lights.new(name, kind)
    lamp.energy = POWER
    lamp.shadow_soft_size = 0.0
    if kind == "SPOT":
        lamp.spot_size, lamp.spot_blend = SPOT_SIZE, SPOT_BLEND
    if kind == "AREA":
        lamp.size = 1.0
    lamp.use_nodes = True
    nt = lamp.node_tree
    emission = next(n for n in nt.nodes if n.bl_idname == "ShaderNodeEmission")
    falloff = nt.nodes.new("ShaderNodeLightFalloff")
    falloff.inputs["Strength"].default_value = strength
    falloff.inputs["Smooth"].default_value = smooth
    nt.links.new(falloff.outputs[output], emission.inputs["Strength"])
    _place_lamp(scene, lamp)
    return scene


@pytest.fixture(scope="module", params=list(FALLOFF_LAMPS))
def falloff_renders(request: pytest.FixtureRequest, library) -> tuple[str, Renders, Renders]:
    reason = stratum_available()
    if reason:
        pytest.skip(reason)
    name = request.param
    scene = functools.partial(_falloff_scene, name)
    cycles = render_two_seeds("cycles", _configure_cycles, FALLOFF_OUT / name, scene, res=RES,
                              block=BLOCK)
    stratum = render_two_seeds("stratum", _configure_stratum, FALLOFF_OUT / name, scene, res=RES,
                               block=BLOCK)
    return name, cycles, stratum


def test_a_light_falloff_in_a_lamp_renders_as_in_cycles(
        falloff_renders: tuple[str, Renders, Renders]) -> None:
    name, c, s = falloff_renders
    kind, output, strength, smooth = FALLOFF_LAMPS[name]
    if kind != "AREA":
        # The centre pixel: the delta lamp's radiance on the axis, 0.8/pi P/(4 pi h^2), times
        # the Light Falloff at the distance h.
        h = HEIGHT
        factor = strength * h ** POWERS[output] * (h * h / (smooth + h * h) if smooth > 0 else 1)
        centre = 0.8 / math.pi * POWER / (4.0 * math.pi * h**2) * factor
        mid = c.mean[RES // 2 - 1:RES // 2 + 1, RES // 2 - 1:RES // 2 + 1].mean(axis=(0, 1))
        assert mid == pytest.approx([centre] * 3, rel=0.01), f"Cycles centre {mid}, expected {centre}"
    cb = c.block_mean()
    lit = cb >= LIT_FRACTION * cb.max()
    assert_agreement(c, s, lit, f"{name} lamp with a Light Falloff", FALLOFF_OUT / name)
