"""Determinism in Blender (issue 12, point 9): same scene + settings + seed => one image, for
every render a Blender process makes and for any thread count. Runs in Blender 3.4 and in the
bpy 5.0 wheel.

The bug of issue 12: a primitive-plane Cornell box rendered 20 times in one Blender 3.4 process
gave two images. Blender < 4.1 computes vertex normals with atomic float adds from parallel
tasks of 1024 faces, so a smooth mesh of more than 1024 faces came out of each evaluation with
different last bits (export/vertex_normals.py); the exporter now computes them in a fixed
order. Here:

* the exporter's vertex normals are the same floats on every evaluation of a 32 768-face
  sphere (3.4 gave 16 different arrays in 20 evaluations); they follow their definition and,
  where the exporter computes them (before 4.1), equal Blender's within its float32 rounding;
* full engine renders (export + render each time, the way the bug appeared) of the reporter's
  box, the bundled Cornell box and the materials and world feature scenes (textures, normal
  maps, glass; an importance-sampled environment) repeat one image, threads 1, 2 and 7 in turn;
* every sampler x integrator of the native registries renders those three .blend scenes 10
  times in this process (threads 1, 2, 7 in turn): one image each. (Instancing and motion
  blur are in the native Determinism test: instancing.blend's 3200 instances cost 6 s here.)
"""

from __future__ import annotations

import hashlib
import math
from pathlib import Path
from typing import Any

import bmesh
import bpy
import numpy as np
import pytest

from conftest import REPO, engine_reports
from exr_file import read_image

REPEATS = 10
THREADS = (1, 2, 7)
SCENE_FILES = {
    "cornell_box": REPO / "scenes" / "cornell_box.blend",
    "materials": REPO / "scenes" / "features" / "materials.blend",
    "world": REPO / "scenes" / "features" / "world.blend",
}


def _digest(pixels: np.ndarray) -> str:
    return hashlib.sha1(np.ascontiguousarray(pixels, dtype=np.float32).tobytes()).hexdigest()[:16]


def _sphere_mesh(name: str, segments: int, rings: int, radius: float) -> Any:
    bm = bmesh.new()
    bm.loops.layers.uv.new("UVMap")
    bmesh.ops.create_uvsphere(bm, u_segments=segments, v_segments=rings, radius=radius,
                              calc_uvs=True)
    mesh = bpy.data.meshes.new(name)
    bm.to_mesh(mesh)
    bm.free()
    mesh.polygons.foreach_set("use_smooth", [True] * len(mesh.polygons))
    mesh.update()
    return mesh


# ---- vertex normals -------------------------------------------------------------------------


def test_exported_vertex_normals_are_the_same_on_every_evaluation(stratum_addon: Any) -> None:
    from stratum.export.meshes import mesh_arrays

    bpy.ops.wm.read_factory_settings(use_empty=True)
    mesh = _sphere_mesh("Sphere", 256, 128, 1.0)  # 32 768 faces: 32 of Blender's tasks
    digests = set()
    for _ in range(REPEATS):
        # A moved-by-nothing vertex tags the normals dirty: Blender recomputes them on read.
        mesh.vertices[0].co.x += 0.0
        mesh.update()
        arrays = mesh_arrays(mesh, "Sphere")
        assert arrays.vertex_normals is not None
        digests.add(_digest(arrays.vertex_normals))
    assert len(digests) == 1, f"{len(digests)} different vertex normal arrays in {REPEATS} exports"


def _get(collection: Any, attr: str, count: int, width: int, dtype: Any) -> np.ndarray:
    out = np.empty(count * width, dtype=dtype)
    collection.foreach_get(attr, out)
    return out.reshape(count, width) if width > 1 else out


def _normal_inputs(mesh: Any) -> tuple[np.ndarray, ...]:
    """(positions, corner vertices, face loop starts, face loop totals, face normals) of a
    mesh whose normals were just computed by Blender's mesh code (not carried over from
    bmesh)."""
    mesh.vertices[0].co.x += 0.0
    mesh.update()
    n_vert, n_loop, n_poly = len(mesh.vertices), len(mesh.loops), len(mesh.polygons)
    return (_get(mesh.vertices, "co", n_vert, 3, np.float32),
            _get(mesh.loops, "vertex_index", n_loop, 1, np.uint32),
            _get(mesh.polygons, "loop_start", n_poly, 1, np.int32),
            _get(mesh.polygons, "loop_total", n_poly, 1, np.int32),
            _get(mesh.polygon_normals, "vector", n_poly, 3, np.float32))


def test_vertex_normals_follow_their_definition(stratum_addon: Any) -> None:
    """angle_weighted_vertex_normals against its definition evaluated face by face in float64
    from the same float32 positions and face normals. Bound per vertex, u = 2^-24: a corner's
    float32 cosine (unit edges from a rounded difference, a rounded normalisation and a
    3-term dot) is off by at most about 12 u, so its angle theta by at most
    12 u / sin(theta) + u theta (acos' derivative, then rounding); the weighted sum s of the
    vertex moves by the sum of those (unit face normals), and normalising moves the unit
    result by at most 2 |delta| / |s|, plus a final float32 rounding of 2 u."""
    from stratum.export.vertex_normals import angle_weighted_vertex_normals

    bpy.ops.wm.read_factory_settings(use_empty=True)
    positions, corner_vert, start, total, face_normals = _normal_inputs(
        _sphere_mesh("Sphere", 64, 32, 1.0))
    ours = angle_weighted_vertex_normals(positions, corner_vert, start, total, face_normals)

    u = 2.0**-24
    p = positions.astype(np.float64)
    summed = np.zeros_like(p)
    slack = np.zeros(len(p))
    for face in range(len(start)):
        corners = corner_vert[start[face]:start[face] + total[face]]
        for k, v in enumerate(corners):
            a = p[corners[k - 1]] - p[v]
            b = p[corners[(k + 1) % len(corners)]] - p[v]
            theta = math.acos(max(-1.0, min(1.0, a @ b / math.sqrt((a @ a) * (b @ b)))))
            summed[v] += face_normals[face] * theta
            slack[v] += 12 * u / math.sin(theta) + u * theta
    length = np.linalg.norm(summed, axis=1)
    reference = summed / length[:, None]
    bound = 2 * slack / length + 2 * u
    error = np.linalg.norm(ours - reference, axis=1)
    worst = int(np.argmax(error / bound))
    assert (error <= bound).all(), (
        f"vertex {worst}: ours {ours[worst]}, definition {reference[worst]}, "
        f"|difference| {error[worst]:.3g} > {bound[worst]:.3g}")


def test_vertex_normals_are_blenders_before_4_1(stratum_addon: Any) -> None:
    """Where the exporter computes them (Blender < 4.1), the normals are Blender's own: on a
    coarse sphere (large faces, so Blender's float32 face and corner terms are accurate to a
    few u) they agree with mesh.vertex_normals within Blender's float32 summation error, at
    most about (n + 4) u for a vertex of n corners whose terms are nearly parallel (Higham,
    Accuracy and Stability of Numerical Algorithms, eq. 4.4: n u for the sum, a few u for the
    terms and the normalisation), tested at twice that. A different weighting (by area, or
    none) would miss by 1e-3 or more."""
    from stratum.export.vertex_normals import angle_weighted_vertex_normals

    bpy.ops.wm.read_factory_settings(use_empty=True)
    mesh = _sphere_mesh("Sphere", 12, 6, 1.0)
    if hasattr(mesh, "corner_normals"):
        pytest.skip("Blender 4.1+ computes vertex normals in a fixed order; they are read as is")
    inputs = _normal_inputs(mesh)
    ours = angle_weighted_vertex_normals(*inputs)
    blender = _get(mesh.vertex_normals, "vector", len(mesh.vertices), 3, np.float32)
    valence = np.bincount(inputs[1], minlength=len(mesh.vertices))
    bound = 2 * (valence + 4) * 2.0**-24
    error = np.linalg.norm(ours.astype(np.float64) - blender, axis=1)
    worst = int(np.argmax(error / bound))
    assert (error <= bound).all(), (
        f"vertex {worst} (valence {valence[worst]}): ours {ours[worst]}, Blender's "
        f"{blender[worst]}, |difference| {error[worst]:.3g} > {bound[worst]:.3g}")


# ---- full engine renders ----------------------------------------------------------------------


def _principled(name: str, color: tuple[float, float, float]) -> Any:
    material = bpy.data.materials.new(name)
    if material.node_tree is None:  # 5.0 makes the tree itself (use_nodes is deprecated)
        material.use_nodes = True
    bsdf = material.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*color, 1.0)
    bsdf.inputs["Roughness"].default_value = 1.0
    specular = "Specular" if "Specular" in bsdf.inputs else "Specular IOR Level"  # 4.0+ name
    bsdf.inputs[specular].default_value = 0.0
    return material


def _emission(name: str, strength: float) -> Any:
    material = bpy.data.materials.new(name)
    if material.node_tree is None:  # 5.0 makes the tree itself (use_nodes is deprecated)
        material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Strength"].default_value = strength
    material.node_tree.links.new(emission.outputs["Emission"],
                                 nodes["Material Output"].inputs["Surface"])
    return material


def _object(scene: Any, name: str, mesh: Any, material: Any,
            location: tuple[float, float, float], rotation: tuple[float, float, float] = (0, 0, 0),
            ) -> Any:
    mesh.materials.append(material)
    ob = bpy.data.objects.new(name, mesh)
    ob.location = location
    ob.rotation_euler = rotation
    scene.collection.objects.link(ob)
    return ob


def _plane_mesh(name: str, size: float) -> Any:
    bm = bmesh.new()
    bmesh.ops.create_grid(bm, x_segments=1, y_segments=1, size=size / 2)
    mesh = bpy.data.meshes.new(name)
    bm.to_mesh(mesh)
    bm.free()
    return mesh


def _cube_mesh(name: str, size: float) -> Any:
    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=size)
    mesh = bpy.data.meshes.new(name)
    bm.to_mesh(mesh)
    bm.free()
    return mesh


def _reporters_box() -> Any:
    """Issue 12's scene: a Cornell box of primitive planes (2 m), a 0.5 m emissive plane of
    strength 15 just under the ceiling, Principled walls with roughness 1 and specular 0, two
    cubes standing on the floor, a smooth UV sphere; 24x24, 8 spp, max_bounces 6, seed 3,
    `random`. The sphere has 64 x 32 segments: more than Blender's 1024 faces per normal task,
    which is what made the reporter's renders differ (the default 32 x 16 has 512)."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "STRATUM"
    white = _principled("White", (0.8, 0.8, 0.8))
    red = _principled("Red", (0.8, 0.1, 0.1))
    green = _principled("Green", (0.1, 0.8, 0.1))
    half_pi = math.pi / 2
    walls = {"Floor": ((0, 0, 0), (0, 0, 0), white), "Ceiling": ((0, 0, 2), (math.pi, 0, 0), white),
             "Back": ((0, 1, 1), (half_pi, 0, 0), white), "Left": ((-1, 0, 1), (0, half_pi, 0), red),
             "Right": ((1, 0, 1), (0, -half_pi, 0), green)}
    for name, (location, rotation, material) in walls.items():
        _object(scene, name, _plane_mesh(name, 2.0), material, location, rotation)
    _object(scene, "Light", _plane_mesh("Light", 0.5), _emission("Emitter", 15.0), (0, 0, 1.99),
            (math.pi, 0, 0))
    _object(scene, "Tall", _cube_mesh("Tall", 0.6), white, (-0.35, 0.3, 0.3), (0, 0, 0.3))
    _object(scene, "Short", _cube_mesh("Short", 0.5), white, (0.4, -0.2, 0.25), (0, 0, -0.3))
    _object(scene, "Sphere", _sphere_mesh("Sphere", 64, 32, 0.3), white, (0.3, 0.2, 0.8))
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.location = (0, -3.5, 1)
    camera.rotation_euler = (half_pi, 0, 0)
    scene.collection.objects.link(camera)
    scene.camera = camera
    world = bpy.data.worlds.new("World")
    world.color = (0, 0, 0)
    scene.world = world
    if world.node_tree is not None:
        world.node_tree.nodes["Background"].inputs["Color"].default_value = (0, 0, 0, 1)
    s = scene.stratum
    s.samples, s.max_bounces, s.seed, s.sampler = 8, 6, 3, "random"
    scene.render.resolution_x = scene.render.resolution_y = 24
    scene.render.resolution_percentage = 100
    return scene


def _normal_mapped_sphere() -> Any:
    """A smooth 32 768-face UV sphere whose Principled BSDF takes a tangent-space Normal Map
    from an image, lit by a sun; 64x64, 4 spp. Blender computes both the vertex normals
    (before 4.1) and the MikkTSpace tangents (mesh.calc_tangents, 3.4 and 5.0 alike) of a mesh
    this size in parallel, with last bits that change between evaluations (measured: 10
    different tangent arrays in 10 calls): an exporter reading either as is would fail here."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "STRATUM"
    image = bpy.data.images.new("Bumps", 32, 32, float_buffer=True)
    texel = np.arange(32, dtype=np.float32) / 31.0
    pixels = np.ones((32, 32, 4), dtype=np.float32)
    pixels[..., 0] = 0.5 + 0.3 * np.sin(12.0 * texel)[None, :]  # tilts along u
    pixels[..., 1] = 0.5 + 0.3 * np.cos(9.0 * texel)[:, None]  # tilts along v
    image.pixels.foreach_set(pixels.ravel())
    image.colorspace_settings.name = "Non-Color"
    material = _principled("Bumpy", (0.7, 0.6, 0.5))
    nodes, links = material.node_tree.nodes, material.node_tree.links
    texture = nodes.new("ShaderNodeTexImage")
    texture.image = image
    normal_map = nodes.new("ShaderNodeNormalMap")
    links.new(texture.outputs["Color"], normal_map.inputs["Color"])
    links.new(normal_map.outputs["Normal"], nodes["Principled BSDF"].inputs["Normal"])
    _object(scene, "Sphere", _sphere_mesh("Sphere", 256, 128, 1.0), material, (0, 0, 0))
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.location = (0, -3, 0)
    camera.rotation_euler = (math.pi / 2, 0, 0)
    scene.collection.objects.link(camera)
    scene.camera = camera
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.rotation_euler = (0.8, 0.2, 0.4)
    scene.collection.objects.link(sun)
    s = scene.stratum
    s.samples, s.max_bounces, s.seed, s.sampler = 4, 6, 3, "random"
    scene.render.resolution_x = scene.render.resolution_y = 64
    scene.render.resolution_percentage = 100
    return scene


def _bundled(case: str) -> Any:
    bpy.ops.wm.open_mainfile(filepath=str(SCENE_FILES[case]), load_ui=False)
    scene = bpy.context.scene
    scene.render.engine = "STRATUM"
    scene.render.resolution_x = scene.render.resolution_y = 16
    scene.render.resolution_percentage = 100
    scene.render.use_border = False
    s = scene.stratum
    s.samples, s.max_bounces, s.seed, s.sampler = 4, 6, 3, "random"
    return scene


def _engine_render(scene: Any, path: Path) -> np.ndarray:
    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_depth = "32"  # half floats would hide a difference in the 7th digit
    scene.render.filepath = str(path)
    scene.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    reports = engine_reports("ERROR") + engine_reports("WARNING")
    assert not reports, reports
    return read_image(path)


BUILT_SCENES = {"reporters_box": _reporters_box, "normal_mapped_sphere": _normal_mapped_sphere}


@pytest.mark.parametrize("case", [*BUILT_SCENES, *SCENE_FILES])
def test_engine_renders_repeat_one_image(library: Any, tmp_path: Path, case: str) -> None:
    scene = BUILT_SCENES[case]() if case in BUILT_SCENES else _bundled(case)
    digests: dict[str, list[int]] = {}
    for i in range(REPEATS):
        scene.stratum.threads = THREADS[i % len(THREADS)]
        pixels = _engine_render(scene, tmp_path / f"{case}_{i}.exr")
        if i == 0:
            assert np.isfinite(pixels).all() and pixels[..., :3].max() > 0.0
        digests.setdefault(_digest(pixels), []).append(i)
    assert len(digests) == 1, f"{case}: renders by image: {list(digests.values())}"


# ---- every sampler x integrator, natively in this process ------------------------------------


@pytest.mark.parametrize("case", list(SCENE_FILES))
def test_every_sampler_and_integrator_repeats_one_image(library: Any, case: str) -> None:
    from stratum.export.sync import export_scene

    _bundled(case)
    samplers = [entry.name for entry in library.registry("sampler")]
    integrators = [entry.name for entry in library.registry("integrator")]
    failures = []
    with library.Scene() as native_scene:
        summary = export_scene(bpy.context.evaluated_depsgraph_get(), native_scene)
        assert not summary.warnings, summary.warnings
        for integrator in integrators:
            for sampler in samplers:
                digests: dict[str, list[int]] = {}
                for i in range(REPEATS):
                    with library.Renderer(native_scene, width=16, height=16, samples=4,
                                          max_bounces=6, seed=3, sampler=sampler,
                                          integrator=integrator,
                                          threads=THREADS[i % len(THREADS)],
                                          # radiosity's solve at its cheapest (one patch per
                                          # triangle side, few rays): as deterministic at any size
                                          radiosity_patch_size=100.0,
                                          radiosity_rays=16) as renderer:
                        renderer.start()
                        while not renderer.wait(1000):
                            pass
                        pixels = renderer.read_pixels()
                    if i == 0:
                        assert np.isfinite(pixels).all() and pixels.max() > 0.0, (
                            f"{integrator} x {sampler}: black or non-finite image")
                    digests.setdefault(_digest(pixels), []).append(i)
                if len(digests) > 1:
                    failures.append(f"{integrator} x {sampler}: {list(digests.values())}")
    assert not failures, f"{case}: renders by image:\n" + "\n".join(failures)
