"""Render settings at their limits: 1 sample and 1024 bounces (path and light tracing), a 1x1
and a 65536-pixel-wide image, empty, inverted and cropped borders, 1024 threads, the
widest pixel filter, the largest seed, the shortest AO distance."""

from __future__ import annotations

from .case import case, clean, error, lit_centre, survive
from .stage import Stage


def _closed_box(s: Stage) -> None:
    """The camera inside a closed 4 m room with the lamp: every path bounces until roulette
    or max_bounces ends it."""
    s.base()
    room = s.mesh("Room", location=(0.0, -4.0, 0.0), scale=(4.0, 4.0, 4.0))
    for polygon in room.data.polygons:
        polygon.flip()


@case("set_one_sample", "settings", "1 sample per pixel", clean(quiet=True))
def set_one_sample(s: Stage) -> None:
    s.base()
    s.scene.stratum.samples = 1


@case("set_1024_bounces_path", "settings", "max_bounces 1024 in a closed room (path tracer)",
      clean(quiet=True, pixels=lit_centre))
def set_1024_bounces_path(s: Stage) -> None:
    _closed_box(s)
    s.scene.stratum.max_bounces = 1024


@case("set_1024_bounces_light", "settings",
      "max_bounces 1024 in a closed room (light tracer), roulette off",
      clean(pixels=lit_centre))
def set_1024_bounces_light(s: Stage) -> None:
    _closed_box(s)
    st = s.scene.stratum
    st.integrator, st.max_bounces, st.rr_mode = "light", 1024, "off"


@case("set_resolution_1x1", "settings", "a 1x1 image (4x4 at 25%)", clean(quiet=True),
      size=(1, 1))
def set_resolution_1x1(s: Stage) -> None:
    s.base()
    r = s.scene.render
    r.resolution_x, r.resolution_y, r.resolution_percentage = 4, 4, 25


@case("set_resolution_65536_wide", "settings", "a 65536x4 image (the widest Blender allows)",
      clean(quiet=True), size=(65536, 4))
def set_resolution_65536_wide(s: Stage) -> None:
    s.base()
    r = s.scene.render
    r.resolution_x, r.resolution_y = 65536, 4
    s.scene.stratum.samples = 1


# Blender's largest frame: the film would need 208 GiB. Refused by the renderer before Blender's
# result or the add-on's pixel buffer is allocated (65536 x 20000 was OOM-killed before); a
# border of it renders (set_border_of_largest_frame).
@case("set_resolution_beyond_memory", "settings",
      "a 65536x65536 image (Blender's largest; its film needs more than the machine has)",
      error(words=("65536 x 65536", "film", "memory")))
def set_resolution_beyond_memory(s: Stage) -> None:
    s.base()
    r = s.scene.render
    r.resolution_x, r.resolution_y, r.resolution_percentage = 65536, 65536, 100
    s.scene.stratum.samples = 1


@case("set_border_of_largest_frame", "settings",
      "an 8x8 border, cropped to, of a 65536x65536 frame (the film is the border's)",
      clean(quiet=True), size=(8, 8))
def set_border_of_largest_frame(s: Stage) -> None:
    s.base()
    r = s.scene.render
    r.resolution_x, r.resolution_y, r.resolution_percentage = 65536, 65536, 100
    r.use_border, r.use_crop_to_border = True, True
    r.border_min_x, r.border_max_x = 0.5, 0.5 + 8 / 65536
    r.border_min_y, r.border_max_y = 0.5, 0.5 + 8 / 65536
    s.scene.stratum.samples = 1


def _border(s: Stage, x: tuple[float, float], y: tuple[float, float], crop: bool) -> None:
    s.base()
    r = s.scene.render
    r.use_border, r.use_crop_to_border = True, crop
    r.border_min_x, r.border_max_x = x
    r.border_min_y, r.border_max_y = y


# Blender itself refuses a border without pixels ("Image too small") before the engine runs.
@case("set_border_zero_width", "settings", "a render border of zero width",
      survive(words=("too small", "border")))
def set_border_zero_width(s: Stage) -> None:
    _border(s, (0.5, 0.5), (0.0, 1.0), crop=False)


@case("set_border_inverted", "settings", "a render border with min > max",
      survive(words=("too small", "border")))
def set_border_inverted(s: Stage) -> None:
    _border(s, (0.9, 0.1), (0.9, 0.1), crop=False)


@case("set_border_cropped", "settings", "the middle 8x8 pixels as border, cropped to it",
      clean(quiet=True, pixels=lit_centre), size=(8, 8))
def set_border_cropped(s: Stage) -> None:
    _border(s, (0.25, 0.75), (0.25, 0.75), crop=True)


@case("set_threads_1024", "settings", "1024 render threads on a 2-core machine",
      clean(quiet=True, pixels=lit_centre))
def set_threads_1024(s: Stage) -> None:
    s.base()
    s.scene.stratum.threads = 1024


@case("set_widest_filter", "settings", "a Blackman-Harris filter 10 pixels wide",
      clean(quiet=True, pixels=lit_centre))
def set_widest_filter(s: Stage) -> None:
    s.base()
    st = s.scene.stratum
    st.filter_type, st.filter_width = "blackman_harris", 10.0


@case("set_largest_seed", "settings", "seed 2^31 - 1 with the sobol sampler", clean(quiet=True))
def set_largest_seed(s: Stage) -> None:
    s.base()
    st = s.scene.stratum
    st.seed, st.sampler = 2**31 - 1, "sobol"


@case("set_ao_shortest_distance", "settings", "ambient occlusion with distance 1e-4",
      clean(quiet=True, pixels=lit_centre))
def set_ao_shortest_distance(s: Stage) -> None:
    s.base()
    st = s.scene.stratum
    st.integrator, st.ao_distance = "ao", 1e-4
