"""The scene every case builds on, made with bpy.data only (no context-dependent operators), so
the same code runs in Blender 3.4 and in the bpy 5.0 wheel; version differences are tested by
feature or by bpy.app.version where the API changed.

The base scene: a camera 6 m in front of a 2 m cube at the origin (the cube fills the middle of
the 16x16 image), a 500 W point light, a dim grey world. One thread, 2 samples, 4 bounces: a case
is about what the renderer survives, not about noise.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

import bpy

CUBE_VERTS = [(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1),
              (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)]
CUBE_FACES = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6),
              (3, 0, 4, 7)]

Vec3 = tuple[float, float, float]


def emission_color_socket() -> str:
    """The Principled BSDF's emission colour input: 'Emission' before 4.0."""
    return "Emission" if bpy.app.version < (4, 0, 0) else "Emission Color"


class Stage:
    """An empty factory scene set up for Stratum; helpers add objects to it. `tmp` is a folder
    of the worker's own for the files a case writes (images, caches)."""

    def __init__(self, tmp: Path) -> None:
        bpy.ops.wm.read_factory_settings(use_empty=True)
        self.tmp = tmp
        self.scene = bpy.context.scene
        self.scene.render.engine = "STRATUM"
        r = self.scene.render
        r.resolution_x, r.resolution_y, r.resolution_percentage = 16, 16, 100
        s = self.scene.stratum
        s.samples, s.max_bounces, s.threads, s.seed = 2, 4, 1, 1

    # ---- objects ----

    def link(self, ob: Any) -> Any:
        self.scene.collection.objects.link(ob)
        return ob

    def camera(self, name: str = "Camera", location: Vec3 = (0.0, -6.0, 0.0)) -> Any:
        cam = bpy.data.objects.new(name, bpy.data.cameras.new(name))
        cam.location = location
        cam.rotation_euler = (math.pi / 2, 0.0, 0.0)  # looks along +Y at the origin
        self.link(cam)
        self.scene.camera = cam
        return cam

    def cube_data(self, name: str = "Cube", half: float = 1.0) -> Any:
        me = bpy.data.meshes.new(name)
        me.from_pydata([tuple(half * c for c in v) for v in CUBE_VERTS], [], CUBE_FACES)
        me.update()
        return me

    def mesh(self, name: str = "Cube", data: Any = None, location: Vec3 = (0.0, 0.0, 0.0),
             scale: Vec3 = (1.0, 1.0, 1.0), material: Any = None) -> Any:
        ob = bpy.data.objects.new(name, data if data is not None else self.cube_data(name))
        ob.location = location
        ob.scale = scale
        if material is not None:
            ob.data.materials.append(material)
        return self.link(ob)

    def light(self, kind: str = "POINT", name: str = "Lamp", energy: float = 500.0,
              location: Vec3 = (0.0, -3.0, 3.0), rotation: Vec3 = (0.0, 0.0, 0.0)) -> Any:
        data = bpy.data.lights.new(name, kind)
        data.energy = energy
        ob = bpy.data.objects.new(name, data)
        ob.location = location
        ob.rotation_euler = rotation
        return self.link(ob)

    def world(self, color: Vec3 = (0.05, 0.05, 0.05), name: str = "World") -> Any:
        world = bpy.data.worlds.new(name)
        world.color = color
        if world.node_tree is None and bpy.app.version < (5, 0, 0):
            world.use_nodes = True
        bg = world.node_tree.nodes.get("Background") if world.node_tree else None
        if bg is not None:
            bg.inputs["Color"].default_value = (*color, 1.0)
            bg.inputs["Strength"].default_value = 1.0
        self.scene.world = world
        return world

    def base(self, cube: bool = True) -> Stage:
        """Camera, the cube 'Cube' (unless cube=False), the point light 'Lamp', a grey world."""
        self.camera()
        if cube:
            self.mesh("Cube")
        self.light()
        self.world()
        return self

    # ---- materials ----

    def material(self, name: str) -> tuple[Any, Any]:
        """A node material and its Principled BSDF."""
        mat = bpy.data.materials.new(name)
        if bpy.app.version < (5, 0, 0):
            mat.use_nodes = True
        return mat, mat.node_tree.nodes["Principled BSDF"]

    def shader_material(self, name: str, shader: str, output: str = "Surface") -> tuple[Any, Any]:
        """A material whose output `output` is fed by one new shader node of type `shader`
        (the default Principled BSDF removed)."""
        mat, principled = self.material(name)
        nt = mat.node_tree
        nt.nodes.remove(principled)
        node = nt.nodes.new(shader)
        out = nt.nodes["Material Output"]
        nt.links.new(node.outputs[0], out.inputs[output])
        return mat, node

    def image_material(self, name: str, image: Any) -> Any:
        mat, principled = self.material(name)
        nt = mat.node_tree
        tex = nt.nodes.new("ShaderNodeTexImage")
        tex.image = image
        nt.links.new(tex.outputs["Color"], principled.inputs["Base Color"])
        return mat

    def textured_cube(self, image: Any, name: str = "Cube") -> Any:
        """The base scene whose cube (with UVs) shows `image` on its faces."""
        self.base(cube=False)
        ob = self.mesh(name, material=self.image_material("Textured", image))
        ob.data.uv_layers.new(name="UVMap")
        return ob

    def file_image(self, name: str, path: Path | str) -> Any:
        """An image datablock pointing at `path` (not loaded by Blender here)."""
        image = bpy.data.images.new(name, 4, 4)
        image.source = "FILE"
        image.filepath = str(path)
        return image

    # ---- geometry nodes ----

    def geometry_nodes(self, ob: Any, name: str,
                       build: Callable[[Any, Any, Any], Any]) -> Any:
        """Gives `ob` a Geometry Nodes modifier whose tree is Group Input -> build -> Group
        Output: build(nodes, links, geometry_in_socket) returns the output geometry socket.
        4.0 replaced NodeTree.inputs/outputs by NodeTree.interface."""
        tree = bpy.data.node_groups.new(name, "GeometryNodeTree")
        if hasattr(tree, "interface"):
            tree.interface.new_socket("Geometry", in_out="INPUT", socket_type="NodeSocketGeometry")
            tree.interface.new_socket("Geometry", in_out="OUTPUT",
                                      socket_type="NodeSocketGeometry")
        else:
            tree.inputs.new("NodeSocketGeometry", "Geometry")
            tree.outputs.new("NodeSocketGeometry", "Geometry")
        group_in = tree.nodes.new("NodeGroupInput")
        group_out = tree.nodes.new("NodeGroupOutput")
        result = build(tree.nodes, tree.links, group_in.outputs[0])
        tree.links.new(result, group_out.inputs[0])
        modifier = ob.modifiers.new(name, "NODES")
        modifier.node_group = tree
        return modifier
