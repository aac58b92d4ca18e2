/* Stratum C ABI, part 3 of 4: building a scene (camera, materials, textures, meshes, instances,
 * lights, world), editing it live, saving and loading it. */
#ifndef STRATUM_SCENE_H
#define STRATUM_SCENE_H

#include "stratum/base.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- scene ----------------------------------------------------------------------------- */

typedef struct StratumScene StratumScene;

STRATUM_API StratumStatus stratum_scene_create(StratumScene** out_scene);
STRATUM_API void stratum_scene_destroy(StratumScene* scene);

typedef enum StratumMaterialModel {
    STRATUM_MATERIAL_DIFFUSE = 0,       /* Lambertian (Cycles' Diffuse BSDF, roughness 0) */
    STRATUM_MATERIAL_PRINCIPLED_V1 = 1, /* Cycles 3.x Principled: Burley diffuse + GGX */
    STRATUM_MATERIAL_PRINCIPLED_V2 = 2, /* Cycles 4.x Principled: Lambert + layered GGX */
    STRATUM_MATERIAL_EMISSION = 3,      /* pure emitter, no reflection */
    STRATUM_MATERIAL_GLOSSY = 4,        /* Cycles Glossy BSDF: GGX reflection, Fresnel 1, tinted by
                                           base_color; roughness 0 = mirror */
    STRATUM_MATERIAL_GLASS = 5,         /* Cycles Glass BSDF: dielectric GGX reflection + refraction
                                           with Fresnel at `ior`, both tinted by base_color;
                                           roughness 0 = smooth glass */
    STRATUM_MATERIAL_TRANSPARENT = 6,   /* Cycles Transparent BSDF: straight through, times base_color;
                                           shadow rays pass too (transparent shadows) */
    STRATUM_MATERIAL_HOLDOUT = 7        /* Cycles Holdout: what it covers is black with alpha 0 */
} StratumMaterialModel;

typedef enum StratumMicrofacetDistribution {
    STRATUM_MICROFACET_GGX = 0,             /* single-scattering GGX */
    STRATUM_MICROFACET_MULTISCATTER_GGX = 1 /* GGX with energy compensation (v2 only) */
} StratumMicrofacetDistribution;

typedef struct StratumMaterialDesc {
    int32_t model;        /* StratumMaterialModel */
    float base_color[3];  /* linear RGB reflectance, each in [0,1] */
    float roughness;      /* [0,1], Principled/Disney convention (alpha = roughness^2) */
    float metallic;       /* [0,1] */
    float specular;       /* v1: "Specular" [0,inf); v2: "Specular IOR Level" [0,inf) */
    float ior;            /* v2: index of refraction of the dielectric coat, > 0 */
    float emission[3];    /* emitted radiance (colour x strength), each >= 0 */
    int32_t distribution; /* StratumMicrofacetDistribution (the Principled node's) */
    /* Appended fields (Principled only; all zero = the opaque Principled above). */
    float transmission;     /* [0,1]: weight of the dielectric transmission lobe (at `ior`; v1
                               derives nothing from `specular` for it, as Cycles 3.x) */
    float coat;             /* [0,inf): v1 "Clearcoat" (GTR1 lobe, IOR 1.5, weight 0.25 coat);
                               v2 "Coat Weight" (dielectric GGX layer on top) */
    float coat_roughness;   /* [0,1]: v1 "Clearcoat Roughness", v2 "Coat Roughness" */
    float coat_ior;         /* v2: > 0 (Blender default 1.5) */
    float coat_tint[3];     /* v2: linear RGB in [0,1] */
    int32_t bump_shadowing; /* StratumBumpShadowing (appended; 0 = none) */
} StratumMaterialDesc;

/* Where a closure's normal differs from the smooth shading normal (a normal map, or the smooth
 * normal bent so that reflections stay above the surface), the BSDF is multiplied by a
 * shadowing term that hides the terminator the perturbed normal would otherwise show, as
 * Cycles does (kernel/closure/bsdf.h bump_shadowing_term). The model depends on the Blender
 * version, and from 4.2 on the material's "Bump Map Correction" chooses the smoothing. */
typedef enum StratumBumpShadowing {
    STRATUM_BUMP_SHADOWING_NONE = 0,              /* the perturbed normal alone */
    STRATUM_BUMP_SHADOWING_CHIANG = 1,            /* Cycles 2.90-4.4: diffuse lobes times Chiang et
                                                     al. 2019's G; 0 where it is negative */
    STRATUM_BUMP_SHADOWING_CHIANG_UNSMOOTHED = 2, /* Cycles 4.2-4.4, correction off: only the 0 */
    STRATUM_BUMP_SHADOWING_CONTY = 3,             /* Cycles 4.5+: every lobe 0 where wi and the
                                                     closure normal lie on different sides of the
                                                     smooth normal; diffuse lobes times Conty Estevez
                                                     et al. 2019's GGX G1 */
    STRATUM_BUMP_SHADOWING_CONTY_UNSMOOTHED = 4   /* Cycles 4.5+, correction off: only the side test */
} StratumBumpShadowing;

/* Adds a material; its id (0, 1, 2, ... in order) is written to out_id. */
STRATUM_API StratumStatus stratum_scene_add_material(StratumScene* scene, const StratumMaterialDesc* material,
                                                     uint32_t* out_id);

/* A material made of several closures (Blender's Mix Shader and Add Shader flattened, as Cycles
 * does): the scattering and emission of a shading point are sum_i weight_i * closure_i.
 * weight: linear RGB, each >= 0 and finite. */
typedef struct StratumClosureDesc {
    float weight[3];
    StratumMaterialDesc closure;
} StratumClosureDesc;

STRATUM_API StratumStatus stratum_scene_add_closure_material(StratumScene* scene,
                                                             const StratumClosureDesc* closures,
                                                             uint32_t closure_count, uint32_t* out_id);

/* ---- image textures ----------------------------------------------------------------------- */

typedef enum StratumTextureInterpolation {
    STRATUM_TEXTURE_CLOSEST = 0, /* nearest texel */
    STRATUM_TEXTURE_LINEAR = 1   /* bilinear (Cycles' Linear, and what Cubic/Smart fall back to) */
} StratumTextureInterpolation;

typedef enum StratumTextureExtension {
    STRATUM_TEXTURE_REPEAT = 0, /* tile */
    STRATUM_TEXTURE_EXTEND = 1, /* clamp to the edge texel */
    STRATUM_TEXTURE_CLIP = 2,   /* transparent black outside [0,1]^2 */
    STRATUM_TEXTURE_MIRROR = 3  /* tile, mirrored every other tile */
} StratumTextureExtension;

/* One image. Exactly one source: `path` (a file OpenImageIO reads), `file_data` + `file_size`
 * (the bytes of such a file in memory: Blender's packed images; `file_name` is required and its
 * extension chooses the reader), or `pixels` (width*height*channels floats, 1 to 4 channels:
 * grey, grey+alpha, RGB, RGBA; rows BOTTOM to top, exactly as Blender's Image.pixels gives
 * them). width/height/channels describe `pixels` only and must be 0 otherwise. Texture UV
 * (0,0) is the bottom-left of the picture (Blender's and Cycles' convention: a file's first
 * scanline is the top row). The image is converted to scene linear with OpenColorIO: from
 * `color_space` (a colour space name or alias in `ocio_config`, e.g. "sRGB", "Linear",
 * "Non-Color") to the config's scene_linear role; data colour spaces (isdata: Non-Color, Raw)
 * are not converted; alpha never is. ocio_config is the path of Blender's
 * datafiles/colormanagement/config.ocio; NULL (or a config the system's OpenColorIO cannot
 * read, e.g. Blender 5.0's version-2.4 config under OCIO 2.1) accepts only "Non-Color", "Raw",
 * "Linear", "Linear Rec.709" and "sRGB" (the exact piecewise sRGB curve). Alpha is straight
 * (not premultiplied; premultiplied OpenEXR data is divided by alpha); a missing alpha reads 1.
 * An unknown colour space is STRATUM_ERROR_INVALID_ARGUMENT naming it; a file that cannot be
 * read is STRATUM_ERROR_IO naming the path and OpenImageIO's message. */
typedef struct StratumTextureDesc {
    const char* path;
    const void* file_data;
    size_t file_size;
    const char* file_name;
    const float* pixels;
    uint32_t width, height, channels;
    const char* color_space;
    const char* ocio_config;
    int32_t interpolation; /* StratumTextureInterpolation */
    int32_t extension;     /* StratumTextureExtension */
} StratumTextureDesc;

/* Adds a texture; its id (0, 1, 2, ...) is written to out_id. Pixels may be NaN or infinite, and
 * a colour conversion may overflow (an sRGB value of 1e19): a texel with any channel not finite
 * after conversion becomes (0, 0, 0, 0), as in Cycles, and is counted (stratum_scene_texture_info).
 * A file is read only when it is a regular file (a FIFO or a device is STRATUM_ERROR_IO), and
 * only when its header's size fits in half of the machine's memory as float RGBA (else
 * STRATUM_ERROR_IO naming the image and the memory it would need); likewise `pixels`. */
STRATUM_API StratumStatus stratum_scene_add_texture(StratumScene* scene, const StratumTextureDesc* texture,
                                                    uint32_t* out_id);

/* What loading a texture found: its size and how many texels were NaN or infinite (replaced). */
typedef struct StratumTextureInfo {
    uint32_t width, height;
    uint64_t replaced_texels;
} StratumTextureInfo;

STRATUM_API StratumStatus stratum_scene_texture_info(const StratumScene* scene, uint32_t texture_id,
                                                     StratumTextureInfo* out);

typedef enum StratumMaterialParam {
    STRATUM_PARAM_BASE_COLOR = 0, /* RGB */
    STRATUM_PARAM_ROUGHNESS = 1,  /* scalar */
    STRATUM_PARAM_METALLIC = 2,   /* scalar */
    STRATUM_PARAM_NORMAL = 3,     /* tangent-space normal map (Normal Map node), strength = scale */
    STRATUM_PARAM_EMISSION = 4,   /* RGB, replaces the emission colour; times emission_strength */
    STRATUM_PARAM_WEIGHT = 5,     /* scalar: multiplies the closure's weight (Mix factors, alpha) */
    STRATUM_PARAM_TRANSMISSION = 6,
    STRATUM_PARAM_SPECULAR = 7
} StratumMaterialParam;

/* Drives one parameter of one closure of a material by a texture, looked up at the mesh's
 * corner_uvs. value = offset + scale * texel, where texel is the texture's RGB (channel -1) or
 * one channel (0..3 = R, G, B, A) replicated; a scalar parameter reads an RGB texel as its
 * luminance 0.2126729 R + 0.7151522 G + 0.0721750 B (Cycles' colour-to-float conversion).
 * Results are clamped as Cycles clamps the sockets: colours >= 0, roughness/metallic/WEIGHT to
 * [0,1], specular >= 0. For STRATUM_PARAM_NORMAL the texel is a tangent-space normal
 * (2 texel - 1), channel must be -1, `scale` is the Normal Map strength and `offset` is unused;
 * the perturbed normal is the shading point's (all closures). STRATUM_PARAM_EMISSION is
 * refused (emissive triangles are light-sampled with constant emission) and
 * STRATUM_PARAM_TRANSMISSION too until materials carry a transmission weight;
 * emission_strength must be 0. A later binding of the same (material, closure, param)
 * replaces the earlier one. */
typedef struct StratumTextureBinding {
    uint32_t material_id;
    uint32_t closure_index; /* 0 for a material added with stratum_scene_add_material */
    int32_t param;          /* StratumMaterialParam */
    uint32_t texture_id;
    int32_t channel; /* -1 = RGB, 0..3 */
    float scale, offset;
    float emission_strength; /* STRATUM_PARAM_EMISSION only */
} StratumTextureBinding;

/* Material > Settings > Pass Index of material `material_id` (0 until set), what the IndexMA
 * pass holds where the material is seen; at most STRATUM_MAX_PASS_INDEX. Also a live edit. */
STRATUM_API StratumStatus stratum_scene_set_material_pass_index(StratumScene* scene, uint32_t material_id,
                                                                uint32_t pass_index);
STRATUM_API StratumStatus stratum_scene_bind_texture(StratumScene* scene,
                                                     const StratumTextureBinding* binding);

typedef struct StratumMeshDesc {
    const float* positions; /* 3 floats per vertex, object space; required */
    uint32_t vertex_count;
    const uint32_t* triangles; /* 3 vertex indices per triangle; required */
    uint32_t triangle_count;
    const float* corner_normals;  /* optional: 9 floats per triangle (3 corners) */
    const float* corner_uvs;      /* optional: 6 floats per triangle (3 corners) */
    const uint32_t* material_ids; /* 1 scene material id per triangle; required */
    /* Appended: optional 3 floats per vertex, interpolated over each triangle (a smooth mesh
     * without split normals, as Cycles takes them: 12 bytes a vertex instead of 36 a triangle).
     * At most one of corner_normals and vertex_normals; neither = geometric normals. */
    const float* vertex_normals;
    /* Appended (issue 12): optional 12 floats per triangle, per corner the tangent (x, y, z) and
     * the bitangent sign, object space: Blender's MikkTSpace tangents (Mesh.calc_tangents,
     * MeshLoop.tangent and .bitangent_sign), which Cycles' Normal Map node uses. Interpolated
     * over the triangle, unnormalised, as Cycles does; B = sign cross(N, T). Without them a
     * Normal Map binding uses the triangle's dpdu (constant per triangle). */
    const float* corner_tangents;
} StratumMeshDesc;

/* Adds a mesh (copied); its id (0, 1, 2, ...) is written to out_id. A mesh is drawn only
 * through instances. */
STRATUM_API StratumStatus stratum_scene_add_mesh(StratumScene* scene, const StratumMeshDesc* mesh,
                                                 uint32_t* out_id);
/* Blender's texture space of mesh `mesh_id` (Mesh.texspace_location and texspace_size): the box
 * location +- size that generated coordinates map to [0,1]^3. Until set, the mesh's bounding box
 * (Blender's automatic texture space); a size component of 0 reads as 1 and one below 1e-5 as
 * 1e-5, as Blender keeps them. Each value finite, at most 1e12 in magnitude. */
STRATUM_API StratumStatus stratum_scene_set_mesh_texture_space(StratumScene* scene, uint32_t mesh_id,
                                                               const float location[3], const float size[3]);
/* Places mesh `mesh_id` with an object-to-world transform (16 floats, row-major). A singular or
 * nearly singular transform (scale (nearly) 0 along some axis) is accepted, and the placement
 * is skipped when the render scene is built, with a notice (stratum_renderer_notices). */
STRATUM_API StratumStatus stratum_scene_add_instance(StratumScene* scene, uint32_t mesh_id,
                                                     const float transform[16]);
/* Places `count` instances as `count` calls of stratum_scene_add_instance(scene, mesh_ids[i],
 * transforms + 16 i) would, in one call (a scene of 10 000s of instances pays one call and one
 * lock). All or nothing: when instance i is rejected none is added, the status and
 * stratum_last_error() say why as stratum_scene_add_instance would, and i is written to
 * *out_failed_index (if not NULL; UINT32_MAX when no instance was rejected). count 0 adds nothing
 * (the arrays may then be NULL). */
STRATUM_API StratumStatus stratum_scene_add_instances(StratumScene* scene, uint32_t count,
                                                      const uint32_t* mesh_ids, const float* transforms,
                                                      uint32_t* out_failed_index);

/* Ray visibility (Cycles' Object > Visibility > Ray Visibility and the light's equivalents). */
typedef enum StratumVisibility {
    STRATUM_VISIBLE_CAMERA = 1,
    STRATUM_VISIBLE_DIFFUSE = 2,
    STRATUM_VISIBLE_GLOSSY = 4,
    STRATUM_VISIBLE_TRANSMISSION = 8,
    STRATUM_VISIBLE_SHADOW = 16,
    STRATUM_VISIBLE_ALL = 31,
    /* Not a ray kind: Blender's Object > Visibility > Shadow Catcher (object.is_shadow_catcher).
       On an instance: the object is a Cycles shadow catcher. On a light: it lights the
       catcher-only copy of a camera path (Blender sets it on lights by default). */
    STRATUM_VISIBLE_SHADOW_CATCHER = 32
} StratumVisibility;

typedef struct StratumInstanceDesc {
    uint32_t mesh_id;
    float transform[16];     /* object-to-world (row-major) at shutter open, or always if static */
    float transform_end[16]; /* at shutter close; read when motion = 1 */
    int32_t motion;          /* 0 static; 1 moves from transform to transform_end over the shutter
                                (rotation interpolated as a quaternion, as Cycles) */
    uint32_t visibility;     /* StratumVisibility bits: which rays see the object */
    int32_t holdout;         /* 1: Cycles' Object > Visibility > Holdout */
    uint32_t pass_index;     /* appended: Object > Relations > Pass Index, what the IndexOB pass
                                holds; at most STRATUM_MAX_PASS_INDEX */
    uint32_t lightgroup;     /* appended: the light group of the object's emission, 0 = none, k in
                                1..STRATUM_MAX_LIGHT_GROUPS = group k (see stratum_renderer_read_lightgroup) */
} StratumInstanceDesc;

/* Cycles' light groups (view_layer.lightgroups): a render writes one RGB pass per group, the
 * light each group's emitters (lights, emissive objects, the world) contribute. */
#define STRATUM_MAX_LIGHT_GROUPS 64u

/* Pass indices are stored in float passes: every integer up to 2^24 is exact there. */
#define STRATUM_MAX_PASS_INDEX 16777216u

/* What shader programs' Object Info node reads of instances first .. first + count - 1: Random
 * (random[i] in [0,1]: Cycles' random_id / 0xFFFFFFFF; NULL leaves it) and the object's colour
 * and alpha (color[4 i .. 4 i + 3], each finite; NULL leaves them). Until set, random 0 and
 * colour (1, 1, 1, 1); stratum_scene_set_instance keeps them. */
STRATUM_API StratumStatus stratum_scene_set_instance_object_info(StratumScene* scene, uint32_t first,
                                                                 uint32_t count, const float* random,
                                                                 const float* color);
/* Light linking and shadow linking (Blender 4.0+, Cycles' definitions): the sets Blender's
 * depsgraph gives objects (receiver_light_set, blocker_shadow_set: ids 0..63, 0 the default set)
 * and emitters (light_set_membership, shadow_set_membership: bit s = set s). An emitter lights a
 * receiver iff bit receiver_light_set of its light_set_membership is set; an occluder blocks it
 * iff bit blocker_shadow_set of its shadow_set_membership is set. Camera rays see every emitter.
 * target STRATUM_LINK_INSTANCES sets instances first .. first + count - 1 (receivers, occluders,
 * and the emitters their emissive materials make); STRATUM_LINK_LIGHTS sets lamps, which are
 * emitters only: their receiver_light_set and blocker_shadow_set must be NULL. A NULL array
 * leaves that field. Until set, set 0 and all memberships (no linking); stratum_scene_set_instance
 * and stratum_scene_set_light keep them. */
typedef enum StratumLinkTarget { STRATUM_LINK_INSTANCES = 0, STRATUM_LINK_LIGHTS = 1 } StratumLinkTarget;
#define STRATUM_MAX_LINK_SET 63u
STRATUM_API StratumStatus stratum_scene_set_light_linking(StratumScene* scene, int32_t target, uint32_t first,
                                                          uint32_t count, const uint8_t* receiver_light_set,
                                                          const uint8_t* blocker_shadow_set,
                                                          const uint64_t* light_set_membership,
                                                          const uint64_t* shadow_set_membership);
/* Places an instance. A mesh placed many times is stored once (Embree instancing). */
STRATUM_API StratumStatus stratum_scene_add_instance_ex(StratumScene* scene,
                                                        const StratumInstanceDesc* instance);

typedef enum StratumLightType {
    STRATUM_LIGHT_POINT = 0,          /* power in W (Blender's), radius in m */
    STRATUM_LIGHT_SUN = 1,            /* strength = irradiance W/m^2, angle = angular diameter (rad) */
    STRATUM_LIGHT_AREA_RECTANGLE = 2, /* power P in W, size_x * size_y (square: equal sizes);
                                         one-sided Lambertian, radiance P / (pi * area) */
    STRATUM_LIGHT_AREA_ELLIPSE = 3,   /* power in W, diameters size_x, size_y (disk: equal) */
    STRATUM_LIGHT_SPOT = 4,           /* point light (power, radius) limited to a cone down local -Z:
                                         spot_size, spot_blend; Cycles 4.x/5.x falloff */
    STRATUM_LIGHT_SPOT_V1 = 5         /* as SPOT, times cos(angle to the axis): Cycles 3.x */
} StratumLightType;

typedef struct StratumLightDesc {
    int32_t type;         /* StratumLightType */
    float color[3];       /* linear RGB, >= 0 */
    float strength;       /* power (W) or, for the sun, irradiance (W/m^2); >= 0 */
    float radius;         /* point: sphere radius, >= 0 */
    float angle;          /* sun: angular diameter in radians, [0, pi] */
    float size_x, size_y; /* area: extent along local x and y, > 0 */
    float transform[16];  /* light-to-world, row-major; lights point down local -Z */
    /* Appended fields (spot lights only; ignored otherwise). */
    float spot_size;  /* full cone angle in radians, (0, pi] */
    float spot_blend; /* [0, 1]: smoothstep falloff over this fraction of (1 - cos(spot_size/2)) */
    /* Appended fields: visibility 0 reads as STRATUM_VISIBLE_ALL | STRATUM_VISIBLE_SHADOW_CATCHER. */
    uint32_t visibility; /* StratumVisibility bits: CAMERA (area lights seen by camera rays),
                            DIFFUSE / GLOSSY / TRANSMISSION (lit by it at such a vertex), SHADOW
                            (Cycles' cast_shadow) */
    float spread;        /* area lights: Cycles' spread in radians, (0, pi]; 0 reads as pi */
    uint32_t lightgroup; /* appended: 0 = none, k = light group k (STRATUM_MAX_LIGHT_GROUPS) */
} StratumLightDesc;

STRATUM_API StratumStatus stratum_scene_add_light(StratumScene* scene, const StratumLightDesc* light);

typedef enum StratumSensorFit {
    STRATUM_SENSOR_FIT_AUTO = 0,
    STRATUM_SENSOR_FIT_HORIZONTAL = 1,
    STRATUM_SENSOR_FIT_VERTICAL = 2
} StratumSensorFit;

typedef enum StratumCameraType {
    STRATUM_CAMERA_PERSPECTIVE = 0,    /* Blender PERSP: lens_mm and the sensor frame the view */
    STRATUM_CAMERA_ORTHOGRAPHIC = 1,   /* Blender ORTHO: ortho_scale frames the view */
    STRATUM_CAMERA_EQUIRECTANGULAR = 2 /* Blender PANO, equirectangular: the image spans longitude
                                          [longitude_min, longitude_max] left to right and latitude
                                          [latitude_min, latitude_max] bottom to top */
} StratumCameraType;

typedef struct StratumCameraDesc {
    float lens_mm;              /* focal length, > 0 */
    float sensor_width_mm;      /* > 0 */
    float sensor_height_mm;     /* > 0 */
    int32_t sensor_fit;         /* StratumSensorFit */
    float shift_x, shift_y;     /* in units of the fitted sensor dimension, as Blender */
    float clip_start, clip_end; /* 0 < clip_start < clip_end */
    float transform[16];        /* camera-to-world, row-major; looks down local -Z, +Y up */
    /* Appended fields: all zero gives the perspective pinhole camera above. */
    int32_t type;                       /* StratumCameraType */
    float ortho_scale;                  /* orthographic: extent of the fitted image side, scene units, > 0 */
    float aperture_radius;              /* thin lens radius in scene units (Cycles: lens/(2 fstop), lens in
                                           m; orthographic 1/(2 fstop)), >= 0; 0 = pinhole */
    float focus_distance;               /* depth of the sharp plane along the view axis; > 0 if aperture */
    int32_t aperture_blades;            /* 0 = round aperture, >= 3 = regular polygon */
    float aperture_rotation;            /* radians, rotates the polygon */
    float latitude_min, latitude_max;   /* equirectangular, radians */
    float longitude_min, longitude_max; /* equirectangular, radians */
} StratumCameraDesc;

STRATUM_API StratumStatus stratum_scene_set_camera(StratumScene* scene, const StratumCameraDesc* camera);
/* Constant background radiance (Blender world colour x strength). */
STRATUM_API StratumStatus stratum_scene_set_background(StratumScene* scene, const float rgb[3]);
/* The light group of the world (background or environment): 0 = none, k = group k (at most
 * STRATUM_MAX_LIGHT_GROUPS); 0 until set. A live edit of the world. */
STRATUM_API StratumStatus stratum_scene_set_world_lightgroup(StratumScene* scene, uint32_t lightgroup);
/* Environment image (Blender World: Background <- Environment Texture, equirectangular): it
 * replaces the constant background and is importance-sampled as a light. rgb: width*height*3
 * linear RGB floats (copied), rows top (+Z) to bottom, each >= 0 and finite; the radiance is
 * rgb * strength (strength >= 0). Cycles' mapping: a world direction d is looked up at
 * e = rotation * d (rotation: row-major 3x3 world-to-environment rotation, NULL = identity) with
 * u = 0.5 - atan2(e.y, e.x)/(2 pi) (left to right), v = 1 - acos(e.z)/pi (bottom to top);
 * nearest texel. Calling it again replaces the image. */
STRATUM_API StratumStatus stratum_scene_set_environment(StratumScene* scene, const float* rgb, uint32_t width,
                                                        uint32_t height, float strength,
                                                        const float rotation[9]);

/* ---- live edits ------------------------------------------------------------------------ */
/* A scene can be edited after renderers were made from it (the viewport's live scene): each call
 * below replaces one part, validated as when it was added, and so do stratum_scene_set_camera,
 * _set_background and _set_environment. A renderer sees the edits at its next
 * stratum_renderer_start, which starts again from sample 0 and rebuilds only what changed: a
 * moved, hidden or re-shaded instance updates its BVH placement (a top-level recommit for an
 * instanced mesh), a material, light or world edit the light set, a camera edit nothing. The
 * image equals that of a scene built anew with the edits. A rejected edit changes nothing. */
STRATUM_API StratumStatus stratum_scene_set_instance(StratumScene* scene, uint32_t index,
                                                     const StratumInstanceDesc* instance);
STRATUM_API StratumStatus stratum_scene_set_material(StratumScene* scene, uint32_t material_id,
                                                     const StratumMaterialDesc* material);
STRATUM_API StratumStatus stratum_scene_set_closure_material(StratumScene* scene, uint32_t material_id,
                                                             const StratumClosureDesc* closures,
                                                             uint32_t closure_count);
STRATUM_API StratumStatus stratum_scene_set_light(StratumScene* scene, uint32_t index,
                                                  const StratumLightDesc* light);

/* Writes / reads a captured scene (JSON) for the native CLI and for bug reports. */
STRATUM_API StratumStatus stratum_scene_save(const StratumScene* scene, const char* path);
STRATUM_API StratumStatus stratum_scene_load(const char* path, StratumScene** out_scene);

/* Benchmark ceiling: traces the path tracer's ray mix (camera ray, then per vertex one bounce
 * and one shadow ray, up to max_bounces) with Embree alone, no shading or sampling, and reports
 * the rays traced and the seconds spent (BVH build excluded). */
STRATUM_API StratumStatus stratum_scene_measure_ray_throughput(const StratumScene* scene, uint32_t width,
                                                               uint32_t height, uint32_t samples,
                                                               uint32_t max_bounces, uint32_t threads,
                                                               double* out_rays, double* out_seconds);

#ifdef __cplusplus
}
#endif

#endif
