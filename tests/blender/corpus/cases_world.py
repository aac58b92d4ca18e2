"""World: NaN and extreme Background colour and strength, environment images with NaN or
negative pixels (both became 0 silently), a missing environment image, an unsupported world
shader, no world at all."""

from __future__ import annotations

from typing import Any

import bpy

from .case import case, clean, lit, warning
from .stage import Stage

NAN = float("nan")


def _world(s: Stage, name: str, color: tuple[float, float, float] = (0.2, 0.2, 0.2),
           strength: float = 1.0) -> Any:
    """The base scene under world `name` with the given Background colour and strength."""
    s.base()
    world = s.world(name=name)
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (*color, 1.0)
    background.inputs["Strength"].default_value = strength
    return world


@case("world_nan_colour", "world", "Background colour NaN",
      warning("NanWorld", words=("colour", "color")))
def world_nan_colour(s: Stage) -> None:
    _world(s, "NanWorld", color=(NAN, NAN, NAN))


@case("world_nan_strength", "world", "Background strength NaN",
      warning("NanStrengthWorld", words=("strength",)))
def world_nan_strength(s: Stage) -> None:
    _world(s, "NanStrengthWorld", strength=NAN)


@case("world_negative_strength", "world", "Background strength -1",
      warning("DarkWorld", words=("strength",)))
def world_negative_strength(s: Stage) -> None:
    _world(s, "DarkWorld", strength=-1.0)


@case("world_strength_3e38", "world", "Background strength 3e38 (colour 0.2)",
      clean(pixels=lit))
def world_strength_3e38(s: Stage) -> None:
    _world(s, "BlindingWorld", strength=3e38)


def _environment(s: Stage, world: str, image: Any, strength: float = 1.0) -> None:
    w = _world(s, world, strength=strength)
    nt = w.node_tree
    env = nt.nodes.new("ShaderNodeTexEnvironment")
    env.image = image
    nt.links.new(env.outputs["Color"], nt.nodes["Background"].inputs["Color"])


def _float_image(name: str, value: float) -> Any:
    image = bpy.data.images.new(name, 8, 4, float_buffer=True)
    image.pixels.foreach_set([value, value, value, 1.0] * 32)
    return image


@case("world_environment_nan_pixels", "world", "an environment image whose pixels are NaN",
      warning("NanSky", words=("nan", "finite", "pixel")))
def world_environment_nan_pixels(s: Stage) -> None:
    _environment(s, "Heaven", _float_image("NanSky", NAN))


@case("world_environment_negative_pixels", "world", "an environment image of pixels -1",
      warning("NegativeSky", words=("negative", "pixel")))
def world_environment_negative_pixels(s: Stage) -> None:
    _environment(s, "Heaven", _float_image("NegativeSky", -1.0))


@case("world_environment_missing_image", "world", "an environment image whose file is missing",
      warning("LostSky"))
def world_environment_missing_image(s: Stage) -> None:
    _environment(s, "Heaven", s.file_image("LostSky", s.tmp / "no_such_sky.exr"))


@case("world_environment_strength_3e38", "world", "an environment image at strength 3e38",
      clean(pixels=lit))
def world_environment_strength_3e38(s: Stage) -> None:
    _environment(s, "Heaven", _float_image("BrightSky", 1.0), strength=3e38)


@case("world_emission_shader", "world", "an Emission shader on the World Output",
      warning("GlowWorld", words=("Emission", "not supported")))
def world_emission_shader(s: Stage) -> None:
    w = _world(s, "GlowWorld")
    nt = w.node_tree
    emission = nt.nodes.new("ShaderNodeEmission")
    nt.links.new(emission.outputs[0], nt.nodes["World Output"].inputs["Surface"])


@case("world_none", "world", "a scene without a world", clean())
def world_none(s: Stage) -> None:
    s.base()
    s.scene.world = None
