"""Lights: zero, negative, NaN, infinite and near-FLT_MAX power (a 3e38 W point light or sun
contributed exactly 0), NaN colour and sizes, degenerate area lights, the extremes of spot size
and sun angle, placement at NaN and far away. Every light is aimed at the base cube."""

from __future__ import annotations

import math
from typing import Any

from .case import case, clean, culprit, lit_centre, survive, warning
from .stage import Stage

NAN = float("nan")
FLT_MAX = 3.4028234663852886e38
# Straight down onto the cube from above and in front: (0, -3, 3) looking at the origin.
AIM = (math.radians(45.0), 0.0, 0.0)


def _lamp(s: Stage, kind: str, name: str, energy: float, **fields: Any) -> Any:
    """The base scene without its point light: `kind` light `name` aimed at the cube."""
    s.camera()
    s.mesh("Cube")
    s.world((0.0, 0.0, 0.0))
    ob = s.light(kind, name, energy, location=(0.0, -3.0, 3.0), rotation=AIM)
    for field_name, value in fields.items():
        setattr(ob.data, field_name, value)
    return ob


def _lamp_case(name: str, what: str, expect: Any, kind: str, lamp: str, energy: float,
               **fields: Any) -> None:
    case(name, "lights", what, expect)(lambda s: _lamp(s, kind, lamp, energy, **fields))


_lamp_case("light_zero_power", "a point light of 0 W", clean(), "POINT", "Off", 0.0)
_lamp_case("light_negative_power", "a point light of -500 W (Cycles subtracts light)", clean(),
           "POINT", "Sink", -500.0)
_lamp_case("light_nan_power", "a point light of NaN W",
           warning("NanLamp", words=("power", "energy", "strength")), "POINT", "NanLamp", NAN)
_lamp_case("light_inf_power", "a point light of +inf W (RNA keeps inf here)",
           warning("InfLamp", words=("power", "energy", "strength")), "POINT", "InfLamp",
           math.inf)
for _kind, _label in (("POINT", "point"), ("SPOT", "spot"), ("SUN", "sun"), ("AREA", "area")):
    _lamp_case(f"light_{_label}_3e38", f"a {_label} light of 3e38 W (a point or sun gave 0)",
               clean(pixels=lit_centre), _kind, f"Blazing{_label.title()}", 3e38)
_lamp_case("light_area_flt_max_colour", "an area light of FLT_MAX W with colour (1, 1, 1)",
           clean(pixels=lit_centre), "AREA", "Brightest", FLT_MAX)
_lamp_case("light_zero_size_area", "an area light of size 0",
           warning("NoArea", words=("size", "area")), "AREA", "NoArea", 100.0, size=0.0)
_lamp_case("light_nan_area_size", "an area light of size NaN",
           warning("NanArea", words=("size",)), "AREA", "NanArea", 100.0, size=NAN)
_lamp_case("light_nan_spot_size", "a spot light of cone NaN",
           warning("NanSpot", words=("spot", "size", "cone")), "SPOT", "NanSpot", 500.0,
           spot_size=NAN)
_lamp_case("light_sun_angle_0", "a sun of angle 0 (a delta light)",
           clean(pixels=lit_centre), "SUN", "Pinpoint", 3.0, angle=0.0)
_lamp_case("light_sun_angle_pi", "a sun of angle 180 degrees (a whole hemisphere)",
           clean(pixels=lit_centre), "SUN", "Dome", 3.0, angle=math.pi)
_lamp_case("light_nan_sun_angle", "a sun of angle NaN", warning("NanSun", words=("angle",)),
           "SUN", "NanSun", 3.0, angle=NAN)
_lamp_case("light_nan_colour", "a point light of colour NaN",
           warning("NanTint", words=("colour", "color")), "POINT", "NanTint", 500.0,
           color=(NAN, NAN, NAN))
_lamp_case("light_nan_radius", "a point light of radius NaN",
           warning("NanBulb", words=("radius", "size")), "POINT", "NanBulb", 500.0,
           shadow_soft_size=NAN)
_lamp_case("light_huge_radius", "a point light of radius FLT_MAX (its disk holds the scene)",
           survive("HugeBulb"), "POINT", "HugeBulb", 500.0, shadow_soft_size=FLT_MAX)


@case("light_tiny_spot", "lights",
      "a spot light of the smallest cone (1 degree), 40 m away: a 0.7 m disk on the cube",
      clean(pixels=lit_centre))
def light_tiny_spot(s: Stage) -> None:
    ob = _lamp(s, "SPOT", "Needle", 5000.0, spot_size=math.radians(1.0))
    ob.location, ob.rotation_euler = (0.0, -40.0, 0.0), (math.pi / 2, 0.0, 0.0)


@case("light_zero_scale_area", "lights", "an area light whose object is scaled 0",
      warning("Squashed", words=("size", "area", "scale")))
def light_zero_scale_area(s: Stage) -> None:
    _lamp(s, "AREA", "Squashed", 100.0).scale = (0.0, 0.0, 0.0)


@case("light_nan_location", "lights", "a point light at (NaN, 0, 0)",
      culprit("Lost", words=("transform", "matrix", "location", "position", "nan", "finite")))
def light_nan_location(s: Stage) -> None:
    _lamp(s, "POINT", "Lost", 500.0).location = (NAN, 0.0, 0.0)


@case("light_far_away", "lights", "a point light 1e19 m away", survive("Distant"))
def light_far_away(s: Stage) -> None:
    _lamp(s, "POINT", "Distant", 500.0).location = (0.0, -1e19, 1e19)


@case("light_none", "lights", "no lights and a black world: a black image", clean())
def light_none(s: Stage) -> None:
    s.camera()
    s.mesh("Cube")
    s.world((0.0, 0.0, 0.0))
