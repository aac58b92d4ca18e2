/* Stratum C ABI, part 5: shader node programs (issue 18).
 *
 * A Blender node graph (a material's, or the world's) is compiled by the host into a program: a
 * straight-line list of nodes over a file of float registers, the shape of Cycles' SVM. Each
 * node reads its inputs from registers and writes its outputs to registers; a vector or colour
 * takes three consecutive registers. The program's registers start as the host gives them (the
 * unlinked sockets' values), except the first STRATUM_SHADER_INPUT_REGISTERS, which the renderer
 * fills at each shading point (the geometry a node can see, below). A node may only read
 * registers: programs have no jumps, so every program ends, and a register read before it is
 * written holds its initial value.
 *
 * Outputs drive closure parameters (stratum_scene_bind_program) or the world's radiance
 * (stratum_scene_set_background_program). The node types and their modes follow Blender's
 * nodes, socket for socket: docs/shader_nodes.md lists each node's registers and modes. Node
 * types have no enumerators here: hosts look each value up by its name in the library's listing
 * (stratum_model_entry with STRATUM_MODEL_SHADER_NODE), so a node added to the library needs no
 * change in this header or in a host that does not use it. */
#ifndef STRATUM_SHADER_NODES_H
#define STRATUM_SHADER_NODES_H

#include "stratum/base.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct StratumScene StratumScene;

/* Input registers the renderer writes before a program runs. Surfaces: world space, normals unit
 * and turned toward the incoming ray (Cycles' sd->N, sd->Ng); the world: POSITION is the ray
 * direction and the normals and INCOMING its opposite. */
typedef enum StratumShaderInput {
    STRATUM_INPUT_POSITION = 0,         /* 3: world position */
    STRATUM_INPUT_NORMAL = 3,           /* 3: smooth shading normal (before any bump or map) */
    STRATUM_INPUT_TRUE_NORMAL = 6,      /* 3: geometric normal */
    STRATUM_INPUT_INCOMING = 9,         /* 3: unit direction toward the ray's origin (Cycles' I) */
    STRATUM_INPUT_UV = 12,              /* 3: the mesh's UV (u, v, 0) */
    STRATUM_INPUT_GENERATED = 15,       /* 3: object position in the mesh's texture space, [0,1] */
    STRATUM_INPUT_OBJECT = 18,          /* 3: object-space position */
    STRATUM_INPUT_CAMERA = 21,          /* 3: camera-space position (+Z forward, as Cycles) */
    STRATUM_INPUT_WINDOW = 24,          /* 3: reserved for the screen position (written 0) */
    STRATUM_INPUT_OBJECT_LOCATION = 27, /* 3: the object's origin in world space */
    STRATUM_INPUT_BACKFACING = 30,      /* 1: 1 on the back (winding) face, else 0 */
    STRATUM_INPUT_OBJECT_RANDOM = 31,   /* 1: Object Info's Random, [0,1] */
    STRATUM_INPUT_RAY_LENGTH = 32,      /* 1: distance the ray travelled to the point from where the
                                           path last scattered (or the camera's near clip plane,
                                           where Cycles starts a camera ray), transparent
                                           surfaces passed on the way counted (Cycles'
                                           sd->ray_length) */
    STRATUM_INPUT_OBJECT_INDEX = 33,    /* 1: the object's pass index */
    STRATUM_INPUT_MATERIAL_INDEX = 34,  /* 1: the material's pass index */
    STRATUM_INPUT_OBJECT_COLOR = 35,    /* 3: the object's colour (Object Info's Color) */
    STRATUM_INPUT_OBJECT_ALPHA = 38,    /* 1: its alpha */
    STRATUM_INPUT_TANGENT = 39,         /* 3: Geometry's Tangent: radial about the object's Z in
                                           generated space, in the shading plane (as Cycles) */
    STRATUM_INPUT_PARAMETRIC = 42,      /* 3: barycentric (1 - u - v, u, 0) as Cycles' Parametric */
    STRATUM_INPUT_OBJECT_NORMAL = 45,   /* 3: the shading normal in object space (Texture
                                           Coordinate's Normal), unit */
    /* The offsets a Bump node takes its finite differences over: two small steps in the tangent
     * plane (world space), and what each step changes GENERATED, OBJECT and UV by. */
    STRATUM_INPUT_DPDX = 48,
    STRATUM_INPUT_DPDY = 51,
    STRATUM_INPUT_DGENERATED_DX = 54,
    STRATUM_INPUT_DGENERATED_DY = 57,
    STRATUM_INPUT_DOBJECT_DX = 60,
    STRATUM_INPUT_DOBJECT_DY = 63,
    STRATUM_INPUT_DUV_DX = 66,
    STRATUM_INPUT_DUV_DY = 69,
    STRATUM_INPUT_REFLECTION = 72, /* 3: the view mirrored about the normal, 2 dot(N, I) N - I */
    STRATUM_INPUT_UV_TANGENT = 75, /* 3: the UV map's dpdu in the shading plane, unit (0 without UVs) */
    /* 1: the ray's footprint at the point, as Cycles' compact ray differential sd->dP: a camera
     * ray's spread between neighbouring pixels (half the sum of the differences of the pixel's
     * direction and origin to those of the next pixel right and the next up) times the distance
     * travelled, kept along the path (Cycles keeps a camera ray's spread through bounces); 0 on
     * light paths and in the world. */
    STRATUM_INPUT_PIXEL_FOOTPRINT = 78,
    /* The mesh's attributes in slots 0..3 (stratum_scene_set_mesh_attribute), 5 registers each:
     * colour (3), alpha, and the float Cycles' Attribute node gives (Fac). A slot the mesh lacks
     * reads colour 0, alpha 1, Fac 0, as Cycles reads a missing attribute. */
    STRATUM_INPUT_ATTRIBUTE_0 = 80,
    STRATUM_INPUT_ATTRIBUTE_1 = 85,
    STRATUM_INPUT_ATTRIBUTE_2 = 90,
    STRATUM_INPUT_ATTRIBUTE_3 = 95,
    /* 9: the hit triangle's three vertices in world space (at the ray's time for a moving
     * object); 0 in the world. */
    STRATUM_INPUT_TRIANGLE = 100,
    /* 3: the mesh's MikkTSpace tangent (stratum_scene_add_mesh's corner tangents) interpolated
     * over the triangle and taken to world space as a normal is (Cycles' UV tangent attribute
     * after object_normal_transform), not normalised nor projected; 0 when the mesh has none. */
    STRATUM_INPUT_MIKKTSPACE_TANGENT = 109,
    /* 9: where the object's normal transform (the inverse transpose of its linear part, up to a
     * positive scale, as Cycles' object_normal_transform before it normalises) takes its X, Y
     * and Z axes: n = x X + y Y + z Z for an object-space (x, y, z). The identity in the world. */
    STRATUM_INPUT_NORMAL_TRANSFORM = 112,
    /* 1 each: Cycles' Light Path node (kernel/svm/light_path.h), what the path that reaches the
     * point is. The ray kinds are 1 or 0: the kind of the ray that arrived (CAMERA until the
     * first scattering, transparent pass-throughs keep the kind), SHADOW on a shadow ray's
     * transparent surfaces; 0 each where Cycles evaluates with its EMISSION flag alone (a lamp,
     * a light sample of the world). The depths count scatterings as Cycles' path state does
     * (RAY_DEPTH all but transparent pass-throughs; DIFFUSE diffuse reflections; GLOSSY glossy
     * and mirror reflections; TRANSMISSION refractions; TRANSPARENT pass-throughs, on a shadow
     * ray those it crossed too), RAY_DEPTH plus one on shadow rays, lamps and the world. Stratum
     * has no volumes and no Ray Portal: VOLUME_SCATTER and PORTAL_DEPTH are 0. docs/cycles_models.md
     * "Light Path node" has the value in each context. */
    STRATUM_INPUT_IS_CAMERA_RAY = 121,
    STRATUM_INPUT_IS_SHADOW_RAY = 122,
    STRATUM_INPUT_IS_DIFFUSE_RAY = 123,
    STRATUM_INPUT_IS_GLOSSY_RAY = 124,
    STRATUM_INPUT_IS_SINGULAR_RAY = 125,
    STRATUM_INPUT_IS_REFLECTION_RAY = 126,
    STRATUM_INPUT_IS_TRANSMISSION_RAY = 127,
    STRATUM_INPUT_IS_VOLUME_SCATTER_RAY = 128,
    STRATUM_INPUT_RAY_DEPTH = 129,
    STRATUM_INPUT_DIFFUSE_DEPTH = 130,
    STRATUM_INPUT_GLOSSY_DEPTH = 131,
    STRATUM_INPUT_TRANSPARENT_DEPTH = 132,
    STRATUM_INPUT_TRANSMISSION_DEPTH = 133,
    STRATUM_INPUT_PORTAL_DEPTH = 134,
    /* 135 to 143 are free for inputs to come. */
    STRATUM_SHADER_INPUT_REGISTERS = 144
} StratumShaderInput;

/* One node: `type`, its enumerations in `modes` (what each means: docs/shader_nodes.md), the
 * register of each input and output (the first of three for a vector or colour; unused slots are
 * ignored), and a range of the program's constant `data` (a Color Ramp's stops, a curve's table,
 * the Sky's parameters). */
typedef struct StratumShaderNode {
    int32_t type; /* a value stratum_model_entry(STRATUM_MODEL_SHADER_NODE, ...) lists, by name */
    int32_t modes[6];
    uint32_t inputs[12];
    uint32_t outputs[6];
    uint32_t data_offset, data_count;
} StratumShaderNode;

typedef struct StratumShaderProgramDesc {
    const StratumShaderNode* nodes;
    uint32_t node_count;     /* at most 65536 */
    const float* registers;  /* register_count initial values (any float; the first
                                STRATUM_SHADER_INPUT_REGISTERS are overwritten) */
    uint32_t register_count; /* STRATUM_SHADER_INPUT_REGISTERS to 65536 */
    const float* data;       /* data_count constants the nodes' data ranges point into */
    uint32_t data_count;     /* at most 2^24 */
} StratumShaderProgramDesc;

/* Adds a program; its id (0, 1, 2, ...) is written to out_id. Every node is checked: a known
 * type, modes within their enumerations, registers and data ranges inside the program, an
 * IMAGE node's texture an added texture. A bad node fails naming its index, type and field. */
STRATUM_API StratumStatus stratum_scene_add_shader_program(StratumScene* scene,
                                                           const StratumShaderProgramDesc* program,
                                                           uint32_t* out_id);
/* Replaces program `program_id` (a live edit: a parameter changed in Blender). */
STRATUM_API StratumStatus stratum_scene_set_shader_program(StratumScene* scene, uint32_t program_id,
                                                           const StratumShaderProgramDesc* program);

/* Closure parameters a program can drive, with the registers each reads. Values are limited as
 * Cycles limits the sockets: colours >= 0 (emission may be negative, as in Cycles), roughness, metallic,
 * transmission and coat roughness to [0,1], specular and coat >= 0, IOR >= 1e-5, coat tint to [0,1]; a NaN
 * reads 0. WEIGHT multiplies the closure's weight by an RGB value >= 0 (the host computes Mix Shader factors,
 * saturated as Cycles saturates them). NORMAL is a world-space normal (the output of a Bump or Normal Map
 * node; normalised, and one that is zero or not finite keeps the smooth normal); it is the shading point's
 * normal for all closures. */
typedef enum StratumProgramParam {
    STRATUM_PROGRAM_BASE_COLOR = 0,      /* 3 */
    STRATUM_PROGRAM_ROUGHNESS = 1,       /* 1 */
    STRATUM_PROGRAM_METALLIC = 2,        /* 1 */
    STRATUM_PROGRAM_NORMAL = 3,          /* 3 */
    STRATUM_PROGRAM_EMISSION = 4,        /* 3: radiance, colour x strength */
    STRATUM_PROGRAM_WEIGHT = 5,          /* 3 */
    STRATUM_PROGRAM_TRANSMISSION = 6,    /* 1 */
    STRATUM_PROGRAM_SPECULAR = 7,        /* 1 */
    STRATUM_PROGRAM_IOR = 8,             /* 1 */
    STRATUM_PROGRAM_COAT = 9,            /* 1 */
    STRATUM_PROGRAM_COAT_ROUGHNESS = 10, /* 1 */
    STRATUM_PROGRAM_COAT_TINT = 11       /* 3 */
} StratumProgramParam;

typedef struct StratumProgramBinding {
    uint32_t material_id;
    uint32_t closure_index; /* 0 for a material added with stratum_scene_add_material */
    int32_t param;          /* StratumProgramParam */
    uint32_t program_id;
    uint32_t register_index; /* the first of the parameter's registers */
} StratumProgramBinding;

/* Drives one parameter of one closure by a program's register, evaluated at every shading point
 * of the material (each program once per point, however many parameters it drives). A later
 * binding of the same (material, closure, param) replaces the earlier one. Emission driven by a
 * program is found by rays that hit the surface (its triangles are not sampled as lights unless
 * the material's constant emission is not black). */
STRATUM_API StratumStatus stratum_scene_bind_program(StratumScene* scene,
                                                     const StratumProgramBinding* binding);

/* The world's radiance is the RGB of register `register_index` of program `program_id`,
 * evaluated for each direction (its inputs: POSITION = the direction, see above). It replaces
 * the background colour and any environment image. The renderer bakes it into an environment
 * of `width` x `height` texels (equirectangular, each the mean of 2 x 2 directions in it, or of
 * 16 x 16 next to a sharp feature such as a sun disc; width 4 to 16384, height 2 to 8192), which
 * is then looked up and importance-sampled as an image. A program that reads the Light Path
 * node's inputs is baked with Cycles' importance-map state (no ray kind, RAY_DEPTH 1, the other
 * depths 0), which only chooses light samples' directions: the program itself then runs for
 * each ray that leaves the scene and each light sample, with their Light Path inputs. */
STRATUM_API StratumStatus stratum_scene_set_background_program(StratumScene* scene, uint32_t program_id,
                                                               uint32_t register_index, uint32_t width,
                                                               uint32_t height);

/* Scales the emission of light `light_id` (in the order lights were added) by the RGB of register
 * `register_index` of program `program_id`, as Cycles shades a lamp with its node tree (Light >
 * Nodes: the Emission's Color x Strength). The program runs wherever the lamp's emission is used:
 * for a point it lights and for a ray that meets it, with RAY_LENGTH the distance between that
 * point (or the ray's origin) and the point on the lamp, FLT_MAX for a sun (Cycles' ls->t); light
 * tracing applies it where a particle first lands. The Light Path node's inputs are those of
 * Cycles' emission evaluation (no ray kind, RAY_DEPTH the path's depth + 1). Its other inputs are
 * those of no object (0, attributes' alpha 1, NORMAL_TRANSFORM the identity): a program that
 * reads any other renderer input is refused. Each channel is at least 0 (a NaN reads 0). The lamp's power, by
 * which lights are chosen, stays its own. program_id STRATUM_NO_PROGRAM removes the lamp's program; a later
 * call replaces it. */
#define STRATUM_NO_PROGRAM 0xFFFFFFFFu
STRATUM_API StratumStatus stratum_scene_set_light_program(StratumScene* scene, uint32_t light_id,
                                                          uint32_t program_id, uint32_t register_index);

/* Attribute slots a mesh can carry, and how an attribute's Fac is made (Cycles' Attribute node:
 * a float or 2-vector attribute gives its first component, a 3-vector or colour the mean). */
#define STRATUM_ATTRIBUTE_SLOTS 4u
typedef enum StratumAttributeKind {
    STRATUM_ATTRIBUTE_SCALAR = 0, /* float, int, boolean, 2-vector: Fac = first component */
    STRATUM_ATTRIBUTE_VECTOR = 1  /* 3-vector, colour: Fac = mean of the three */
} StratumAttributeKind;
/* Gives mesh `mesh_id` an attribute in slot `slot`: corner_rgba holds 12 floats per triangle (3
 * corners x RGBA, each finite; a scalar attribute repeated in RGB, alpha 1 unless it is a colour
 * with alpha), interpolated over each triangle into the ATTRIBUTE_<slot> input registers.
 * triangle_count must be the mesh's. Setting a slot again replaces it. */
STRATUM_API StratumStatus stratum_scene_set_mesh_attribute(StratumScene* scene, uint32_t mesh_id,
                                                           uint32_t slot, int32_t kind,
                                                           const float* corner_rgba, uint32_t triangle_count);

/* Evaluates program `program_id` with the given input registers (STRATUM_SHADER_INPUT_REGISTERS
 * floats) and copies `count` registers starting at `first` to `out`: for hosts' tests and
 * previews of a single node. */
STRATUM_API StratumStatus stratum_scene_evaluate_program(const StratumScene* scene, uint32_t program_id,
                                                         const float* inputs, uint32_t first, uint32_t count,
                                                         float* out);

#ifdef __cplusplus
}
#endif

#endif
