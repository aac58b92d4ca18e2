"""Compares Stratum's Sky Texture with Cycles' at the pixel directions of a reference written by
scripts/sky_cycles_reference.py: the worst relative difference per case, for the sky (away from
the sun disc) and for the disc.

    PYTHONPATH=addon .venv/bin/python scripts/compare_sky.py ref.json [--dump N]

Relative difference: |a - b| / max(|b|, floor) per channel, floor 1e-3 of the case's brightest
reference channel (near-black pixels, e.g. the ground's fade, compare absolutely)."""

from __future__ import annotations

import argparse
import json
import math
from types import SimpleNamespace
from typing import Any

import numpy as np
from stratum import native
from stratum.shaders.nodes import NodeCompiler, Unsupported
from stratum.shaders.nodes.sky_texture import translate_sky

DEFAULTS: dict[str, Any] = {
    "sun_direction": (0.0, 0.0, 1.0), "turbidity": 2.2, "ground_albedo": 0.3, "sun_disc": True,
    "sun_size": 0.009512044489383698, "sun_intensity": 1.0, "sun_elevation": math.radians(15.0),
    "sun_rotation": 0.0, "altitude": 0.0, "air_density": 1.0, "dust_density": 1.0,
    "ozone_density": 1.0,
}


class _Socket(SimpleNamespace):
    is_linked = False


def sky_node(settings: dict[str, Any], altitude_default: float = 0.0) -> Any:
    values = dict(DEFAULTS, altitude=altitude_default)
    for key, value in settings.items():
        values["dust_density" if key == "dust" else key] = value
    return SimpleNamespace(name="Sky", bl_idname="ShaderNodeTexSky",
                           inputs=[_Socket(name="Vector", identifier="Vector", links=[],
                                           default_value=(0.0, 0.0, 0.0))],
                           outputs=[_Socket(name="Color", identifier="Color", links=[])],
                           mute=False, **values)


def evaluate(settings: dict[str, Any], directions: np.ndarray, version: tuple[int, int, int],
             ) -> np.ndarray | None:
    warnings: list[str] = []
    c = NodeCompiler(version, lambda node, message: warnings.append(message))
    node = sky_node(settings, 100.0 if version[0] >= 4 else 0.0)
    try:
        color = translate_sky(c, node)["Color"]
    except Unsupported as exc:
        print(f"  not supported: {exc}")
        return None
    scene = native.Scene()
    pid = scene.add_shader_program(c.builder.program)
    out = np.zeros_like(directions)
    inputs = np.zeros(native.SHADER_INPUT_REGISTERS, dtype=np.float32)
    pos = native.SHADER_INPUTS["position"][0]
    gen = native.SHADER_INPUTS["generated"][0]
    for i, d in enumerate(directions):
        inputs[pos:pos + 3] = d
        inputs[gen:gen + 3] = d
        out[i] = scene.evaluate_program(pid, inputs, color, 3)
    return out


def in_disc(settings: dict[str, Any], d: np.ndarray, version: tuple[int, int, int]) -> np.ndarray:
    if not settings.get("sun_disc", False):
        return np.zeros(len(d), dtype=bool)
    el = settings.get("sun_elevation", DEFAULTS["sun_elevation"])
    rot = settings.get("sun_rotation", 0.0)
    lon = -rot + math.pi / 2  # the sun's azimuth: Cycles' 2 pi - rotation, plus pi/2
    sun = np.array([math.cos(el) * math.cos(lon), math.cos(el) * math.sin(lon), math.sin(el)])
    half = settings.get("sun_size", DEFAULTS["sun_size"]) / 2
    ang = np.arccos(np.clip(d @ sun, -1, 1))
    # Pixels within 1% of the rim either side are neither (float rounding decides them).
    return ang < half * 0.99


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("reference")
    ap.add_argument("--dump", type=int, default=0, help="print N worst pixels per case")
    args = ap.parse_args()
    with open(args.reference) as f:
        ref = json.load(f)
    version = tuple(ref["blender"])
    dirs = np.array(ref["directions"], dtype=np.float32)
    print(f"Blender {'.'.join(map(str, version))}: {len(dirs)} directions")
    for name, case in ref["cases"].items():
        settings = case["settings"]
        want = np.array(case["rgb"], dtype=np.float64)
        print(f"{name}: {settings['sky_type']}")
        got = evaluate(settings, dirs, version)
        if got is None:
            continue
        floor = 1e-3 * max(want.max(), 1e-30)
        rel = np.abs(got - want) / np.maximum(np.abs(want), floor)
        disc = in_disc(settings, dirs.astype(np.float64), version)
        for label, mask in (("sky", ~disc), ("disc", disc)):
            if not mask.any():
                continue
            worst = rel[mask].max()
            idx = np.flatnonzero(mask)[int(np.argmax(rel[mask].max(axis=1)))]
            print(f"  {label}: {mask.sum()} px, worst rel {worst:.2e} at {dirs[idx].tolist()} "
                  f"(ours {got[idx].tolist()}, Cycles {want[idx].tolist()}), "
                  f"mean rel {rel[mask].mean():.2e}")
        for idx in np.argsort(-rel.max(axis=1))[:args.dump]:
            print("   ", dirs[idx].tolist(), got[idx].tolist(), want[idx].tolist())


if __name__ == "__main__":
    main()
