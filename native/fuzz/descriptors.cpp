#include "descriptors.h"

#include <cmath>
#include <initializer_list>
#include <variant>

namespace stratum::fuzz {

namespace {

struct FloatField {
    float* value;
    FloatKind kind;
};
struct IntField {
    int32_t* value;
};
struct VisibilityField {
    uint32_t* value;
};
using Field = std::variant<FloatField, IntField, VisibilityField>;

// Visibility bits: mostly within STRATUM_VISIBLE_ALL, sometimes with bits beyond it.
uint32_t draw_visibility(ByteReader& in) {
    const uint8_t s = in.u8();
    return s < 224 ? s % 32u : s;
}

// Up to max_count mutations, each of one field chosen by a byte.
void mutate(ByteReader& in, std::initializer_list<Field> fields, unsigned max_count) {
    const unsigned count = in.u8() % (max_count + 1);
    const std::vector<Field> table(fields);
    for (unsigned i = 0; i < count; ++i) {
        const Field& f = table[in.u8() % table.size()];
        if (const auto* ff = std::get_if<FloatField>(&f)) {
            *ff->value = in.f32(ff->kind);
        } else if (const auto* fi = std::get_if<IntField>(&f)) {
            *fi->value = draw_small_int(in);
        } else {
            *std::get<VisibilityField>(f).value = draw_visibility(in);
        }
    }
}

void copy_matrix(const Matrix& m, float (&out)[16]) {
    for (size_t i = 0; i < 16; ++i) out[i] = m[i];
}

Matrix identity() { return translation(0.0f, 0.0f, 0.0f); }

}  // namespace

int32_t draw_small_int(ByteReader& in) {
    const uint8_t s = in.u8();
    static constexpr int32_t kBoundary[16] = {
        INT32_MIN,     INT32_MAX,     -1, 0, 1, 2, 3, 4, 1000000, 1000001, 65535, 65536, -2,
        INT32_MIN + 1, INT32_MAX - 1, 7};
    if (s < 16) return kBoundary[s];
    return s % 12 - 2;
}

int32_t draw_enum(ByteReader& in, int32_t count) {
    const uint8_t s = in.u8();
    return s < 240 ? s % count : s - 242;
}

int32_t draw_model(ByteReader& in, int32_t kind) {
    const int32_t index = draw_enum(in, stratum_model_count(kind));
    int32_t value = index;
    if (index >= 0) stratum_model_entry(kind, index, nullptr, &value);
    return value;
}

Matrix translation(float x, float y, float z) { return {1, 0, 0, x, 0, 1, 0, y, 0, 0, 1, z, 0, 0, 0, 1}; }

Matrix draw_matrix(ByteReader& in, const Matrix& preset) {
    Matrix m = preset;
    switch (in.u8() % 6) {
        case 0:
            break;
        case 1:
            for (size_t row = 0; row < 3; ++row) m[4 * row + 3] += in.f32(FloatKind::Signed);
            break;
        case 2: {
            const float s = in.f32(FloatKind::Positive);
            for (size_t row = 0; row < 3; ++row)
                for (size_t col = 0; col < 3; ++col) m[4 * row + col] *= s;
            break;
        }
        case 3:
            for (size_t row = 0; row < 3; ++row)
                for (size_t col = 0; col < 3; ++col)
                    m[4 * row + col] = row == col ? in.f32(FloatKind::Signed) : 0.0f;
            break;
        case 4: {
            // A rotation about the x, y or z axis, keeping the preset's translation.
            const size_t axis = in.u8() % 3, a = (axis + 1) % 3, b = (axis + 2) % 3;
            const float angle = in.f32(FloatKind::Signed), c = std::cos(angle), s = std::sin(angle);
            for (size_t row = 0; row < 3; ++row)
                for (size_t col = 0; col < 3; ++col) m[4 * row + col] = row == col ? 1.0f : 0.0f;
            m[4 * a + a] = c;
            m[4 * a + b] = -s;
            m[4 * b + a] = s;
            m[4 * b + b] = c;
            break;
        }
        default:
            for (size_t i = 0; i < 12; ++i) m[i] = in.f32(FloatKind::Signed);
            break;
    }
    const unsigned mutations = in.u8() % 4;
    for (unsigned i = 0; i < mutations; ++i) {
        const size_t element = in.u8() % 16;
        m[element] = in.f32(FloatKind::Signed);
    }
    return m;
}

StratumMaterialDesc draw_material(ByteReader& in) {
    StratumMaterialDesc d{};
    d.model = draw_model(in, STRATUM_MODEL_CLOSURE);
    for (float& c : d.base_color) c = 0.8f;
    d.roughness = 0.5f;
    d.specular = 0.5f;
    d.ior = 1.45f;
    if (d.model == STRATUM_MATERIAL_EMISSION)
        for (float& e : d.emission) e = 4.0f;
    d.coat_roughness = 0.03f;
    d.coat_ior = 1.5f;
    for (float& t : d.coat_tint) t = 1.0f;
    d.bump_shadowing = draw_enum(in, STRATUM_BUMP_SHADOWING_CONTY_UNSMOOTHED + 1);
    using K = FloatKind;
    mutate(in,
           {FloatField{&d.base_color[0], K::Unit},
            FloatField{&d.base_color[1], K::Unit},
            FloatField{&d.base_color[2], K::Unit},
            FloatField{&d.roughness, K::Unit},
            FloatField{&d.metallic, K::Unit},
            FloatField{&d.specular, K::Unit},
            FloatField{&d.ior, K::Positive},
            FloatField{&d.emission[0], K::Positive},
            FloatField{&d.emission[1], K::Positive},
            FloatField{&d.emission[2], K::Positive},
            FloatField{&d.transmission, K::Unit},
            FloatField{&d.coat, K::Unit},
            FloatField{&d.coat_roughness, K::Unit},
            FloatField{&d.coat_ior, K::Positive},
            FloatField{&d.coat_tint[0], K::Unit},
            FloatField{&d.coat_tint[1], K::Unit},
            FloatField{&d.coat_tint[2], K::Unit},
            IntField{&d.model},
            IntField{&d.distribution},
            IntField{&d.bump_shadowing}},
           4);
    return d;
}

StratumLightDesc draw_light(ByteReader& in) {
    StratumLightDesc d{};
    d.type = draw_model(in, STRATUM_MODEL_LIGHT);
    for (float& c : d.color) c = 1.0f;
    d.strength = d.type == STRATUM_LIGHT_SUN ? 3.0f : 100.0f;
    d.radius = 0.1f;
    d.angle = 0.01f;
    d.size_x = d.size_y = 1.0f;
    d.spot_size = 1.0f;
    d.spot_blend = 0.15f;
    // Above the origin, pointing down (lights point down local -Z).
    copy_matrix(draw_matrix(in, translation(0.0f, 0.0f, 3.0f)), d.transform);
    using K = FloatKind;
    mutate(in,
           {FloatField{&d.color[0], K::Unit}, FloatField{&d.color[1], K::Unit},
            FloatField{&d.color[2], K::Unit}, FloatField{&d.strength, K::Positive},
            FloatField{&d.radius, K::Positive}, FloatField{&d.angle, K::Unit},
            FloatField{&d.size_x, K::Positive}, FloatField{&d.size_y, K::Positive},
            FloatField{&d.spot_size, K::Unit}, FloatField{&d.spot_blend, K::Unit},
            FloatField{&d.spread, K::Unit}, IntField{&d.type}, VisibilityField{&d.visibility}},
           3);
    return d;
}

StratumCameraDesc draw_camera(ByteReader& in) {
    StratumCameraDesc d{};
    const int preset = in.u8() % 4;
    d.lens_mm = 50.0f;
    d.sensor_width_mm = 36.0f;
    d.sensor_height_mm = 24.0f;
    d.clip_start = 0.1f;
    d.clip_end = 100.0f;
    d.type = preset == 3 ? STRATUM_CAMERA_PERSPECTIVE : preset;
    d.ortho_scale = 6.0f;
    if (preset == 3) {
        d.aperture_radius = 0.05f;
        d.focus_distance = 5.0f;
        d.aperture_blades = 6;
    }
    d.latitude_min = -1.5707963f;
    d.latitude_max = 1.5707963f;
    d.longitude_min = -3.1415926f;
    d.longitude_max = 3.1415926f;
    // At +5 on z, looking down -z at the origin.
    copy_matrix(draw_matrix(in, translation(0.0f, 0.0f, 5.0f)), d.transform);
    using K = FloatKind;
    mutate(in,
           {FloatField{&d.lens_mm, K::Positive}, FloatField{&d.sensor_width_mm, K::Positive},
            FloatField{&d.sensor_height_mm, K::Positive}, FloatField{&d.shift_x, K::Signed},
            FloatField{&d.shift_y, K::Signed}, FloatField{&d.clip_start, K::Positive},
            FloatField{&d.clip_end, K::Positive}, FloatField{&d.ortho_scale, K::Positive},
            FloatField{&d.aperture_radius, K::Positive}, FloatField{&d.focus_distance, K::Positive},
            FloatField{&d.aperture_rotation, K::Signed}, FloatField{&d.latitude_min, K::Signed},
            FloatField{&d.latitude_max, K::Signed}, FloatField{&d.longitude_min, K::Signed},
            FloatField{&d.longitude_max, K::Signed}, IntField{&d.sensor_fit}, IntField{&d.type},
            IntField{&d.aperture_blades}},
           5);
    return d;
}

StratumInstanceDesc draw_instance(ByteReader& in, uint32_t mesh_count) {
    StratumInstanceDesc d{};
    d.mesh_id = in.id(mesh_count);
    const Matrix start = draw_matrix(in, identity());
    copy_matrix(start, d.transform);
    static constexpr int32_t kMotion[8] = {0, 1, 1, 0, 1, 2, -1, 0};
    d.motion = kMotion[in.u8() % 8];
    // The end transform starts from the start one, so its mutations are motion (a shear, a
    // shift) rather than a teleport.
    copy_matrix(draw_matrix(in, start), d.transform_end);
    d.visibility = draw_visibility(in);
    const uint8_t holdout = in.u8();
    d.holdout = holdout % 8 == 7 ? 2 : holdout % 2;
    // The same byte's high bits give the pass index (no new byte: the corpus keeps its meaning);
    // 31 is one past the largest accepted.
    d.pass_index = holdout / 8 == 31 ? STRATUM_MAX_PASS_INDEX + 1 : holdout / 8;
    return d;
}

StratumMeshDesc MeshArrays::desc() const {
    StratumMeshDesc d{};
    d.positions = null_positions ? nullptr : positions.data();
    d.vertex_count = vertex_count;
    d.triangles = null_triangles ? nullptr : triangles.data();
    d.triangle_count = triangle_count;
    d.corner_normals = with_corner_normals ? corner_normals.data() : nullptr;
    d.corner_uvs = with_corner_uvs ? corner_uvs.data() : nullptr;
    d.material_ids = null_material_ids ? nullptr : material_ids.data();
    d.vertex_normals = with_vertex_normals ? vertex_normals.data() : nullptr;
    d.corner_tangents = with_corner_tangents ? corner_tangents.data() : nullptr;
    return d;
}

MeshArrays draw_mesh(ByteReader& in, uint32_t material_count) {
    MeshArrays m;
    switch (in.u8() % 4) {
        case 0:  // one triangle facing +z
            m.positions = {-1, -1, 0, 1, -1, 0, 0, 1, 0};
            m.triangles = {0, 1, 2};
            break;
        case 1:  // a 2 x 2 square facing +z
            m.positions = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
            m.triangles = {0, 1, 2, 0, 2, 3};
            break;
        case 2:  // the cube [-1, 1]^3
            m.positions = {-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1,
                           -1, -1, 1,  1, -1, 1,  1, 1, 1,  -1, 1, 1};
            m.triangles = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                           3, 7, 6, 3, 6, 2, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5};
            break;
        default: {  // any 0..16 vertices and 0..16 triangles, indices sometimes out of range
            const uint32_t vertices = in.u8() % 17, triangles = in.u8() % 17;
            for (uint32_t i = 0; i < 3 * vertices; ++i) m.positions.push_back(in.f32(FloatKind::Signed));
            for (uint32_t i = 0; i < 3 * triangles; ++i) m.triangles.push_back(in.u8() % (vertices + 1));
            break;
        }
    }
    m.vertex_count = static_cast<uint32_t>(m.positions.size() / 3);
    m.triangle_count = static_cast<uint32_t>(m.triangles.size() / 3);
    const unsigned moves = in.u8() % 5;
    for (unsigned i = 0; i < moves && !m.positions.empty(); ++i) {
        const size_t k = in.u8() % m.positions.size();
        m.positions[k] = in.f32(FloatKind::Signed);
    }
    const uint8_t flags = in.u8();
    m.with_corner_normals = flags & 1;
    m.with_vertex_normals = flags & 2;
    m.with_corner_uvs = flags & 4;
    m.null_positions = (flags & 0x38) == 0x08;
    m.null_triangles = (flags & 0x38) == 0x10;
    m.null_material_ids = (flags & 0x38) == 0x18;
    // Optional arrays: plausible values (normals +z, uvs from x and y), then a few mutations.
    const size_t t = m.triangle_count;
    for (size_t c = 0; c < 3 * t; ++c) m.corner_normals.insert(m.corner_normals.end(), {0.0f, 0.0f, 1.0f});
    for (size_t v = 0; v < m.vertex_count; ++v)
        m.vertex_normals.insert(m.vertex_normals.end(), {0.0f, 0.0f, 1.0f});
    for (size_t c = 0; c < 3 * t; ++c) {
        const size_t v = m.triangles[c] < m.vertex_count ? m.triangles[c] : 0;
        const float x = m.vertex_count ? m.positions[3 * v] : 0.0f,
                    y = m.vertex_count ? m.positions[3 * v + 1] : 0.0f;
        m.corner_uvs.insert(m.corner_uvs.end(), {0.5f * x + 0.5f, 0.5f * y + 0.5f});
    }
    for (std::vector<float>* array : {&m.corner_normals, &m.vertex_normals, &m.corner_uvs}) {
        const unsigned n = in.u8() % 3;
        for (unsigned i = 0; i < n && !array->empty(); ++i) {
            const size_t k = in.u8() % array->size();
            (*array)[k] = in.f32(FloatKind::Signed);
        }
    }
    // Tangents (+x, sign +1), mutated: read only with the flag, so inputs without it keep their
    // meaning.
    m.with_corner_tangents = flags & 0x80;
    if (m.with_corner_tangents) {
        for (size_t c = 0; c < 3 * t; ++c)
            m.corner_tangents.insert(m.corner_tangents.end(), {1.0f, 0.0f, 0.0f, 1.0f});
        const unsigned n = in.u8() % 4;
        for (unsigned i = 0; i < n && !m.corner_tangents.empty(); ++i) {
            const size_t k = in.u8() % m.corner_tangents.size();
            m.corner_tangents[k] = in.f32(FloatKind::Signed);
        }
    }
    const uint32_t material = in.id(material_count);
    m.material_ids.assign(t, material);
    if (flags & 0x40)
        for (uint32_t& id : m.material_ids) id = in.id(material_count);
    return m;
}

EnvironmentArrays draw_environment(ByteReader& in) {
    EnvironmentArrays e;
    e.width = in.u8() % 5;
    e.height = in.u8() % 5;
    const uint8_t flags = in.u8();
    e.null_rgb = (flags & 7) == 7;
    e.rgb.assign(static_cast<size_t>(e.width) * e.height * 3, in.f32(FloatKind::Positive));
    const unsigned texels = in.u8() % 4;
    for (unsigned i = 0; i < texels && !e.rgb.empty(); ++i)
        e.rgb[in.u8() % e.rgb.size()] = in.f32(FloatKind::Positive);
    e.strength = in.f32(FloatKind::Positive);
    switch ((flags >> 3) % 4) {
        case 0:
            break;
        case 1:
            e.with_rotation = true;
            e.rotation = {1, 0, 0, 0, 1, 0, 0, 0, 1};
            break;
        case 2: {
            e.with_rotation = true;
            const float angle = in.f32(FloatKind::Signed), c = std::cos(angle), s = std::sin(angle);
            e.rotation = {c, -s, 0, s, c, 0, 0, 0, 1};
            break;
        }
        default:
            e.with_rotation = true;
            for (float& r : e.rotation) r = in.f32(FloatKind::Signed);
            break;
    }
    const unsigned mutations = e.with_rotation ? in.u8() % 3 : 0;
    for (unsigned i = 0; i < mutations; ++i) e.rotation[in.u8() % 9] = in.f32(FloatKind::Signed);
    return e;
}

}  // namespace stratum::fuzz
