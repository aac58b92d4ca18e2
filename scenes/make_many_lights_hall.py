"""Build the many-light scene of issue 16 (a hall lit by 1,000 small lamps) and save it as a
compressed .blend.

Run (Blender 3.4, so that the file opens in 3.4 and in every later Blender):

    blender -b --factory-startup --python scenes/make_many_lights_hall.py -- scenes/many_lights_hall.blend

The light tree's study (docs/study.md "Light selection", `make study`) needs a scene where most
lamps contribute nothing to most shading points and where their powers differ, so that power
or uniform selection waste nearly every shadow ray: a hall (floor, back and side walls, no
ceiling, a black world) 20 m x 10 m x 4 m, two rows of columns and a few boxes so that what a
point sees varies, and LAMPS point lamps of radius 2-5 cm in four groups:

* chandeliers: 10 clusters of 40 lamps within 0.5 m of a point 3.2 m up along the hall;
* wall strings: two rows of 100 lamps along the back wall (1.2 m and 2.6 m up);
* side lamps: 50 lamps on each side wall;
* floor lamps: 300 lamps 0.1-0.6 m above the floor, scattered between columns and boxes.

Powers are log-uniform in [POWER_LO, POWER_HI] W (a factor 50) and colours drawn from a warm to
cold palette, by a seeded generator: the file is the same at every run. Lamps are invisible to
camera rays (their discs would be single-pixel fireflies in any error measure), visible to
every other ray. Lamps of one (colour, power-step) share one light datablock, which keeps the
file small. The stored engine is Cycles (`-E STRATUM` selects Stratum at render time).
"""

from __future__ import annotations

import os
import random
import sys

import bpy

# Blender does not put a --python script's folder on sys.path; scene_building.py is there.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scene_building import (
    Face,
    Vec,
    aim,
    clear_scene,
    mesh_object,
    output_path,
    perspective_camera,
    png_render_settings,
    principled,
    quad,
    save,
    uniform_world,
)

LAMPS = 1000
POWER_LO, POWER_HI = 0.05, 2.5  # W, log-uniform
POWER_STEPS = 8  # distinct powers (shared light datablocks)
PALETTE: list[Vec] = [(1.0, 0.62, 0.3), (1.0, 0.8, 0.55), (1.0, 0.95, 0.85), (0.75, 0.85, 1.0),
                      (0.5, 0.7, 1.0), (1.0, 0.45, 0.45), (0.55, 1.0, 0.6)]
HALL_X, HALL_Y, HALL_Z = 10.0, 5.0, 4.0  # half length, half depth, height (m)
# Columns (x, y) of 0.5 m x 0.5 m, and boxes (lo, hi): the obstacles.
COLUMNS = [(x, y) for x in (-7.5, -4.5, -1.5, 1.5, 4.5, 7.5) for y in (-2.0, 2.0)]
BOXES = [((-6.0, -0.5, 0.0), (-5.0, 0.5, 1.0)), ((2.5, -1.0, 0.0), (3.5, 0.2, 0.7)),
         ((-2.8, 3.0, 0.0), (-1.8, 4.0, 1.5)), ((6.0, 0.5, 0.0), (7.2, 1.5, 1.2))]


def box(name: str, lo: Vec, hi: Vec, material: bpy.types.Material) -> bpy.types.Object:
    """Axis-aligned box [lo, hi], faces outward."""
    v = [(x, y, z) for z in (lo[2], hi[2]) for y in (lo[1], hi[1]) for x in (lo[0], hi[0])]
    faces: list[Face] = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2),
                         (1, 3, 7, 5)]
    return mesh_object(name, v, faces, material)


def build_hall() -> None:
    floor = principled("Floor", (0.6, 0.6, 0.6), roughness=0.6)
    wall = principled("Wall", (0.7, 0.68, 0.65))
    stone = principled("Stone", (0.5, 0.5, 0.55))
    X, Y, Z = HALL_X, HALL_Y, HALL_Z
    quad("Floor", [(-X, -Y - 5.0, 0.0), (X, -Y - 5.0, 0.0), (X, Y, 0.0), (-X, Y, 0.0)], floor)
    quad("BackWall", [(-X, Y, 0.0), (X, Y, 0.0), (X, Y, Z), (-X, Y, Z)], wall)
    quad("LeftWall", [(-X, -Y, 0.0), (-X, Y, 0.0), (-X, Y, Z), (-X, -Y, Z)], wall)
    quad("RightWall", [(X, Y, 0.0), (X, -Y, 0.0), (X, -Y, Z), (X, Y, Z)], wall)
    for k, (x, y) in enumerate(COLUMNS):
        box(f"Column{k}", (x - 0.25, y - 0.25, 0.0), (x + 0.25, y + 0.25, Z), stone)
    for k, (lo, hi) in enumerate(BOXES):
        box(f"Box{k}", lo, hi, stone)


def blocked(x: float, y: float) -> bool:
    """Inside (or within 0.1 m of) a column or a box: no floor lamp there."""
    if any(abs(x - cx) < 0.35 and abs(y - cy) < 0.35 for cx, cy in COLUMNS):
        return True
    return any(lo[0] - 0.1 < x < hi[0] + 0.1 and lo[1] - 0.1 < y < hi[1] + 0.1 for lo, hi in BOXES)


def lamp_positions(rng: random.Random) -> list[Vec]:
    """The four groups of the module's docstring, LAMPS in all."""
    positions: list[Vec] = []
    for c in range(10):
        cx, cy = -9.0 + 2.0 * c, -1.0 + 2.0 * (c % 2)
        while len(positions) < 40 * (c + 1):
            dx, dy, dz = (rng.uniform(-0.5, 0.5) for _ in range(3))
            if dx * dx + dy * dy + dz * dz <= 0.25:
                positions.append((cx + dx, cy + dy, 3.2 + dz))
    for z in (1.2, 2.6):
        positions += [(-9.8 + 19.6 * (i + 0.5) / 100, HALL_Y - 0.15, z) for i in range(100)]
    for x in (-HALL_X + 0.15, HALL_X - 0.15):
        positions += [(x, rng.uniform(-HALL_Y + 0.3, HALL_Y - 0.3), rng.uniform(0.5, 3.5)) for _ in range(50)]
    while len(positions) < LAMPS:
        x, y = rng.uniform(-HALL_X + 0.3, HALL_X - 0.3), rng.uniform(-HALL_Y + 0.3, HALL_Y - 0.3)
        if not blocked(x, y):
            positions.append((x, y, rng.uniform(0.1, 0.6)))
    return positions


def build_lamps() -> None:
    rng = random.Random(16)
    datablocks: dict[tuple[int, int], bpy.types.Light] = {}
    for k, position in enumerate(lamp_positions(rng)):
        colour, step = rng.randrange(len(PALETTE)), rng.randrange(POWER_STEPS)
        data = datablocks.get((colour, step))
        if data is None:
            data = bpy.data.lights.new(f"Lamp{colour}_{step}", type="POINT")
            data.color = PALETTE[colour]
            data.energy = POWER_LO * (POWER_HI / POWER_LO) ** (step / (POWER_STEPS - 1))
            data.shadow_soft_size = 0.02 + 0.03 * step / (POWER_STEPS - 1)  # radius, m
            datablocks[(colour, step)] = data
        obj = bpy.data.objects.new(f"Lamp{k:04d}", data)
        obj.location = position
        obj.visible_camera = False
        bpy.context.scene.collection.objects.link(obj)


def main() -> None:
    path = output_path("scenes/make_many_lights_hall.py -- scenes/many_lights_hall.blend")
    clear_scene()
    scene = bpy.context.scene
    scene.name = "ManyLightsHall"
    build_hall()
    build_lamps()
    cam = perspective_camera(lens=20.0, clip_start=0.05, location=(0.0, -9.5, 1.8))
    aim(cam, (0.0, 2.0, 1.3))
    uniform_world(scene, (0.0, 0.0, 0.0))
    png_render_settings(scene, 320, 180)
    save(path)


main()
