"""Sky Texture (ShaderNodeTexSky) into the native `sky` node.

| sky_type (Blender)              | native model | data                                         |
|---------------------------------|--------------|----------------------------------------------|
| PREETHAM (3.x, 4.x, 5.x)        | 0            | 32 coefficients computed here (as Cycles)    |
| NISHITA (3.x, 4.x)              | 2            | elevation, rotation, size, intensity,        |
|                                 |              | altitude, air, dust, ozone (table natively)  |
| SINGLE_SCATTERING (5.x)         | 3            | the same 8 (aerosol density as dust)         |
| HOSEK_WILKIE (3.x, 4.x, 5.x)    | 1            | 32 values cooked here from the published     |
|                                 |              | dataset (hosek_wilkie_data.py), as Cycles    |
| MULTIPLE_SCATTERING (5.x)       | 4            | the same 8                                   |

The Vector input unlinked reads Cycles' default, the Generated coordinate (for the world, the
ray's direction). A Texture Mapping other than the identity is warned about and ignored."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from ... import blender_versions
from . import hosek_wilkie_data as hw_dataset
from .compiler import NodeCompiler, Unsupported
from .registry import translator

PREETHAM, HOSEK_WILKIE, NISHITA, SINGLE_SCATTERING, MULTIPLE_SCATTERING = 0, 1, 2, 3, 4
SCATTERING_MODELS = {"NISHITA": NISHITA, "SINGLE_SCATTERING": SINGLE_SCATTERING,
                     "MULTIPLE_SCATTERING": MULTIPLE_SCATTERING}


def _perez(k: Sequence[float], theta: float, gamma: float) -> float:
    return ((1.0 + k[0] * math.exp(k[1] / math.cos(theta)))
            * (1.0 + k[2] * math.exp(k[3] * gamma) + k[4] * math.cos(gamma) ** 2))


def preetham_data(sun_direction: Sequence[float], turbidity: float) -> list[float]:
    """The 32 values Cycles' sky_texture_precompute_preetham packs: the sun's phi and theta,
    the zenith Y, x, y (divided by the Perez function at the zenith), and per channel the five
    Perez coefficients padded with four zeros."""
    x, y, z = (float(v) for v in sun_direction)
    norm = math.sqrt(x * x + y * y + z * z)  # Blender's sync normalises the direction
    if norm > 0.0:
        x, y, z = x / norm, y / norm, z / norm
    theta = math.acos(max(-1.0, min(1.0, z)))
    phi = math.atan2(x, y)
    t, t2 = float(turbidity), float(turbidity) ** 2
    th2, th3 = theta * theta, theta ** 3
    chi = (4.0 / 9.0 - t / 120.0) * (math.pi - 2.0 * theta)
    zenith_y = ((4.0453 * t - 4.9710) * math.tan(chi) - 0.2155 * t + 2.4192) * 0.06
    zenith_x = ((0.00166 * th3 - 0.00375 * th2 + 0.00209 * theta) * t2
                + (-0.02903 * th3 + 0.06377 * th2 - 0.03202 * theta + 0.00394) * t
                + (0.11693 * th3 - 0.21196 * th2 + 0.06052 * theta + 0.25886))
    zenith_yy = ((0.00275 * th3 - 0.00610 * th2 + 0.00317 * theta) * t2
                 + (-0.04214 * th3 + 0.08970 * th2 - 0.04153 * theta + 0.00516) * t
                 + (0.15346 * th3 - 0.26756 * th2 + 0.06670 * theta + 0.26688))
    perez_y = [0.1787 * t - 1.4630, -0.3554 * t + 0.4275, -0.0227 * t + 5.3251,
               0.1206 * t - 2.5771, -0.0670 * t + 0.3703]
    perez_x = [-0.0193 * t - 0.2592, -0.0665 * t + 0.0008, -0.0004 * t + 0.2125,
               -0.0641 * t - 0.8989, -0.0033 * t + 0.0452]
    perez_yy = [-0.0167 * t - 0.2608, -0.0950 * t + 0.0092, -0.0079 * t + 0.2102,
                -0.0441 * t - 1.6537, -0.0109 * t + 0.0529]
    data = [phi, theta]
    # Cycles calls perez(config, 0, theta): theta 0 as the view angle, the sun's theta as gamma.
    data += [zenith_y / _perez(perez_y, 0.0, theta), zenith_x / _perez(perez_x, 0.0, theta),
             zenith_yy / _perez(perez_yy, 0.0, theta)]
    for k in (perez_y, perez_x, perez_yy):
        data += k + [0.0] * 4
    return data


def _bezier(points: Sequence[float], at: int, stride: int, t: float) -> float:
    """The quintic Bezier of the 6 control points points[at + k * stride] at t."""
    u = 1.0 - t
    weights = (u ** 5, 5.0 * u ** 4 * t, 10.0 * u ** 3 * t ** 2, 10.0 * u ** 2 * t ** 3,
               5.0 * u * t ** 4, t ** 5)
    return sum(w * points[at + k * stride] for k, w in enumerate(weights))


def _cook(dataset: Sequence[float], width: int, turbidity: float, albedo: float,
          elevation: float) -> list[float]:
    """Hosek and Wilkie's interpolation of `width` coefficients: a quintic Bezier over the cube
    root of the elevation's fraction of pi/2, linear in albedo (0, 1) and in turbidity (1..10)."""
    whole = int(turbidity)
    rest = turbidity - whole
    t = (elevation / (math.pi / 2.0)) ** (1.0 / 3.0)
    block = 6 * width  # one turbidity's control points
    out = [0.0] * width
    terms = [(1.0 - albedo) * (1.0 - rest), albedo * (1.0 - rest)]
    starts = [block * (whole - 1), block * 10 + block * (whole - 1)]
    if whole != 10:
        terms += [(1.0 - albedo) * rest, albedo * rest]
        starts += [block * whole, block * 10 + block * whole]
    for weight, start in zip(terms, starts, strict=True):
        for i in range(width):
            out[i] += weight * _bezier(dataset, start + i, width, t)
    return out


def hosek_wilkie_data(sun_direction: Sequence[float], turbidity: float,
                      ground_albedo: float) -> list[float]:
    """The 32 values of Cycles' sky_texture_precompute_hosek: the sun's phi and theta (theta
    clamped to the horizon), the X, Y, Z radiances and 9 configuration values per channel, from
    the XYZ dataset (in double precision, as Cycles cooks them). Turbidity is clamped to [1, 10]
    (Blender's range; Cycles' [0, 10] reads before the dataset below 1)."""
    x, y, z = (float(v) for v in sun_direction)
    norm = math.sqrt(x * x + y * y + z * z)
    if norm > 0.0:
        x, y, z = x / norm, y / norm, z / norm
    theta = min(max(math.acos(max(-1.0, min(1.0, z))), 0.0), math.pi / 2.0)
    phi = math.atan2(x, y)
    t = min(max(float(turbidity), 1.0), 10.0)
    albedo = float(ground_albedo)
    elevation = math.pi / 2.0 - theta
    configs = [_cook(hw_dataset.CONFIGS[c], 9, t, albedo, elevation) for c in range(3)]
    radiances = [_cook(hw_dataset.RADIANCES[c], 1, t, albedo, elevation)[0]
                 for c in range(3)]
    return [phi, theta, *radiances, *configs[0], *configs[1], *configs[2]]


def nishita_data(node: Any) -> list[float]:
    """Elevation, rotation, size, intensity, altitude, air, dust and ozone, as Blender holds
    them (the native node applies Cycles' clamps and wraps)."""
    dust = getattr(node, "dust_density", getattr(node, "aerosol_density", 1.0))
    return [float(node.sun_elevation), float(node.sun_rotation), float(node.sun_size),
            float(node.sun_intensity), float(node.altitude), float(node.air_density),
            float(dust), float(node.ozone_density)]


def _mapping_is_identity(node: Any) -> bool:
    mapping = getattr(node, "texture_mapping", None)
    if mapping is None:
        return True
    same = (tuple(getattr(mapping, "translation", (0, 0, 0))) == (0, 0, 0)
            and tuple(getattr(mapping, "rotation", (0, 0, 0))) == (0, 0, 0)
            and tuple(getattr(mapping, "scale", (1, 1, 1))) == (1, 1, 1))
    return same and not getattr(mapping, "use_min", False) and not getattr(mapping, "use_max",
                                                                            False)


@translator("ShaderNodeTexSky")
def translate_sky(c: NodeCompiler, node: Any) -> dict[str, int]:
    sky_type = str(node.sky_type)
    if sky_type == "PREETHAM":
        model, data = PREETHAM, preetham_data(node.sun_direction, node.turbidity)
        disc = 0
    elif sky_type == "HOSEK_WILKIE":
        model = HOSEK_WILKIE
        data = hosek_wilkie_data(node.sun_direction, node.turbidity, node.ground_albedo)
        disc = 0
    elif sky_type in SCATTERING_MODELS:
        model = SCATTERING_MODELS[sky_type]
        data = nishita_data(node)
        disc = int(bool(node.sun_disc))
    else:
        raise Unsupported(f"Sky Texture '{node.name}': sky type {sky_type} is not supported")
    if not _mapping_is_identity(node):
        c.warn(node, f"Sky Texture '{node.name}': its Texture Mapping is ignored", "mapping")
    vector = c.vector_or(node, "Vector", "generated")
    # XYZ to Rec.709 as the version's colour configuration defines it, for every model: Cycles
    # converts each through its film's XYZ -> scene linear (xyz_to_rgb_clamped).
    matrix = blender_versions.color_config(c.version)
    color = c.builder.node("sky", (model, disc, matrix), (vector,), (3,), data)[0]
    return {"Color": color}
