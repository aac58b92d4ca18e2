"""How much of the sun disc's irradiance a baked world keeps (issue 18, the Sky brief).

    PYTHONPATH=addon .venv/bin/python scripts/sky_disc_energy.py [--width 1024] [--size 0.545]

The renderer bakes a world program into an equirectangular map, each texel the mean of 2 x 2
directions (shading/world_baking.cpp, which now integrates texels next to a sharp feature again
with 16 x 16 directions: tests/native/test_sky_nodes.cpp checks that). This measures the plain
2 x 2 bake, the reason for that refinement. For a Nishita sky, it compares the disc's share of the
irradiance on a horizontal plane, sum over texels of (with disc - without disc) cos(theta) dOmega,
with the integral of the disc itself (a 400 x 400 grid over the disc's tangent plane)."""

from __future__ import annotations

import argparse
import math
from types import SimpleNamespace

import numpy as np
from stratum import native
from stratum.shaders.nodes import NodeCompiler
from stratum.shaders.nodes.sky_texture import translate_sky


def program(disc: bool, size: float, elevation: float, rotation: float) -> tuple[object, int]:
    node = SimpleNamespace(
        name="Sky", bl_idname="ShaderNodeTexSky", sky_type="NISHITA", sun_disc=disc,
        sun_size=size, sun_intensity=1.0, sun_elevation=elevation, sun_rotation=rotation,
        altitude=0.0, air_density=1.0, dust_density=1.0, ozone_density=1.0,
        inputs=[SimpleNamespace(name="Vector", identifier="Vector", links=[], is_linked=False)],
        outputs=[])
    c = NodeCompiler((3, 4, 1), lambda n, m: None)
    color = translate_sky(c, node)["Color"]
    return c.builder.program, color


def luminance(rgb: np.ndarray) -> np.ndarray:
    return rgb @ np.array([0.2126729, 0.7151522, 0.0721750])


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--width", type=int, default=1024)
    ap.add_argument("--size", type=float, default=0.545, help="sun size, degrees")
    ap.add_argument("--elevation", type=float, default=30.0, help="degrees")
    args = ap.parse_args()
    size, elevation, rotation = math.radians(args.size), math.radians(args.elevation), 0.3
    scene = native.Scene()
    pos = native.SHADER_INPUTS["position"][0]
    gen = native.SHADER_INPUTS["generated"][0]
    ids = {}
    for disc in (True, False):
        prog, color = program(disc, size, elevation, rotation)
        ids[disc] = (scene.add_shader_program(prog), color)
    inputs = np.zeros(native.SHADER_INPUT_REGISTERS, dtype=np.float32)

    def radiance(disc: bool, d: np.ndarray) -> np.ndarray:
        pid, color = ids[disc]
        inputs[pos:pos + 3] = d
        inputs[gen:gen + 3] = d
        return scene.evaluate_program(pid, inputs, color, 3).astype(np.float64)

    # The sun's direction as the node places it: azimuth (2 pi - rotation) + pi/2.
    lon = 2 * math.pi - rotation + math.pi / 2
    sun = np.array([math.cos(elevation) * math.cos(lon), math.cos(elevation) * math.sin(lon),
                    math.sin(elevation)])
    # Reference: the disc on a fine grid of its tangent plane (a gnomonic grid; dOmega per point
    # is the plane's area element / (1 + r^2)^(3/2)).
    half = size / 2
    t = np.cross(sun, [0.0, 0.0, 1.0])
    t /= np.linalg.norm(t)
    b = np.cross(sun, t)
    n = 400
    extent = math.tan(half) * 1.02
    step = 2 * extent / n
    reference = np.zeros(3)
    for i in range(n):
        for j in range(n):
            x, y = -extent + (i + 0.5) * step, -extent + (j + 0.5) * step
            r2 = x * x + y * y
            if r2 > extent * extent:
                continue
            d = sun + x * t + y * b
            d /= np.linalg.norm(d)
            extra = radiance(True, d) - radiance(False, d)
            if not extra.any():
                continue
            reference += extra * d[2] * step * step / (1 + r2) ** 1.5
    # The bake: texels around the sun, each the mean of its 2 x 2 directions.
    w, h = args.width, args.width // 2
    theta_sun = math.acos(sun[2])
    phi_sun = math.atan2(sun[1], sun[0])
    col_sun = (0.5 - phi_sun / (2 * math.pi)) % 1.0 * w
    row_sun = theta_sun / math.pi * h
    baked = np.zeros(3)
    for row in range(int(row_sun) - 3, int(row_sun) + 4):
        for col in range(int(col_sun) - 3, int(col_sun) + 4):
            extra = np.zeros(3)
            for sy in range(2):
                for sx in range(2):
                    u = ((col % w) + 0.25 + 0.5 * sx) / w
                    theta = math.pi * (row + 0.25 + 0.5 * sy) / h
                    phi = (0.5 - u) * 2 * math.pi
                    d = np.array([math.sin(theta) * math.cos(phi),
                                  math.sin(theta) * math.sin(phi), math.cos(theta)])
                    extra += radiance(True, d) - radiance(False, d)
            extra /= 4
            t0, t1 = math.pi * row / h, math.pi * (row + 1) / h
            d_omega = 2 * math.pi / w * (math.cos(t0) - math.cos(t1))
            baked += extra * math.cos(math.pi * (row + 0.5) / h) * d_omega
    sky = np.zeros(3)  # the sky's own irradiance, coarse (64 x 32 midpoint rule)
    for row in range(16):
        for col in range(64):
            theta = math.pi * (row + 0.5) / 32
            phi = 2 * math.pi * (col + 0.5) / 64
            d = np.array([math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi),
                          math.cos(theta)])
            d_omega = 2 * math.pi / 64 * (math.cos(math.pi * row / 32) -
                                          math.cos(math.pi * (row + 1) / 32))
            sky += radiance(False, d) * d[2] * d_omega
    ref_y, baked_y, sky_y = (float(luminance(v)) for v in (reference, baked, sky))
    print(f"sun size {args.size} deg, elevation {args.elevation} deg, map {w} x {h}")
    print(f"disc irradiance: reference {ref_y:.5g}, baked {baked_y:.5g}, "
          f"error {baked_y / ref_y - 1:+.2%} (per channel "
          f"{np.round(baked / reference - 1, 4).tolist()})")
    print(f"sky irradiance (no disc) {sky_y:.5g}: the disc is {ref_y / (ref_y + sky_y):.1%} "
          "of the total")


if __name__ == "__main__":
    main()
