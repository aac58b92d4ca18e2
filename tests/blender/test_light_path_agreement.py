"""Stratum against Cycles under Cycles' Light Paths settings (issue 34, acceptance 1): each bounce
kind capped at 0, 1 and 2, and clamping at 1 and at 10, in the running Blender.

Runs in Blender 3.4 (run_in_blender.py) and under the bpy wheels, with the machinery and the
tolerances of agreement.py (test_cycles_agreement.py's docstring derives them): image means
within 2% and 16 x 16 block means within 5% per channel, after the noise gate (4 sigma of each
difference below half its tolerance).

Scene: the Cornell box (Principled walls: a diffuse and a glossy lobe each) with its sphere
made rough glass (Glass BSDF, roughness GLASS_ROUGHNESS, IOR 1.45): diffuse, glossy and
transmission scatterings mix on most paths, so each limit removes light somewhere. At RES x RES
= 32 x 32 with 16 x 16 blocks (four blocks: a block's noise depends on its pixels and samples,
not on the image size, so the small image buys the same gate for a quarter of the time).

Cases (LIMITS: a Latin square, each kind at 0, 1 and 2 once, max_bounces MAX_BOUNCES; CLAMPS):
Cycles renders with the values set in scene.cycles; Stratum renders the same file with
scene.stratum.light_paths = 'CYCLES', so the values reach it the way a file tuned for Cycles
does (engine/light_paths.py). Clamping scales contributions, so Stratum must scale the same
ones (direct: light samples at the first vertex and emission after at most one scattering;
the sum of the channels to 3 x the clamp) to agree; the glass sphere's caustics are the
fireflies clamping is for.
"""

from __future__ import annotations

import functools
from pathlib import Path

import bpy
import pytest

from agreement import (
    MAX_BOUNCES,
    OUT,
    Renders,
    assert_agreement,
    configure_cycles,
    configure_stratum,
    open_scene,
    render_two_seeds,
    stratum_available,
)

RES = 32
BLOCK = 16
SPP_PER_SEED = 1024
GLASS_ROUGHNESS = 0.3
PATHS_OUT = OUT / "light_paths"
# name -> the scene.cycles Light Paths values the case sets.
LIMITS = {
    "diffuse0_glossy1_transmission2": {"diffuse_bounces": 0, "glossy_bounces": 1,
                                       "transmission_bounces": 2},
    "diffuse1_glossy2_transmission0": {"diffuse_bounces": 1, "glossy_bounces": 2,
                                       "transmission_bounces": 0},
    "diffuse2_glossy0_transmission1": {"diffuse_bounces": 2, "glossy_bounces": 0,
                                       "transmission_bounces": 1},
}
CLAMPS = {
    "clamp1": {"sample_clamp_direct": 1.0, "sample_clamp_indirect": 1.0},
    "clamp10": {"sample_clamp_indirect": 10.0},
}
CASES = LIMITS | CLAMPS


def _glass_box() -> bpy.types.Scene:
    scene = open_scene()
    r = scene.render
    r.resolution_x = r.resolution_y = RES
    glass = bpy.data.materials.new("RoughGlass")
    glass.use_nodes = True
    nodes = glass.node_tree.nodes
    nodes.clear()
    bsdf = nodes.new("ShaderNodeBsdfGlass")
    bsdf.distribution = "GGX"
    bsdf.inputs["Roughness"].default_value = GLASS_ROUGHNESS
    bsdf.inputs["IOR"].default_value = 1.45
    out = nodes.new("ShaderNodeOutputMaterial")
    glass.node_tree.links.new(bsdf.outputs["BSDF"], out.inputs["Surface"])
    sphere = bpy.data.objects["Sphere"]
    sphere.data.materials.clear()
    sphere.data.materials.append(glass)
    return scene


def _set_light_paths(scene: bpy.types.Scene, case: str) -> None:
    for name, value in CASES[case].items():
        setattr(scene.cycles, name, value)


def _configure_cycles(case: str, scene: bpy.types.Scene, seed: int) -> None:
    configure_cycles(scene, seed, samples=SPP_PER_SEED)
    _set_light_paths(scene, case)


def _configure_stratum(case: str, scene: bpy.types.Scene, seed: int) -> None:
    # Cycles' values in scene.cycles (all bounces MAX_BOUNCES, no clamping, then the case's),
    # read by Stratum as from a file tuned for Cycles.
    configure_cycles(scene, seed, samples=SPP_PER_SEED)
    _set_light_paths(scene, case)
    configure_stratum(scene, seed, samples=SPP_PER_SEED)
    scene.stratum.light_paths = "CYCLES"


def _render(case: str, renderer: str, configure) -> Renders:
    out: Path = PATHS_OUT / case
    return render_two_seeds(renderer, functools.partial(configure, case), out, _glass_box,
                            res=RES, block=BLOCK)


@pytest.mark.parametrize("case", list(CASES))
def test_light_paths_agree_with_cycles(library, case: str) -> None:
    reason = stratum_available()
    if reason:
        pytest.skip(reason)
    cycles = _render(case, "cycles", _configure_cycles)
    stratum = _render(case, "stratum", _configure_stratum)
    compared = cycles.block_mean() > 0.01
    assert compared.any()
    assert_agreement(cycles, stratum, compared,
                     f"light paths {case} (max_bounces {MAX_BOUNCES})", PATHS_OUT / case)
