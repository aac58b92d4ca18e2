#include "describe.h"

#include <cmath>
#include <cstdio>

namespace stratum::fuzz {

namespace {

std::string field(const char* name, const std::string& value) {
    return std::string(".") + name + " = " + value;
}

std::string integer(int64_t v) { return std::to_string(v); }

// `{a, b, c}` of n floats, or `NULL` for a missing array.
std::string array_or_null(const float* v, size_t n) { return v ? describe_floats(v, n) : "NULL"; }

std::string indices(const uint32_t* v, size_t n) {
    if (!v) return "NULL";
    std::string s = "{";
    for (size_t i = 0; i < n; ++i) s += (i ? ", " : "") + std::to_string(v[i]);
    return s + "}";
}

}  // namespace

std::string describe_float(float v) {
    if (std::isnan(v)) return std::signbit(v) ? "-NAN" : "NAN";
    if (std::isinf(v)) return v > 0 ? "INFINITY" : "-INFINITY";
    // 9 significant digits round-trip every float exactly.
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.9gf", static_cast<double>(v));
    std::string s = buffer;
    // "1f" is not a C float literal: give integral values a decimal point.
    if (s.find_first_of(".e") == std::string::npos) s.insert(s.size() - 1, ".0");
    return s;
}

std::string describe_uints(const uint32_t* v, size_t n) { return indices(v, n); }

std::string describe_floats(const float* v, size_t n) {
    std::string s = "{";
    for (size_t i = 0; i < n; ++i) s += (i ? ", " : "") + describe_float(v[i]);
    return s + "}";
}

std::string describe_string(const char* s) {
    if (!s) return "NULL";
    std::string out = "\"";
    for (const char* p = s; *p; ++p) {
        const auto c = static_cast<unsigned char>(*p);
        if (c == '"' || c == '\\') {
            out += '\\';
            out += static_cast<char>(c);
        } else if (c < 32 || c >= 127) {
            char buffer[8];
            std::snprintf(buffer, sizeof buffer, "\\x%02x\"\"", c);
            out += buffer;
        } else {
            out += static_cast<char>(c);
        }
    }
    return out + "\"";
}

std::string describe(const StratumMaterialDesc& d) {
    return "{" + field("model", integer(d.model)) + ", " +
           field("base_color", describe_floats(d.base_color, 3)) + ", " +
           field("roughness", describe_float(d.roughness)) + ", " +
           field("metallic", describe_float(d.metallic)) + ", " +
           field("specular", describe_float(d.specular)) + ", " + field("ior", describe_float(d.ior)) + ", " +
           field("emission", describe_floats(d.emission, 3)) + ", " +
           field("distribution", integer(d.distribution)) + ", " +
           field("transmission", describe_float(d.transmission)) + ", " +
           field("coat", describe_float(d.coat)) + ", " +
           field("coat_roughness", describe_float(d.coat_roughness)) + ", " +
           field("coat_ior", describe_float(d.coat_ior)) + ", " +
           field("coat_tint", describe_floats(d.coat_tint, 3)) + ", " +
           field("bump_shadowing", integer(d.bump_shadowing)) + "}";
}

std::string describe(const StratumCameraDesc& d) {
    return "{" + field("lens_mm", describe_float(d.lens_mm)) + ", " +
           field("sensor_width_mm", describe_float(d.sensor_width_mm)) + ", " +
           field("sensor_height_mm", describe_float(d.sensor_height_mm)) + ", " +
           field("sensor_fit", integer(d.sensor_fit)) + ", " + field("shift_x", describe_float(d.shift_x)) +
           ", " + field("shift_y", describe_float(d.shift_y)) + ", " +
           field("clip_start", describe_float(d.clip_start)) + ", " +
           field("clip_end", describe_float(d.clip_end)) + ", " +
           field("transform", describe_floats(d.transform, 16)) + ", " + field("type", integer(d.type)) +
           ", " + field("ortho_scale", describe_float(d.ortho_scale)) + ", " +
           field("aperture_radius", describe_float(d.aperture_radius)) + ", " +
           field("focus_distance", describe_float(d.focus_distance)) + ", " +
           field("aperture_blades", integer(d.aperture_blades)) + ", " +
           field("aperture_rotation", describe_float(d.aperture_rotation)) + ", " +
           field("latitude_min", describe_float(d.latitude_min)) + ", " +
           field("latitude_max", describe_float(d.latitude_max)) + ", " +
           field("longitude_min", describe_float(d.longitude_min)) + ", " +
           field("longitude_max", describe_float(d.longitude_max)) + "}";
}

std::string describe(const StratumLightDesc& d) {
    return "{" + field("type", integer(d.type)) + ", " + field("color", describe_floats(d.color, 3)) + ", " +
           field("strength", describe_float(d.strength)) + ", " + field("radius", describe_float(d.radius)) +
           ", " + field("angle", describe_float(d.angle)) + ", " + field("size_x", describe_float(d.size_x)) +
           ", " + field("size_y", describe_float(d.size_y)) + ", " +
           field("transform", describe_floats(d.transform, 16)) + ", " +
           field("spot_size", describe_float(d.spot_size)) + ", " +
           field("spot_blend", describe_float(d.spot_blend)) + ", " +
           field("visibility", integer(d.visibility)) + ", " + field("spread", describe_float(d.spread)) +
           "}";
}

std::string describe(const StratumInstanceDesc& d) {
    return "{" + field("mesh_id", integer(d.mesh_id)) + ", " +
           field("transform", describe_floats(d.transform, 16)) + ", " +
           field("transform_end", describe_floats(d.transform_end, 16)) + ", " +
           field("motion", integer(d.motion)) + ", " + field("visibility", integer(d.visibility)) + ", " +
           field("holdout", integer(d.holdout)) + ", " + field("pass_index", integer(d.pass_index)) + "}";
}

std::string describe(const StratumMeshDesc& d) {
    const size_t v = d.vertex_count, t = d.triangle_count;
    return "{" + field("positions", array_or_null(d.positions, 3 * v)) + ", " +
           field("vertex_count", integer(v)) + ", " + field("triangles", indices(d.triangles, 3 * t)) + ", " +
           field("triangle_count", integer(t)) + ", " +
           field("corner_normals", array_or_null(d.corner_normals, 9 * t)) + ", " +
           field("corner_uvs", array_or_null(d.corner_uvs, 6 * t)) + ", " +
           field("material_ids", indices(d.material_ids, t)) + ", " +
           field("vertex_normals", array_or_null(d.vertex_normals, 3 * v)) + ", " +
           field("corner_tangents", array_or_null(d.corner_tangents, 12 * t)) + "}";
}

std::string describe(const StratumTextureDesc& d) {
    const size_t n = d.pixels ? static_cast<size_t>(d.width) * d.height * d.channels : 0;
    std::string file = "NULL";
    if (d.file_data) {
        // The bytes as a C string literal of hex escapes.
        file = "\"";
        const auto* bytes = static_cast<const unsigned char*>(d.file_data);
        for (size_t i = 0; i < d.file_size; ++i) {
            char buffer[8];
            std::snprintf(buffer, sizeof buffer, "\\x%02x", bytes[i]);
            file += buffer;
        }
        file += "\"";
    }
    return "{" + field("path", describe_string(d.path)) + ", " + field("file_data", file) + ", " +
           field("file_size", integer(static_cast<int64_t>(d.file_size))) + ", " +
           field("file_name", describe_string(d.file_name)) + ", " +
           field("pixels", array_or_null(d.pixels, n)) + ", " + field("width", integer(d.width)) + ", " +
           field("height", integer(d.height)) + ", " + field("channels", integer(d.channels)) + ", " +
           field("color_space", describe_string(d.color_space)) + ", " +
           field("ocio_config", describe_string(d.ocio_config)) + ", " +
           field("interpolation", integer(d.interpolation)) + ", " +
           field("extension", integer(d.extension)) + "}";
}

std::string describe(const StratumTextureBinding& d) {
    return "{" + field("material_id", integer(d.material_id)) + ", " +
           field("closure_index", integer(d.closure_index)) + ", " + field("param", integer(d.param)) + ", " +
           field("texture_id", integer(d.texture_id)) + ", " + field("channel", integer(d.channel)) + ", " +
           field("scale", describe_float(d.scale)) + ", " + field("offset", describe_float(d.offset)) + ", " +
           field("emission_strength", describe_float(d.emission_strength)) + "}";
}

}  // namespace stratum::fuzz
