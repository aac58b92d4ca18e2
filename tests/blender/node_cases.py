"""The node configurations of test_node_agreement.py: one description for every Blender
(`cases()` keeps the ones the running Blender offers), and the graphs that feed each one.

A case is one node (bl_idname) in one mode (its enum/bool properties), its inputs given as
constants or as *sources* (below), and the output that drives the tile's Emission: a float
output drives Strength (Color white), a colour or vector output drives Color (Strength 1).
Sources are built from Texture Coordinate, Separate/Combine XYZ and Math nodes only (the nodes
of the core, so a case tests its own node, not another family's), all from the pixel-snapped
Generated coordinates

    x, y = (floor(T X) + 0.5) / T, (floor(T Y) + 0.5) / T      (X, Y: Generated, T = 16)

which are the coordinates of the pixel's centre whatever the sample's offset within the pixel:
both renderers then evaluate the node at bit-identical inputs (every step is exact in float:
T and 1/T are powers of two), so a case compares the node's values, not the sample positions.

| source     | value over the tile                                                               |
|------------|-----------------------------------------------------------------------------------|
| p<S>       | a point varying in all three axes: (S x + .13, S y - .29, S (x - y) / 2 + .41)   |
| o          | the object coordinates of the pixel centre: (x - .5, y - .5, 0)                   |
| q4         | (floor(4 x), floor(4 y), .25): integer cells of 4 x 4 pixels                      |
| f:lo:hi    | lo + (hi - lo) (.7313 x + .2687 y)    g:lo:hi  the same with x and y swapped      |
| c:lo:hi    | colour (lo + d x, lo + d y, hi - d (x + y) / 2), d = hi - lo                      |
| n          | unit normal (a, b, sqrt(1 - a^2 - b^2)), a = .6 (x - .5), b = .6 (y - .5)       |

q4 is White Noise's input (a hash of the coordinates' bits): integers are the same bits even if
one renderer fused a multiply-add that the other rounded twice. Cases of the nodes that read
the shading point themselves (Texture Coordinate, Geometry, Object Info, Camera Data,
Wireframe, Tangent: RAW_NODES) are not snapped (Case.snapped is False) and compared with the
sample-position term of the tolerance.

Which cases a Blender has is asked of that Blender, not of its version number (offered()): its
node type, and every enum value the case sets (an operation, a blend type) among the
property's items. A case of a node's older form (Noise before its noise_type) names the
property whose absence it is about (Case.without). Where a Blender offers the same case but
Cycles evaluates it differently, the case asks stratum.blender_versions, as the exporter does.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import bpy
from stratum import blender_versions

Spec = float | tuple | str
RAW_NODES = ("ShaderNodeTexCoord", "ShaderNodeNewGeometry", "ShaderNodeObjectInfo",
             "ShaderNodeCameraData", "ShaderNodeWireframe", "ShaderNodeTangent")
T = 16  # pixels per tile side (test_node_agreement.T)


@dataclass(frozen=True)
class Case:
    name: str  # unique; also the tile's material name
    node: str  # bl_idname of the node under test ('' for a custom graph)
    props: dict[str, Any] = field(default_factory=dict)
    inputs: dict[str, Spec] = field(default_factory=dict)  # by socket identifier
    out: str = ""  # output identifier ('' = the first)
    without: str = ""  # a property of the node whose absence the case is about (module doc)
    rel: float = 1e-3  # relative tolerance (Cycles' float approximations would raise it)
    warns: bool = False  # an unsupported mode: the export must warn about this material
    compare: bool = True  # compared with Cycles pixel by pixel
    setup: Callable[[Any], None] | None = None  # sets ramps, curves...
    graph: Callable[[Graph], Any] | None = None  # builds the whole graph; returns the output
    shape: str = ""  # the tile's mesh: "" the flat fan, "tilted", "dome" (test_node_agreement)
    lit: bool = False  # a point lamp over the tile (for a graph that is not an Emission)

    @property
    def snapped(self) -> bool:
        """Whether the node reads only pixel-snapped sources (module docstring)."""
        return self.node not in RAW_NODES

    def mode(self) -> str:
        return " ".join(f"{k}={v}" for k, v in self.props.items()) or "-"


# ---- graph building ---------------------------------------------------------------------------


def socket(sockets: Any, key: str) -> Any:
    for s in sockets:
        if s.identifier == key:
            return s
    for s in sockets:
        if s.name == key:
            return s
    raise KeyError(f"no socket '{key}' in {[s.identifier for s in sockets]}")


class Graph:
    """The node tree of one tile's material, with the sources of the module docstring."""

    def __init__(self, tree: Any) -> None:
        self.tree = tree
        self.nodes, self.links = tree.nodes, tree.links
        self._texco: Any = None
        self._xy: tuple[Any, Any] | None = None

    def new(self, bl_idname: str, **props: Any) -> Any:
        node = self.nodes.new(bl_idname)
        for key, value in props.items():
            setattr(node, key, value)
        return node

    def link(self, src: Any, dst: Any) -> None:
        self.links.new(src, dst)

    def texco(self, out: str) -> Any:
        if self._texco is None:
            self._texco = self.new("ShaderNodeTexCoord")
        return socket(self._texco.outputs, out)

    def xy(self) -> tuple[Any, Any]:
        """The pixel-snapped Generated X and Y (module docstring)."""
        if self._xy is None:
            sep = self.new("ShaderNodeSeparateXYZ")
            self.link(self.texco("Generated"), sep.inputs[0])
            self._xy = tuple(
                self.math("MULTIPLY_ADD", self.math("FLOOR", self.math("MULTIPLY", a, float(T))),
                          1.0 / T, 0.5 / T) for a in (sep.outputs[0], sep.outputs[1]))
        return self._xy

    def math(self, op: str, *args: Any) -> Any:
        node = self.new("ShaderNodeMath", operation=op)
        for i, a in enumerate(args):
            if isinstance(a, int | float):
                node.inputs[i].default_value = float(a)
            else:
                self.link(a, node.inputs[i])
        return node.outputs[0]

    def combine(self, x: Any, y: Any, z: Any) -> Any:
        node = self.new("ShaderNodeCombineXYZ")
        for i, a in enumerate((x, y, z)):
            if isinstance(a, int | float):
                node.inputs[i].default_value = float(a)
            else:
                self.link(a, node.inputs[i])
        return node.outputs[0]

    def source(self, spec: str) -> Any:
        x, y = self.xy()
        if spec == "o":
            return self.combine(self.math("ADD", x, -0.5), self.math("ADD", y, -0.5), 0.0)
        if spec.startswith("p"):
            s = float(spec[1:])
            return self.combine(self.math("MULTIPLY_ADD", x, s, 0.13),
                                self.math("MULTIPLY_ADD", y, s, -0.29),
                                self.math("MULTIPLY_ADD", self.math("SUBTRACT", x, y), s / 2,
                                          0.41))
        if spec == "q4":
            return self.combine(*(self.math("FLOOR", self.math("MULTIPLY", a, 4.0))
                                  for a in (x, y)), 0.25)
        if spec[:2] in ("f:", "g:"):
            lo, hi = (float(v) for v in spec[2:].split(":"))
            a, b = (x, y) if spec[0] == "f" else (y, x)
            d = hi - lo
            return self.math("MULTIPLY_ADD", b, 0.2687 * d,
                             self.math("MULTIPLY_ADD", a, 0.7313 * d, lo))
        if spec.startswith("c:"):
            lo, hi = (float(v) for v in spec[2:].split(":"))
            d = hi - lo
            return self.combine(self.math("MULTIPLY_ADD", x, d, lo),
                                self.math("MULTIPLY_ADD", y, d, lo),
                                self.math("MULTIPLY_ADD", self.math("ADD", x, y), -d / 2, hi))
        if spec == "n":
            a = self.math("MULTIPLY_ADD", x, 0.6, -0.3)
            b = self.math("MULTIPLY_ADD", y, 0.6, -0.3)
            r2 = self.math("ADD", self.math("MULTIPLY", a, a), self.math("MULTIPLY", b, b))
            return self.combine(a, b, self.math("SQRT", self.math("SUBTRACT", 1.0, r2)))
        raise ValueError(f"unknown source '{spec}'")

    def feed(self, dst: Any, spec: Spec) -> None:
        if isinstance(spec, str):
            self.link(self.source(spec), dst)
        elif isinstance(spec, tuple) and len(dst.default_value) == 4 and len(spec) == 3:
            dst.default_value = (*spec, 1.0)
        else:
            dst.default_value = spec

    def node_case(self, case: Case) -> Any:
        node = self.new(case.node, **case.props)
        if case.setup is not None:
            case.setup(node)
        for key, spec in case.inputs.items():
            self.feed(socket(node.inputs, key), spec)
        return socket(node.outputs, case.out) if case.out else node.outputs[0]


def build_material(case: Case) -> Any:
    """The tile's material: Emission driven by the case's output (None output: nothing is
    connected to the Material Output)."""
    mat = bpy.data.materials.new(case.name)
    mat.use_nodes = True
    tree = mat.node_tree
    for n in list(tree.nodes):
        if n.bl_idname != "ShaderNodeOutputMaterial":
            tree.nodes.remove(n)
    output = tree.nodes["Material Output"]
    g = Graph(tree)
    result = case.graph(g) if case.graph is not None else g.node_case(case)
    if result is None:
        return mat
    emission = g.new("ShaderNodeEmission")
    emission.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    emission.inputs["Strength"].default_value = 1.0
    g.link(emission.outputs[0], output.inputs["Surface"])
    if result.type in ("VALUE", "INT", "BOOLEAN"):
        g.link(result, emission.inputs["Strength"])
    else:
        g.link(result, emission.inputs["Color"])
    return mat


# ---- graphs that are not one node -------------------------------------------------------------


def _group(name: str, inner: Callable[[Graph, Any], Any]) -> Any:
    """A node group with one float input and one float output; inner(graph, group input
    socket) returns the socket that feeds the output."""
    group = bpy.data.node_groups.new(name, "ShaderNodeTree")
    if hasattr(group, "interface"):  # 4.x/5.0
        group.interface.new_socket("In", in_out="INPUT", socket_type="NodeSocketFloat")
        group.interface.new_socket("Out", in_out="OUTPUT", socket_type="NodeSocketFloat")
    else:
        group.inputs.new("NodeSocketFloat", "In")
        group.outputs.new("NodeSocketFloat", "Out")
    g = Graph(group)
    gin, gout = g.new("NodeGroupInput"), g.new("NodeGroupOutput")
    g.link(inner(g, gin.outputs[0]), gout.inputs[0])
    return group


def _group_math(g: Graph) -> Any:
    group = _group("harness_math", lambda h, v: h.math("MULTIPLY_ADD", v, 2.5, -0.7))
    node = g.new("ShaderNodeGroup")
    node.node_tree = group
    g.link(g.source("f:-1:2"), node.inputs[0])
    return node.outputs[0]


def _group_nested(g: Graph) -> Any:
    inner = bpy.data.node_groups.get("harness_math") or _group(
        "harness_math", lambda h, v: h.math("MULTIPLY_ADD", v, 2.5, -0.7))

    def outer_body(h: Graph, v: Any) -> Any:
        node = h.new("ShaderNodeGroup")
        node.node_tree = inner
        h.link(h.math("SINE", v), node.inputs[0])
        return h.math("POWER", node.outputs[0], 2.0)

    outer = _group("harness_outer", outer_body)
    node = g.new("ShaderNodeGroup")
    node.node_tree = outer
    g.link(g.source("f:-1:2"), node.inputs[0])
    return node.outputs[0]


def _reroutes(g: Graph) -> Any:
    first, second = g.new("NodeReroute"), g.new("NodeReroute")
    g.link(g.source("c:-0.2:1.3"), first.inputs[0])
    g.link(first.outputs[0], second.inputs[0])
    return second.outputs[0]


def _muted(g: Graph) -> Any:
    node = g.new("ShaderNodeMath", operation="SINE")
    node.mute = True  # passes its first input through
    g.link(g.source("f:-2:3"), node.inputs[0])
    return node.outputs[0]


def _empty(g: Graph) -> None:
    return None


def _script(g: Graph, output: str) -> Any:
    """A Script node (as one whose OSL script declared an input In and an output of type
    `output`, its sockets made as Blender's script update makes them)."""
    script = g.new("ShaderNodeScript")
    script.inputs.new("NodeSocketFloat", "In").default_value = 2.0
    return script.outputs.new(output, "Out")


def _script_value(g: Graph) -> Any:
    """Script output 0.3 into a Math node's first input (its own value 0.6), plus 0.25."""
    out = _script(g, "NodeSocketFloat")
    out.default_value = 0.3
    add = g.new("ShaderNodeMath", operation="ADD")
    add.inputs[0].default_value = 0.6
    add.inputs[1].default_value = 0.25
    g.link(out, add.inputs[0])
    return add.outputs[0]


def _script_shader(g: Graph) -> None:
    """A Script's closure output on the Material Output's Surface."""
    g.link(_script(g, "NodeSocketShader"), g.nodes["Material Output"].inputs["Surface"])


def _wireframe_in_bump(g: Graph) -> Any:
    """A Bump whose Height is a Wireframe's Fac; its normal drives the colour."""
    wire = g.new("ShaderNodeWireframe")
    wire.inputs[0].default_value = 0.1
    bump = g.new("ShaderNodeBump")
    g.link(wire.outputs[0], socket(bump.inputs, "Height"))
    return bump.outputs[0]


# ---- the description --------------------------------------------------------------------------


def _ramp(interpolation: str, color_mode: str = "RGB",
          hue: str = "NEAR") -> Callable[[Any], None]:
    def setup(node: Any) -> None:
        ramp = node.color_ramp
        ramp.interpolation, ramp.color_mode, ramp.hue_interpolation = (
            interpolation, color_mode, hue)
        e = ramp.elements
        e[0].position, e[0].color = 0.1, (0.9, 0.1, 0.05, 1.0)
        e[1].position, e[1].color = 0.8, (0.1, 0.2, 0.95, 0.3)
        mid = e.new(0.45)
        mid.color = (0.2, 0.85, 0.3, 0.7)
    return setup


def _curves(extend: str) -> Callable[[Any], None]:
    def setup(node: Any) -> None:
        m = node.mapping
        m.extend = extend
        m.curves[3].points.new(0.35, 0.6)  # combined
        m.curves[0].points.new(0.5, 0.25)  # red
        m.curves[2].points[1].location = (1.0, 0.7)  # blue end
        m.update()
    return setup


MATH_OPS = ("ADD", "SUBTRACT", "MULTIPLY", "DIVIDE", "MULTIPLY_ADD", "POWER", "LOGARITHM", "SQRT",
            "INVERSE_SQRT", "ABSOLUTE", "EXPONENT", "MINIMUM", "MAXIMUM", "LESS_THAN",
            "GREATER_THAN", "SIGN", "COMPARE", "SMOOTH_MIN", "SMOOTH_MAX", "ROUND", "FLOOR",
            "CEIL", "TRUNC", "FRACT", "MODULO", "WRAP", "SNAP", "PINGPONG", "SINE", "COSINE",
            "TANGENT", "ARCSINE", "ARCCOSINE", "ARCTANGENT", "ARCTAN2", "SINH", "COSH", "TANH",
            "RADIANS", "DEGREES")
VMATH_OPS = ("ADD", "SUBTRACT", "MULTIPLY", "DIVIDE", "MULTIPLY_ADD", "CROSS_PRODUCT", "PROJECT",
             "REFLECT", "REFRACT", "FACEFORWARD", "DOT_PRODUCT", "DISTANCE", "LENGTH", "SCALE",
             "NORMALIZE", "ABSOLUTE", "MINIMUM", "MAXIMUM", "FLOOR", "CEIL", "FRACTION", "MODULO",
             "WRAP", "SNAP", "SINE", "COSINE", "TANGENT")
BLENDS = ("MIX", "DARKEN", "MULTIPLY", "BURN", "LIGHTEN", "SCREEN", "DODGE", "ADD", "OVERLAY",
          "SOFT_LIGHT", "LINEAR_LIGHT", "DIFFERENCE", "SUBTRACT", "DIVIDE", "HUE", "SATURATION",
          "COLOR", "VALUE")
# Math ops with a pole or a log singularity at a first operand of 0 (+ a non-integer power of
# a negative base): compared on positive first operands, and on negative ones separately.
POSITIVE_ONLY = ("POWER", "LOGARITHM", "INVERSE_SQRT")
DIMS = ("1D", "2D", "3D", "4D")
FRACTALS = ("MULTIFRACTAL", "RIDGED_MULTIFRACTAL", "HYBRID_MULTIFRACTAL", "FBM", "HETERO_TERRAIN")
METRICS = ("EUCLIDEAN", "MANHATTAN", "CHEBYCHEV", "MINKOWSKI")


def _describe() -> list[Case]:
    c: list[Case] = []
    add = c.append
    # Inputs and coordinates.
    for out in ("Generated", "Normal", "UV", "Object", "Camera", "Reflection"):
        add(Case(f"texcoord-{out}", "ShaderNodeTexCoord", out=out))
    add(Case("texcoord-Window", "ShaderNodeTexCoord", out="Window", warns=True, compare=False))
    for vt in ("POINT", "TEXTURE", "VECTOR", "NORMAL"):
        add(Case(f"mapping-{vt}", "ShaderNodeMapping", {"vector_type": vt},
                 {"Vector": "p1", "Location": (0.3, -0.2, 0.5), "Rotation": (0.5, -0.3, 0.8),
                  "Scale": (1.5, 0.7, -2.0)}))
    for out in ("Position", "Normal", "Tangent", "True Normal", "Incoming", "Parametric",
                "Backfacing"):
        add(Case(f"geometry-{out}", "ShaderNodeNewGeometry", out=out))
    for out in ("Pointiness", "Random Per Island"):
        add(Case(f"geometry-{out}", "ShaderNodeNewGeometry", out=out, warns=True,
                 compare=False))
    for out in ("Location", "Color", "Alpha", "Object Index", "Material Index", "Random"):
        add(Case(f"objectinfo-{out}", "ShaderNodeObjectInfo", out=out))
    add(Case("value", "ShaderNodeValue", setup=lambda n: setattr(n.outputs[0], "default_value",
                                                                 -1.75)))
    add(Case("rgb", "ShaderNodeRGB", setup=lambda n: setattr(n.outputs[0], "default_value",
                                                             (0.2, 0.45, 0.9, 1.0))))
    add(Case("ao-unsupported", "ShaderNodeAmbientOcclusion", warns=True, compare=False))
    # Textures.
    for dims in DIMS:
        for detail, name in ((0.0, "plain"), (3.5, "rich")):
            common = {"Vector": "p1", "W": "f:0.2:1.7", "Scale": 2.5, "Detail": detail,
                      "Roughness": 0.6, "Distortion": 0.4 if detail else 0.0}
            add(Case(f"noise34-{dims}-{name}", "ShaderNodeTexNoise",
                     {"noise_dimensions": dims}, common, without="noise_type"))
            for ntype in FRACTALS:
                if name == "plain" and ntype != "FBM":
                    continue
                for normalize in (True, False) if ntype == "FBM" else (True,):
                    add(Case(f"noise-{ntype}-{dims}-{name}-n{int(normalize)}",
                             "ShaderNodeTexNoise",
                             {"noise_dimensions": dims, "noise_type": ntype,
                              "normalize": normalize},
                             {**common, "Lacunarity": 2.2, "Offset": 0.3, "Gain": 1.2}))
        for mtype in FRACTALS:
            add(Case(f"musgrave-{mtype}-{dims}", "ShaderNodeTexMusgrave",
                     {"musgrave_dimensions": dims, "musgrave_type": mtype},
                     {"Vector": "p1", "W": "f:0.2:1.7", "Scale": 2.5, "Detail": 3.5,
                      "Dimension": 1.3, "Lacunarity": 2.2, "Offset": 0.6, "Gain": 1.1}))
    add(Case("noise34-3D-color", "ShaderNodeTexNoise", {"noise_dimensions": "3D"},
             {"Vector": "p1", "Scale": 2.5, "Detail": 2.0, "Distortion": 0.3}, out="Color",
             without="noise_type"))
    add(Case("noise-FBM-3D-color", "ShaderNodeTexNoise",
             {"noise_dimensions": "3D", "noise_type": "FBM"},
             {"Vector": "p1", "Scale": 2.5, "Detail": 2.0, "Distortion": 0.3}, out="Color"))
    vor = {"Vector": "p1", "W": "f:0.2:1.7", "Scale": 3.0, "Smoothness": 0.6, "Exponent": 1.5,
           "Randomness": 0.8}
    for dims in DIMS:
        for feature in ("F1", "F2", "SMOOTH_F1", "DISTANCE_TO_EDGE", "N_SPHERE_RADIUS"):
            metrics = METRICS if dims != "1D" and feature in ("F1", "F2", "SMOOTH_F1") else \
                ("EUCLIDEAN",)
            for metric in metrics:
                add(Case(f"voronoi-{feature}-{metric}-{dims}", "ShaderNodeTexVoronoi",
                         {"voronoi_dimensions": dims, "feature": feature, "distance": metric},
                         vor, out="Radius" if feature == "N_SPHERE_RADIUS" else "Distance"))
    for out in ("Color", "Position"):
        add(Case(f"voronoi-F1-3D-{out}", "ShaderNodeTexVoronoi",
                 {"voronoi_dimensions": "3D", "feature": "F1"}, vor, out=out))
    add(Case("voronoi-F1-4D-W", "ShaderNodeTexVoronoi",
             {"voronoi_dimensions": "4D", "feature": "F1"}, vor, out="W"))
    for feature in ("F1", "F2", "SMOOTH_F1", "DISTANCE_TO_EDGE"):
        for normalize in (True, False):
            add(Case(f"voronoi-detail-{feature}-n{int(normalize)}", "ShaderNodeTexVoronoi",
                     {"voronoi_dimensions": "3D", "feature": feature, "normalize": normalize},
                     {**vor, "Detail": 2.5, "Roughness": 0.6, "Lacunarity": 2.2}))
    for wtype, dirs in (("BANDS", ("X", "Y", "Z", "DIAGONAL")),
                        ("RINGS", ("X", "Y", "Z", "SPHERICAL"))):
        for direction in dirs:
            for profile in ("SIN", "SAW", "TRI"):
                key = "bands_direction" if wtype == "BANDS" else "rings_direction"
                add(Case(f"wave-{wtype}-{direction}-{profile}", "ShaderNodeTexWave",
                         {"wave_type": wtype, key: direction, "wave_profile": profile},
                         {"Vector": "p1", "Scale": 2.0, "Distortion": 2.0, "Detail": 2.0,
                          "Detail Scale": 1.5, "Detail Roughness": 0.6, "Phase Offset": 0.4},
                         out="Fac"))
    add(Case("wave-color", "ShaderNodeTexWave", {"wave_type": "BANDS"},
             {"Vector": "p1", "Scale": 2.0, "Distortion": 1.0}, out="Color"))
    for out in ("Color", "Fac"):
        add(Case(f"checker-{out}", "ShaderNodeTexChecker", {},
                 {"Vector": "p1", "Color1": (0.9, 0.3, 0.1), "Color2": "c:0:1", "Scale": 3.0},
                 out=out))
        add(Case(f"brick-{out}", "ShaderNodeTexBrick",
                 {"offset": 0.3, "offset_frequency": 3, "squash": 1.4, "squash_frequency": 2},
                 {"Vector": "p1", "Color1": (0.8, 0.2, 0.1), "Color2": (0.2, 0.6, 0.9),
                  "Mortar": "c:0:1", "Scale": 4.0, "Mortar Size": 0.04, "Mortar Smooth": 0.3,
                  "Bias": 0.3, "Brick Width": 0.6, "Row Height": 0.3}, out=out))
    for gtype in ("LINEAR", "QUADRATIC", "EASING", "DIAGONAL", "SPHERICAL", "QUADRATIC_SPHERE",
                  "RADIAL"):
        add(Case(f"gradient-{gtype}", "ShaderNodeTexGradient", {"gradient_type": gtype},
                 {"Vector": "o"}, out="Fac"))
    add(Case("gradient-color", "ShaderNodeTexGradient", {"gradient_type": "RADIAL"},
             {"Vector": "o"}, out="Color"))
    for depth in range(11):
        add(Case(f"magic-{depth}", "ShaderNodeTexMagic", {"turbulence_depth": depth},
                 {"Vector": "p1", "Scale": 2.0, "Distortion": 1.5}, out="Color"))
    add(Case("magic-fac", "ShaderNodeTexMagic", {"turbulence_depth": 3},
             {"Vector": "p1", "Scale": 2.0, "Distortion": 1.5}, out="Fac"))
    for dims in DIMS:
        for out in ("Value", "Color"):
            add(Case(f"whitenoise-{dims}-{out}", "ShaderNodeTexWhiteNoise",
                     {"noise_dimensions": dims}, {"Vector": "q4", "W": 1.25}, out=out))
    # Colour.
    for interp in ("EASE", "CARDINAL", "LINEAR", "B_SPLINE", "CONSTANT"):
        add(Case(f"colorramp-{interp}", "ShaderNodeValToRGB", {}, {"Fac": "f:-0.2:1.2"},
                 setup=_ramp(interp)))
    for mode in ("HSV", "HSL"):
        for hue in ("NEAR", "FAR", "CW", "CCW"):
            add(Case(f"colorramp-{mode}-{hue}", "ShaderNodeValToRGB", {}, {"Fac": "f:-0.2:1.2"},
                     setup=_ramp("LINEAR", mode, hue)))
    add(Case("colorramp-alpha", "ShaderNodeValToRGB", {}, {"Fac": "f:-0.2:1.2"}, out="Alpha",
             setup=_ramp("LINEAR")))
    for extend in ("EXTRAPOLATED", "HORIZONTAL"):
        add(Case(f"rgbcurves-{extend}", "ShaderNodeRGBCurve", {},
                 {"Fac": 0.8, "Color": "c:-0.2:1.2"}, setup=_curves(extend)))
    for blend in (*BLENDS, "EXCLUSION"):
        add(Case(f"mix-RGBA-{blend}", "ShaderNodeMix", {"data_type": "RGBA", "blend_type": blend},
                 {"Factor_Float": "g:0:1", "A_Color": "c:0:1", "B_Color": (0.8, 0.3, 0.55)},
                 out="Result_Color"))
        add(Case(f"mixrgb-{blend}", "ShaderNodeMixRGB", {"blend_type": blend},
                 {"Fac": "g:0:1", "Color1": "c:0:1", "Color2": (0.8, 0.3, 0.55)}))
    for blend in ("MIX", "MULTIPLY", "DODGE", "LINEAR_LIGHT"):
        add(Case(f"mix-RGBA-{blend}-clamped", "ShaderNodeMix",
                 {"data_type": "RGBA", "blend_type": blend, "clamp_result": True,
                  "clamp_factor": False},
                 {"Factor_Float": "g:-0.3:1.4", "A_Color": "c:-0.2:1.3",
                  "B_Color": (1.4, 0.3, 0.55)}, out="Result_Color"))
        add(Case(f"mixrgb-{blend}-clamped", "ShaderNodeMixRGB",
                 {"blend_type": blend, "use_clamp": True},
                 {"Fac": "g:0:1", "Color1": "c:-0.2:1.3", "Color2": (1.4, 0.3, 0.55)}))
    for clamp in (True, False):
        add(Case(f"mix-FLOAT-clamp{int(clamp)}", "ShaderNodeMix",
                 {"data_type": "FLOAT", "clamp_factor": clamp},
                 {"Factor_Float": "g:-0.3:1.4", "A_Float": "f:-1:2", "B_Float": 0.7},
                 out="Result_Float"))
    for fmode in ("UNIFORM", "NON_UNIFORM"):
        add(Case(f"mix-VECTOR-{fmode}", "ShaderNodeMix",
                 {"data_type": "VECTOR", "factor_mode": fmode, "clamp_factor": False},
                 {"Factor_Float": "g:-0.3:1.4", "Factor_Vector": "c:-0.2:1.2",
                  "A_Vector": "p1", "B_Vector": (0.5, -1.0, 2.0)}, out="Result_Vector"))
    add(Case("huesat", "ShaderNodeHueSaturation", {},
             {"Hue": 0.3, "Saturation": 1.4, "Value": 0.8, "Fac": 0.9, "Color": "c:0:1"}))
    add(Case("invert", "ShaderNodeInvert", {}, {"Fac": 0.7, "Color": "c:-0.2:1.2"}))
    for gamma in (2.2, 0.45):
        add(Case(f"gamma-{gamma}", "ShaderNodeGamma", {}, {"Color": "c:-0.2:1.2",
                                                            "Gamma": gamma}))
    add(Case("brightcontrast", "ShaderNodeBrightContrast", {},
             {"Color": "c:-0.2:1.2", "Bright": 0.1, "Contrast": 0.4}))
    # Converters.
    for op in (*MATH_OPS, "FLOORED_MODULO"):
        # The second operand of a division-like op stays away from 0 (and a logarithm's base
        # from 1; WRAP's range, max - min, from 0), a logarithm's argument from 0 and tangent's
        # within +-pi/2: near a pole a 1-ulp difference of the input (a multiply-add fused by
        # one renderer and not the other) is amplified without bound. Non-positive arguments of
        # POSITIVE_ONLY have their own cases.
        a = {"ARCSINE": "f:-1.2:1.2", "ARCCOSINE": "f:-1.2:1.2", "TANGENT": "f:-1.4:1.4",
             **dict.fromkeys(POSITIVE_ONLY, "f:0.2:3")}.get(op, "f:-2:3")
        b = {"DIVIDE": "g:0.35:1.45", "MODULO": "g:0.35:1.45", "FLOORED_MODULO": "g:0.35:1.45",
             "WRAP": "g:0.35:1.45", "SNAP": "g:0.35:1.45", "PINGPONG": "g:0.35:1.45",
             "LOGARITHM": "g:1.3:3.1"}.get(op, "g:-1.5:2.5")
        add(Case(f"math-{op}", "ShaderNodeMath", {"operation": op},
                 {"Value": a, "Value_001": b, "Value_002": -0.6 if op == "WRAP" else 0.6}))
    for op, b in (*((op, 2.0) for op in POSITIVE_ONLY), ("POWER", 3.0)):
        add(Case(f"math-{op}-negative-{b}", "ShaderNodeMath", {"operation": op},
                 {"Value": "f:-2:-0.2", "Value_001": b}))
    for op in ("DIVIDE", "MODULO", "LOGARITHM"):  # Cycles' safe_* at an exact 0 operand
        add(Case(f"math-{op}-by-zero", "ShaderNodeMath", {"operation": op},
                 {"Value": "f:-2:3", "Value_001": 0.0}))
    add(Case("math-ADD-clamped", "ShaderNodeMath", {"operation": "ADD", "use_clamp": True},
             {"Value": "f:-2:3", "Value_001": "g:-1.5:2.5"}))
    for op in (*VMATH_OPS, "POWER", "SIGN"):
        out = "Value" if op in ("DOT_PRODUCT", "DISTANCE", "LENGTH") else "Vector"
        add(Case(f"vmath-{op}", "ShaderNodeVectorMath", {"operation": op},
                 {"Vector": "p1", "Vector_001": "c:-1:1.5", "Vector_002": (0.3, -0.6, 0.9),
                  "Scale": 1.7}, out=out))
    for dtype, value, out in (("FLOAT", "Value", "Result"), ("FLOAT_VECTOR", "Vector", "Vector")):
        for interp in ("LINEAR", "STEPPED", "SMOOTHSTEP", "SMOOTHERSTEP"):
            for clamp in (True, False) if interp == "LINEAR" else (True,):
                v = dtype == "FLOAT_VECTOR"
                add(Case(f"maprange-{dtype}-{interp}-clamp{int(clamp)}", "ShaderNodeMapRange",
                         {"data_type": dtype, "interpolation_type": interp, "clamp": clamp},
                         {value: "c:-0.5:1.5" if v else "f:-0.5:1.5",
                          ("From_Min_FLOAT3" if v else "From Min"): (0.1,) * 3 if v else 0.1,
                          ("From_Max_FLOAT3" if v else "From Max"): (0.9, 0.7, 0.8) if v else
                          0.9,
                          ("To_Min_FLOAT3" if v else "To Min"): (-1.0,) * 3 if v else -1.0,
                          ("To_Max_FLOAT3" if v else "To Max"): (2.0, 1.0, 3.0) if v else 2.0,
                          ("Steps_FLOAT3" if v else "Steps"): (4.0, 3.0, 5.0) if v else 4.0},
                         out=out))
    for rtype in ("AXIS_ANGLE", "X_AXIS", "Y_AXIS", "Z_AXIS", "EULER_XYZ"):
        for invert in (False, True) if rtype in ("AXIS_ANGLE", "EULER_XYZ") else (False,):
            add(Case(f"vectorrotate-{rtype}-inv{int(invert)}", "ShaderNodeVectorRotate",
                     {"rotation_type": rtype, "invert": invert},
                     {"Vector": "p1", "Center": (0.2, -0.1, 0.3), "Axis": (0.3, 0.5, 0.8),
                      "Angle": "f:-2:3", "Rotation": (0.4, -0.7, 1.1)}))
    add(Case("rgbtobw", "ShaderNodeRGBToBW", {}, {"Color": "c:-0.2:1.2"}))
    for ctype in ("MINMAX", "RANGE"):
        add(Case(f"clamp-{ctype}", "ShaderNodeClamp", {"clamp_type": ctype},
                 {"Value": "f:-1:2", "Min": 0.8, "Max": 0.2}, out="Result"))
    for out in ("R", "G", "B"):
        add(Case(f"separatergb-{out}", "ShaderNodeSeparateRGB", {}, {"Image": "c:-0.2:1.2"},
                 out=out))
    for out in ("H", "S", "V"):
        add(Case(f"separatehsv-{out}", "ShaderNodeSeparateHSV", {}, {"Color": "c:0:1"},
                 out=out))
    add(Case("combinergb", "ShaderNodeCombineRGB", {},
             {"R": "f:-0.2:1.2", "G": "g:0:1", "B": 0.4}))
    add(Case("combinehsv", "ShaderNodeCombineHSV", {},
             {"H": "f:0:1", "S": "g:0:1", "V": 0.8}))
    for mode in ("RGB", "HSV", "HSL"):
        for out in ("Red", "Green", "Blue"):
            add(Case(f"separatecolor-{mode}-{out}", "ShaderNodeSeparateColor", {"mode": mode},
                     {"Color": "c:0:1"}, out=out))
        add(Case(f"combinecolor-{mode}", "ShaderNodeCombineColor", {"mode": mode},
                 {"Red": "f:0:1", "Green": "g:0:1", "Blue": 0.6}))
    for out in ("X", "Y", "Z"):
        add(Case(f"separatexyz-{out}", "ShaderNodeSeparateXYZ", {}, {"Vector": "p2"}, out=out))
    add(Case("combinexyz", "ShaderNodeCombineXYZ", {}, {"X": "f:-1:2", "Y": "g:0:1", "Z": -0.4}))
    # Shading-dependent inputs (an orthographic view straight down: I = N, so the normal varies).
    add(Case("fresnel", "ShaderNodeFresnel", {}, {"IOR": 1.45, "Normal": "n"}))
    add(Case("fresnel-flat", "ShaderNodeFresnel", {}, {"IOR": 2.2}))
    for out in ("Fresnel", "Facing"):
        add(Case(f"layerweight-{out}", "ShaderNodeLayerWeight", {},
                 {"Blend": 0.3, "Normal": "n"}, out=out))
    # Graph structure.
    add(Case("group-math", "", graph=_group_math))
    add(Case("group-nested", "", graph=_group_nested))
    add(Case("reroutes", "", graph=_reroutes))
    add(Case("muted-math", "", graph=_muted))
    add(Case("empty-output", "", graph=_empty, warns=True))
    # Camera, ray and geometry nodes (issue 33).
    for out in ("View Vector", "View Z Depth", "View Distance"):
        add(Case(f"cameradata-{out.replace(' ', '')}", "ShaderNodeCameraData", out=out))
    # The ray length is the camera ray's, the same over every tile (orthographic view); the
    # strength and smoothing vary.
    for out in ("Quadratic", "Linear", "Constant"):
        for smooth, name in ((0.0, "sharp"), ("g:5:40", "smooth")):
            add(Case(f"lightfalloff-{out}-{name}", "ShaderNodeLightFalloff", {},
                     {"Strength": "f:0.5:3", "Smooth": smooth}, out=out))
    # Half widths (Size / 2, in world units or times the pixel's 1/16) chosen by search so that
    # no pixel centre lies within 0.089 px of a wire's border: the two renderers' samples, at
    # most 0.01 px apart, fall on the same side of it.
    for pixel_size, size in ((False, 0.1), (False, 0.275), (True, 2.8), (True, 1.2)):
        add(Case(f"wireframe-{'pixel' if pixel_size else 'world'}-{size}", "ShaderNodeWireframe",
                 {"use_pixel_size": pixel_size}, {"Size": size}, out="Fac"))
    # Inside a Bump: a difference quotient before 4.4 (warned), the offset points from 4.4. The
    # bumped normal of a step height is not compared (its offsets straddle a wire's border).
    add(Case("wireframe-in-bump", "", graph=_wireframe_in_bump, compare=False,
             warns=not blender_versions.wireframe_at_bump_offsets(bpy.app.version)))
    # Radial tangents on the tilted tile (a flat one's texture space has no depth, where the X
    # and Y axes' tangents lie along the normal), and about Z on the flat fan; UV tangents on
    # the dome, of the one map it has, named or not; another map named: Cycles reads a tangent
    # attribute the mesh lacks (0), Stratum the carried map's, with a warning.
    for axis in ("X", "Y", "Z"):
        add(Case(f"tangent-radial-{axis}", "ShaderNodeTangent",
                 {"direction_type": "RADIAL", "axis": axis}, shape="tilted"))
    add(Case("tangent-radial-Z-flat", "ShaderNodeTangent", {"direction_type": "RADIAL",
                                                            "axis": "Z"}))
    for uv_map in ("", "UVMap"):
        add(Case(f"tangent-uvmap-{uv_map or 'default'}", "ShaderNodeTangent",
                 {"direction_type": "UV_MAP", "uv_map": uv_map}, shape="dome"))
    add(Case("tangent-uvmap-other", "ShaderNodeTangent",
             {"direction_type": "UV_MAP", "uv_map": "Other"}, shape="dome", warns=True,
             compare=False))
    # Script (OSL): Cycles without OSL (its default, and any GPU) makes no node of it, so what it
    # feeds reads as unlinked: the Math node's own 0.6 (+ 0.25), and no surface at all (black,
    # lit by a lamp so that a stand-in closure would show).
    add(Case("script-value", "", graph=_script_value, warns=True))
    add(Case("script-shader", "", graph=_script_shader, warns=True, lit=True))
    return c


EMPTY_OUTPUT = "empty-output"  # the tile lit by a point lamp


def offered(case: Case) -> bool:
    """Whether the running Blender offers the case (module docstring): its node type, each
    enum value it sets among the property's items, and not the property it is `without`."""
    if not case.node:
        return True
    node_type = getattr(bpy.types, case.node, None)
    if node_type is None:
        return False
    properties = node_type.bl_rna.properties
    if case.without and case.without in properties:
        return False
    for key, value in case.props.items():
        prop = properties.get(key)
        if prop is None:
            return False
        if prop.type == "ENUM" and value not in {e.identifier for e in prop.enum_items}:
            return False
    return True


def cases() -> list[Case]:
    """The cases the running Blender offers."""
    chosen = [k for k in _describe() if offered(k)]
    names = [k.name for k in chosen]
    assert len(set(names)) == len(names), "case names must be unique"
    return chosen
