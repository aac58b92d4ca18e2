"""Object types other than plain meshes: what renders (curves, text, metaballs, instancers) and
what Stratum cannot render and must name once per kind (point clouds, volumes, hair, fluid
domains) instead of dropping silently or, for a fluid domain, drawing its box as a surface."""

from __future__ import annotations

from typing import Any

import bpy

from .case import case, clean, lit_centre, warning
from .stage import Stage


@case("obj_bevelled_curve", "objects", "a bevelled Bezier curve across the view",
      clean(quiet=True, pixels=lit_centre))
def obj_bevelled_curve(s: Stage) -> None:
    s.base(cube=False)
    curve = bpy.data.curves.new("Rail", "CURVE")
    curve.dimensions = "3D"
    curve.bevel_depth = 0.5
    spline = curve.splines.new("BEZIER")
    spline.bezier_points.add(1)
    for point, x in zip(spline.bezier_points, (-2.0, 2.0), strict=True):
        point.co = (x, 0.0, 0.0)
        point.handle_left_type = point.handle_right_type = "AUTO"
    s.link(bpy.data.objects.new("Rail", curve))


@case("obj_curve_without_geometry", "objects", "a curve without bevel or extrusion (no faces)",
      clean(same_as=lambda s: s.base()))
def obj_curve_without_geometry(s: Stage) -> None:
    s.base()
    curve = bpy.data.curves.new("Thread", "CURVE")
    spline = curve.splines.new("POLY")
    spline.points.add(1)
    spline.points[1].co = (1.0, 0.0, 0.0, 1.0)
    s.link(bpy.data.objects.new("Thread", curve))


@case("obj_text", "objects", "a text object in front of the camera",
      clean(quiet=True, pixels=lit_centre))
def obj_text(s: Stage) -> None:
    s.base(cube=False)
    text = bpy.data.curves.new("Label", "FONT")
    text.body = "HX"
    text.size = 3.0
    text.align_x = text.align_y = "CENTER"
    text.extrude = 0.1
    ob = s.link(bpy.data.objects.new("Label", text))
    ob.rotation_euler = (1.5708, 0.0, 0.0)


@case("obj_metaball", "objects", "a metaball", clean(quiet=True, pixels=lit_centre))
def obj_metaball(s: Stage) -> None:
    s.base(cube=False)
    mball = bpy.data.metaballs.new("Blob")
    mball.resolution = 0.2
    mball.render_resolution = 0.2
    element = mball.elements.new()
    element.radius = 1.5
    s.link(bpy.data.objects.new("Blob", mball))


def _mesh_to_points(nodes: Any, links: Any, geometry: Any) -> Any:
    points = nodes.new("GeometryNodeMeshToPoints")
    links.new(geometry, points.inputs["Mesh"])
    return points.outputs["Points"]


@case("obj_point_cloud", "objects",
      "a point cloud (Geometry Nodes Mesh to Points): was 'mesh has no faces'",
      warning("Dots", words=("point",), same_as=lambda s: s.base()))
def obj_point_cloud(s: Stage) -> None:
    s.base()
    ob = s.mesh("Dots", location=(0.0, -2.0, 0.0), scale=(0.5, 0.5, 0.5))
    s.geometry_nodes(ob, "ToPoints", _mesh_to_points)


@case("obj_volume", "objects", "a Volume object (vanished silently)",
      warning("Fog", words=("volume",), same_as=lambda s: s.base()))
def obj_volume(s: Stage) -> None:
    s.base()
    s.link(bpy.data.objects.new("Fog", bpy.data.volumes.new("Fog")))


@case("obj_hair_particles", "objects", "a cube with a hair particle system (hair vanished)",
      warning("Furry", words=("hair", "particle")))
def obj_hair_particles(s: Stage) -> None:
    s.base(cube=False)
    ob = s.mesh("Furry")
    ob.modifiers.new("Hair", "PARTICLE_SYSTEM")
    settings = ob.particle_systems[0].settings
    settings.type = "HAIR"
    settings.count = 50
    settings.hair_length = 0.5


@case("obj_curves_hair", "objects", "a hair Curves object (points where the API can add them)",
      warning("Strands", words=("hair", "curves")))
def obj_curves_hair(s: Stage) -> None:
    s.base()
    curves = bpy.data.hair_curves.new("Strands")
    if hasattr(curves, "add_curves"):  # 4.x+; 3.4 has no API to add points
        curves.add_curves([4] * 8)
    s.link(bpy.data.objects.new("Strands", curves))


def _fluid_domain(s: Stage, domain: bool) -> None:
    """A smoke domain box around the base cube and the lamp: drawn as a surface it hides both.
    (The reference scene has no domain.)"""
    s.base()
    if not domain:
        return
    ob = s.mesh("SmokeDomain", scale=(4.0, 4.0, 4.0))
    modifier = ob.modifiers.new("Fluid", "FLUID")
    modifier.fluid_type = "DOMAIN"
    modifier.domain_settings.cache_directory = str(s.tmp / "fluid_cache")


@case("obj_fluid_domain", "objects",
      "a mesh with a Fluid modifier of type Domain (rendered as an opaque box)",
      warning("SmokeDomain", words=("volume", "fluid", "domain", "smoke"),
              same_as=lambda s: _fluid_domain(s, False)))
def obj_fluid_domain(s: Stage) -> None:
    _fluid_domain(s, True)


def _instance_cubes(nodes: Any, links: Any, geometry: Any) -> Any:
    points = nodes.new("GeometryNodeMeshToPoints")
    links.new(geometry, points.inputs["Mesh"])
    cube = nodes.new("GeometryNodeMeshCube")
    cube.inputs["Size"].default_value = (0.4, 0.4, 0.4)
    on_points = nodes.new("GeometryNodeInstanceOnPoints")
    links.new(points.outputs["Points"], on_points.inputs["Points"])
    links.new(cube.outputs["Mesh"], on_points.inputs["Instance"])
    return on_points.outputs["Instances"]


@case("obj_geometry_nodes_instances", "objects",
      "Geometry Nodes: a cube instanced on the 8 vertices of the base cube",
      clean(quiet=True, pixels=lit_centre))
def obj_geometry_nodes_instances(s: Stage) -> None:
    s.base(cube=False)
    s.geometry_nodes(s.mesh("Corners"), "Corners", _instance_cubes)


def _collection_instancer(s: Stage, scale: float) -> None:
    s.base()
    collection = bpy.data.collections.new("Parts")
    part = bpy.data.objects.new("Part", s.cube_data("Part", half=0.5))
    collection.objects.link(part)
    empty = s.link(bpy.data.objects.new("PartsInstancer", None))
    empty.instance_type = "COLLECTION"
    empty.instance_collection = collection
    empty.location = (0.0, -2.0, 0.0)
    empty.scale = (scale, scale, scale)


@case("obj_collection_instance", "objects", "an empty instancing a collection",
      clean(quiet=True, pixels=lit_centre))
def obj_collection_instance(s: Stage) -> None:
    _collection_instancer(s, 1.0)


@case("obj_collection_instance_zero_scale", "objects",
      "a collection instanced by an empty scaled 0 (a degenerate instance of its mesh)",
      clean(same_as=lambda s: s.base()))
def obj_collection_instance_zero_scale(s: Stage) -> None:
    _collection_instancer(s, 0.0)


@case("obj_many_instancers_zero_scale", "objects",
      "the same collection instanced twice, once scaled 0: the mesh is a real Embree instance",
      warning("'Part'|FlatInstancer", same_as=lambda s: _collection_instancer(s, 1.0)))
def obj_many_instancers_zero_scale(s: Stage) -> None:
    _collection_instancer(s, 1.0)
    second = s.link(bpy.data.objects.new("FlatInstancer", None))
    second.instance_type = "COLLECTION"
    second.instance_collection = bpy.data.collections["Parts"]
    second.location = (0.0, -2.0, 1.5)
    second.scale = (0.0, 0.0, 0.0)
