"""Blender materials -> native materials (one id per distinct Blender material).

The node walk is stratum.shaders.surface (pure Python, unit-tested without Blender); this module
feeds it the active Material Output's Surface input, then sends the closures, the images and
their bindings to the native scene. A material of one closure with weight 1 is added with
stratum_scene_add_material, any other with stratum_scene_add_closure_material: the same thing
to the renderer.

Each native material remembers what it was made from (SentMaterial), so that a later change of
the Blender material can be sent as a live edit (MaterialTable.change): its closures can be
replaced in place; its texture bindings and the UV layer they read cannot (they are part of the
native scene's structure, and decide which arrays its meshes hold), so a change of those needs a
full export.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace
from functools import partial
from typing import Any

import bpy

from .. import blender_versions, native
from ..shaders.fallbacks import UNIT, clamp_rgb
from ..shaders.records import DEFAULT_GREY, Closure, Rgb
from ..shaders.surface import flatten_surface
from .common import (
    ExportError,
    ExportSummary,
    FullExportNeeded,
    active_output,
    linked_from,
    named_edit,
    rgb,
    uses_nodes,
)
from .images import TextureTable


@dataclass
class ConvertedMaterial:
    closures: list[Closure]
    uv_map: str = ""  # UV layer its textures read ("" = the mesh's active render layer)
    warnings: list[str] = field(default_factory=list)  # each names the material and node
    pass_index: int = 0  # Material > Settings > Pass Index (the IndexMA pass)
    # The node program its closures' ProgramInputs read, and the Image Texture nodes that
    # program reads (its IMAGE nodes' mode 0 indexes them); None without one.
    program: native.ShaderProgram | None = None
    program_images: list[Any] = field(default_factory=list)
    # Its program's Tangent nodes in UV-map mode: node name -> UV map named ("" the active
    # render map); its meshes then carry MikkTSpace tangents.
    uv_tangent_maps: dict[str, str] = field(default_factory=dict)


def _single(material: native.Material) -> list[Closure]:
    return [Closure((1.0, 1.0, 1.0), material)]


class AttributeSlots:
    """The mesh-attribute slots of an export: each distinct attribute name the materials' nodes
    read gets the next of native.ATTRIBUTE_SLOTS (in order of first use); meshes then carry the
    attributes of every named slot."""

    def __init__(self) -> None:
        self.names: dict[str, int] = {}

    def slot(self, name: str) -> int | None:
        found = self.names.get(name)
        if found is None and len(self.names) < native.ATTRIBUTE_SLOTS:
            found = self.names[name] = len(self.names)
        return found


def convert_material(material: Any | None,
                     attributes: AttributeSlots | None = None) -> ConvertedMaterial:
    """Closures of a Blender material (None: the default grey diffuse)."""
    if material is None:
        return ConvertedMaterial(_single(native.Material(model=native.closure_model("diffuse"),
                                                         base_color=DEFAULT_GREY)))
    if not uses_nodes(material):
        color, problem = clamp_rgb(rgb(material.diffuse_color), UNIT)
        return ConvertedMaterial(
            _single(native.Material(model=native.closure_model("diffuse"), base_color=color)),
            warnings=[f"Material '{material.name}': 'Color' {problem}"] if problem else [])
    output = active_output(material.node_tree, "ShaderNodeOutputMaterial")
    surface = output.inputs.get("Surface") if output is not None else None
    volume = output.inputs.get("Volume") if output is not None else None
    has_volume = volume is not None and linked_from(volume) is not None
    volume_warning = (f"Material '{material.name}': its Volume shader is not rendered "
                      "(Stratum renders surfaces only)")
    if has_volume and (surface is None or linked_from(surface) is None):
        # Cycles makes the surface of a volume-only material a transparent boundary
        # (scene/shader.cpp: SD_HAS_ONLY_VOLUME, "we can assume transparent surface").
        return ConvertedMaterial(
            _single(native.Material(model=native.closure_model("transparent"),
                                    base_color=(1.0, 1.0, 1.0))),
            warnings=[volume_warning + "; its surface is transparent, as in Cycles"])
    if surface is None or linked_from(surface) is None:
        # Cycles renders a Material Output with nothing connected black (and opaque): a lit
        # plane gives 0.0 in 3.4. Rendered the same, and said.
        return ConvertedMaterial(
            _single(native.Material(model=native.closure_model("diffuse"),
                                    base_color=(0.0, 0.0, 0.0))),
            warnings=[f"Material '{material.name}': no shader connected to the Material Output "
                      "(rendered black, as Cycles does)"])
    warnings: list[str] = []

    def warn(node: Any, message: str) -> None:
        warnings.append(f"Material '{material.name}': {message}")

    flat = flatten_surface(surface, tuple(bpy.app.version), warn,
                           attributes.slot if attributes is not None else None)
    if has_volume:
        warnings.append(volume_warning)
    closures = flat.closures
    if not closures:
        # Every closure had weight 0: Cycles shades the surface black (and opaque).
        closures = _single(native.Material(model=native.closure_model("diffuse"),
                                           base_color=(0.0, 0.0, 0.0)))
    return ConvertedMaterial(closures, flat.uv_map, warnings, program=flat.program,
                             program_images=flat.program_images,
                             uv_tangent_maps=flat.uv_tangent_maps)


def bump_shadowing_model(material: Any | None, version: tuple[int, ...]) -> int:
    """The shadowing term Cycles of this Blender gives closures whose normal differs from the
    smooth one (kernel/closure/bsdf.h bump_shadowing_term): Chiang et al. 2019 up to 4.4, Conty
    Estevez et al. 2019 from 4.5; from 4.2 the material's Bump Map Correction (default on)
    keeps or drops the smoothing."""
    cycles = getattr(material, "cycles", None) if material is not None else None
    smoothed = bool(getattr(cycles, "use_bump_map_correction", True))
    if not blender_versions.has_bump_map_correction(version):
        smoothed = True
    if not blender_versions.conty_bump_shadowing(version):
        return native.BUMP_SHADOWING_CHIANG if smoothed else native.BUMP_SHADOWING_CHIANG_UNSMOOTHED
    return native.BUMP_SHADOWING_CONTY if smoothed else native.BUMP_SHADOWING_CONTY_UNSMOOTHED


def with_bump_shadowing(converted: ConvertedMaterial, model: int) -> ConvertedMaterial:
    closures = [replace(c, material=replace(c.material, bump_shadowing=model))
                for c in converted.closures]
    return replace(converted, closures=closures)


@dataclass(frozen=True)
class SentMaterial:
    """What a native material was made from: its weighted closures, and per texture binding
    (closure index, parameter, original image pointer, interpolation, extension, channel,
    scale, offset), the UV layer its textures read, and its pass index."""

    closures: tuple[tuple[Rgb, native.Material], ...]
    textures: tuple[tuple[Any, ...], ...]
    uv_map: str
    pass_index: int = 0
    # Per program binding (closure index, parameter, register), the program's images (original
    # image pointers) and the program itself (ShaderProgram.key()).
    program_inputs: tuple[tuple[int, str, int], ...] = ()
    program_images: tuple[int, ...] = ()
    program: tuple[Any, ...] | None = None
    uv_tangent_maps: tuple[tuple[str, str], ...] = ()  # (Tangent node, UV map named)

    @property
    def images(self) -> frozenset[int]:
        return frozenset(texture[2] for texture in self.textures)


def sent_material(converted: ConvertedMaterial) -> SentMaterial:
    textures = []
    for index, closure in enumerate(converted.closures):
        for b in closure.bindings:
            node = b.image.node
            textures.append((index, b.param, _image_pointer(node), str(node.interpolation),
                             str(node.extension), b.channel, b.scale, b.offset))
    program_inputs = tuple((index, p.param, p.register)
                           for index, closure in enumerate(converted.closures)
                           for p in closure.programs)
    return SentMaterial(tuple((c.weight, c.material) for c in converted.closures),
                        tuple(textures), converted.uv_map, converted.pass_index, program_inputs,
                        tuple(_image_pointer(node) for node in converted.program_images),
                        converted.program.key() if converted.program is not None else None,
                        tuple(sorted(converted.uv_tangent_maps.items())))


def _image_pointer(node: Any) -> int:
    """The original data-block pointer of an Image Texture node's image (0 without one)."""
    image = getattr(node, "image", None)
    original = getattr(image, "original", None) or image
    return original.as_pointer() if original is not None else 0


def _single_closure(closures: list[Closure]) -> native.Material | None:
    """The material of a one-closure material of weight 1 (sent as a plain material), else
    None (sent as a closure material)."""
    if len(closures) == 1 and closures[0].weight == (1.0, 1.0, 1.0):
        return closures[0].material
    return None


class MaterialTable:
    """Assigns native material ids, once per Blender material (plus one default), and the
    textures they bind, once per image. With an `override` (the view layer's material
    override), every slot and the default are that material."""

    def __init__(self, scene: Any, summary: ExportSummary, override: Any | None = None) -> None:
        self._scene = scene
        self._summary = summary
        self._override = override
        self.ids: dict[int, int] = {}  # original material pointer -> native id
        self.sent: dict[int, SentMaterial] = {}  # native id -> what it was made from
        self._default: int | None = None
        self._material_name = ""
        self.textures = TextureTable(scene, self._texture_warning)
        self.uv_maps: dict[int, str] = {}  # material id -> UV layer its textures read
        self.textured: set[int] = set()  # material ids with texture bindings
        self.normal_mapped: set[int] = set()  # material ids with a Normal Map binding
        # Material id -> (material name, Tangent node, UV map named) of its program's Tangent
        # nodes in UV-map mode: its meshes carry MikkTSpace tangents too.
        self.uv_tangents: dict[int, list[tuple[str, str, str]]] = {}
        self.programs: dict[int, int] = {}  # material id -> its native program id
        self.programmed: set[int] = set()  # material ids with a node program
        self.attributes = AttributeSlots()

    def _texture_warning(self, node: Any, message: str) -> None:
        self._summary.warn(f"Material '{self._material_name}': {message}")

    def default_id(self) -> int:
        if self._default is None:
            converted = convert_material(None)
            model = bump_shadowing_model(None, tuple(bpy.app.version))
            self._default = self._add("(default)", with_bump_shadowing(converted, model))
        return self._default

    def id_for(self, material: Any | None) -> int:
        if self._override is not None:
            material = self._override
        if material is None:
            return self.default_id()
        original = getattr(material, "original", material) or material
        key = original.as_pointer()
        found = self.ids.get(key)
        if found is not None:
            return found
        mat_id = self._add(material.name, _converted(material, self._summary, self.attributes))
        self.ids[key] = mat_id
        return mat_id

    def change(self, mat_id: int, material: Any,
               summary: ExportSummary) -> Callable[[], None] | None:
        """The live edit that makes native material `mat_id` the evaluated Blender `material`
        as it is now, or None when that is what it is already. FullExportNeeded when its
        textures or their UV layer changed."""
        converted = _converted(material, summary, self.attributes)
        now = sent_material(converted)
        before = self.sent[mat_id]
        if now.textures != before.textures or now.uv_map != before.uv_map:
            raise FullExportNeeded(f"Material '{material.name}': its image textures changed")
        if (now.program_inputs != before.program_inputs
                or now.program_images != before.program_images
                or (now.program is None) != (before.program is None)):
            raise FullExportNeeded(f"Material '{material.name}': its node program's outputs "
                                   "changed")
        if now.uv_tangent_maps != before.uv_tangent_maps:
            # Which meshes carry tangents (and which UV map's) is decided when they are sent.
            raise FullExportNeeded(f"Material '{material.name}': its UV-map Tangent nodes "
                                   "changed")
        sends: list[Callable[[], None]] = []
        if now.program != before.program and converted.program is not None:
            # The same bindings with other values (a socket value, a node's mode): the program
            # is replaced in place.
            program = self._resolved_program(converted)
            sends.append(partial(self._scene.set_shader_program, self.programs[mat_id], program))
        if now.closures != before.closures:
            single = _single_closure(converted.closures)
            if single is not None:
                sends.append(partial(self._scene.set_material, mat_id, single))
            else:
                sends.append(partial(self._scene.set_closure_material, mat_id,
                                     list(now.closures)))
        if now.pass_index != before.pass_index:
            sends.append(partial(self._scene.set_material_pass_index, mat_id, now.pass_index))
        if not sends:
            return None
        self.sent[mat_id] = now

        def send() -> None:
            for one in sends:
                one()

        return named_edit(f"Material '{material.name}'", send)

    def _resolved_program(self, converted: ConvertedMaterial) -> native.ShaderProgram:
        assert converted.program is not None
        ids = [self.textures.id_for(node) for node in converted.program_images]
        return resolve_images(converted.program, ids)

    def _add(self, name: str, converted: ConvertedMaterial) -> int:
        closures = converted.closures
        self._material_name = name
        single = _single_closure(closures)
        try:
            if single is not None:
                mat_id = self._scene.add_material(single)
            else:
                mat_id = self._scene.add_closure_material(
                    [(c.weight, c.material) for c in closures])
            if converted.pass_index:
                self._scene.set_material_pass_index(mat_id, converted.pass_index)
            for index, closure in enumerate(closures):
                for b in closure.bindings:
                    self._scene.bind_texture(native.TextureBinding(
                        material_id=mat_id, closure_index=index, param=b.param,
                        texture_id=self.textures.id_for(b.image.node), channel=b.channel,
                        scale=b.scale, offset=b.offset))
            if converted.program is not None:
                program_id = self._scene.add_shader_program(self._resolved_program(converted))
                self.programs[mat_id] = program_id
                for index, closure in enumerate(closures):
                    for p in closure.programs:
                        self._scene.bind_program(native.ProgramBinding(
                            mat_id, index, p.param, program_id, p.register))
        except native.StratumError as exc:
            raise ExportError(f"Material '{name}': {exc}") from exc
        self._summary.materials += 1
        self.sent[mat_id] = sent_material(converted)
        self.uv_maps[mat_id] = converted.uv_map
        if any(c.bindings for c in closures):
            self.textured.add(mat_id)
        if converted.program is not None:
            # A node program may read the UV input: the mesh then carries its UVs (a mesh without
            # any reads (0, 0), as Cycles reads a missing UV attribute, without a warning).
            self.programmed.add(mat_id)
        if any(b.param == native.PARAM_NORMAL for c in closures for b in c.bindings):
            self.normal_mapped.add(mat_id)
        if converted.uv_tangent_maps:
            self.uv_tangents[mat_id] = [(name, node, uv_map) for node, uv_map
                                        in sorted(converted.uv_tangent_maps.items())]
        return mat_id


def resolve_images(program: native.ShaderProgram, texture_ids: list[int]) -> native.ShaderProgram:
    """The program with each IMAGE node's mode 0 (an index into the compiler's image list)
    replaced by the native texture id of that image."""
    image_type = native.node_type("image")
    nodes = [replace(n, modes=(texture_ids[n.modes[0]], *n.modes[1:]))
             if n.type == image_type else n for n in program.nodes]
    return native.ShaderProgram(nodes, list(program.registers), list(program.data))


def _converted(material: Any, summary: ExportSummary,
               attributes: AttributeSlots) -> ConvertedMaterial:
    """The closures of a Blender material with this Blender's bump shadowing; its warnings go
    to `summary`."""
    converted = with_bump_shadowing(convert_material(material, attributes),
                                    bump_shadowing_model(material, tuple(bpy.app.version)))
    converted.pass_index = int(getattr(material, "pass_index", 0))
    for warning in converted.warnings:
        summary.warn(warning)
    return converted
