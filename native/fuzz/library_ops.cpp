// The entry points that need no scene: sampler points, hemisphere warps, the blue-noise
// texture, dimension names, the model listings and vertex normals. Their outputs have
// mathematical invariants: sample values in [0, 1), unit directions in the upper hemisphere with
// finite densities, unit (or, at the origin, zero) normals that no thread count changes.
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "checked_call.h"
#include "describe.h"
#include "descriptors.h"
#include "program.h"

namespace stratum::fuzz {

namespace {

void sampler_points(ByteReader& in) {
    static const std::vector<const char*> samplers = setting_choice_names("sampler");
    const std::string sampler = in.name(samplers);
    const auto samples = static_cast<uint32_t>(in.i64());
    const uint32_t seed = in.u32();
    const auto width = static_cast<uint32_t>(in.i64()), height = static_cast<uint32_t>(in.i64());
    const auto pixel_x = static_cast<uint32_t>(in.i64()), pixel_y = static_cast<uint32_t>(in.i64());
    // Dimensions well past the camera block, in the bounce blocks, and at the 32-bit edge.
    const uint32_t dim_a = in.u8() == 255 ? in.u32() : in.u16() % 512;
    const uint32_t dim_b = in.u8() % 4 == 0 ? dim_a + 1 : (in.u8() == 255 ? in.u32() : in.u16() % 512);
    const uint32_t count = in.u8();
    std::vector<float> xy(2 * static_cast<size_t>(count) + 2);
    const StratumStatus status = checked(
        "stratum_sampler_points",
        [&] {
            return stratum_sampler_points(sampler.c_str(), samples, seed, width, height, pixel_x, pixel_y,
                                          dim_a, dim_b, count, xy.data());
        },
        [&] {
            return describe_string(sampler.c_str()) + ", " + std::to_string(samples) + ", " +
                   std::to_string(seed) + ", " + std::to_string(width) + ", " + std::to_string(height) +
                   ", " + std::to_string(pixel_x) + ", " + std::to_string(pixel_y) + ", " +
                   std::to_string(dim_a) + ", " + std::to_string(dim_b) + ", " + std::to_string(count) +
                   ", xy";
        });
    if (status != STRATUM_OK) return;
    for (size_t i = 0; i < 2 * static_cast<size_t>(count); ++i) {
        if (!(xy[i] >= 0.0f && xy[i] < 1.0f))
            finding("stratum_sampler_points: sampler '" + sampler + "' value " + std::to_string(i) + " = " +
                    describe_float(xy[i]) + " is outside [0, 1)");
    }
}

void warp_hemisphere(ByteReader& in) {
    static const std::vector<const char*> distributions = setting_choice_names("hemisphere");
    const std::string distribution = in.name(distributions);
    const uint32_t count = in.u8() % 9;
    std::vector<float> uv(2 * static_cast<size_t>(count));
    for (float& u : uv) u = in.f32(FloatKind::Unit);
    std::vector<float> xyz(3 * static_cast<size_t>(count)), pdf(count);
    const bool with_pdf = in.flag();
    const StratumStatus status = checked(
        "stratum_warp_hemisphere",
        [&] {
            return stratum_warp_hemisphere(distribution.c_str(), uv.data(), count, xyz.data(),
                                           with_pdf ? pdf.data() : nullptr);
        },
        [&] {
            return describe_string(distribution.c_str()) + ", (float[])" +
                   describe_floats(uv.data(), uv.size()) + ", " + std::to_string(count) + ", xyz, " +
                   (with_pdf ? "pdf" : "NULL");
        });
    if (status != STRATUM_OK) return;
    for (uint32_t i = 0; i < count; ++i) {
        const float x = xyz[3 * i], y = xyz[3 * i + 1], z = xyz[3 * i + 2];
        const float length = std::sqrt(x * x + y * y + z * z);
        const bool ok = std::isfinite(length) && std::abs(length - 1.0f) < 1e-3f && z >= -1e-6f &&
                        (!with_pdf || (std::isfinite(pdf[i]) && pdf[i] >= 0.0f));
        if (!ok)
            finding("stratum_warp_hemisphere '" + distribution + "': uv " + describe_floats(&uv[2 * i], 2) +
                    " gives " + describe_floats(&xyz[3 * i], 3) +
                    (with_pdf ? ", pdf " + describe_float(pdf[i]) : ""));
    }
}

void bluenoise(ByteReader& in) {
    constexpr uint32_t kTexels = 128 * 128;
    const uint8_t which = in.u8() % 4;
    const uint32_t count = which == 0 ? kTexels - 1 : which == 1 ? kTexels + 1 : kTexels;
    std::vector<float> texels(kTexels + 1);
    if (checked(
            "stratum_bluenoise_texture", [&] { return stratum_bluenoise_texture(texels.data(), count); },
            [&] { return "out, " + std::to_string(count); }) != STRATUM_OK)
        return;
    for (uint32_t i = 0; i < kTexels; ++i) {
        if (!(texels[i] > 0.0f && texels[i] < 1.0f))
            finding("stratum_bluenoise_texture: texel " + std::to_string(i) + " = " +
                    describe_float(texels[i]));
    }
}

}  // namespace

void op_sampling(ByteReader& in, ProgramState&) {
    switch (in.u8() % 4) {
        case 0:
            sampler_points(in);
            break;
        case 1:
            warp_hemisphere(in);
            break;
        case 2:
            bluenoise(in);
            break;
        default: {
            const uint32_t dimension = in.u8() == 255 ? in.u32() : in.u16();
            const char* name = nullptr;
            if (checked(
                    "stratum_dimension_name", [&] { return stratum_dimension_name(dimension, &name); },
                    [&] { return std::to_string(dimension) + ", &name"; }) == STRATUM_OK &&
                (!name || name[0] == '\0'))
                finding("stratum_dimension_name(" + std::to_string(dimension) + ") gave no name");
            break;
        }
    }
}

void op_models(ByteReader& in, ProgramState&) {
    // Kinds 0..2 (the last, shader nodes, was the invalid one before nodes were listed: committed
    // inputs keep their draws), and from selector 240 on -2..13.
    const int32_t kind = draw_enum(in, STRATUM_MODEL_SHADER_NODE + 1);
    const int32_t count = stratum_model_count(kind);
    const auto index = static_cast<int32_t>(in.i64());
    const char* name = nullptr;
    int32_t value = -1;
    const StratumStatus status = checked(
        "stratum_model_entry", [&] { return stratum_model_entry(kind, index, &name, &value); },
        [&] { return std::to_string(kind) + ", " + std::to_string(index) + ", &name, &value"; });
    const bool valid = count >= 0 && index >= 0 && index < count;
    if ((status == STRATUM_OK) != valid)
        finding("stratum_model_entry(" + std::to_string(kind) + ", " + std::to_string(index) + ") returned " +
                std::to_string(status) + " for a kind of " + std::to_string(count) + " models");
    if (status == STRATUM_OK && !(name && name[0] && value >= 0))
        finding("stratum_model_entry(" + std::to_string(kind) + ", " + std::to_string(index) +
                ") gave an empty name or a negative value");
    if (!stratum_version() || !stratum_version()[0]) finding("stratum_version() is empty");
}

// A polygon mesh of up to 8 vertices, 4 faces and 16 corners: each face's start and size a
// small number or (byte 255) a raw 32-bit one, corner vertices up to 2 past the vertex count,
// then a thread count (0-3, or raw) and a byte whose bits pass NULL for positions (1), the face
// arrays (2), corner_vertices (4) or out_normals (8). An accepted call must give finite normals
// of length 1, or 0 for a vertex at the origin, and the same bits on one thread.
void op_vertex_normals(ByteReader& in, ProgramState&) {
    const uint32_t n_vert = in.u8() % 9u;
    std::vector<float> positions(3 * size_t{n_vert});
    for (float& x : positions) x = in.f32(FloatKind::Signed);
    const uint32_t n_face = in.u8() % 5u;
    std::vector<uint32_t> starts(n_face), sizes(n_face);
    std::vector<float> face_normals(3 * size_t{n_face});
    for (uint32_t f = 0; f < n_face; ++f) {
        const uint8_t start = in.u8(), size = in.u8();
        starts[f] = start == 255 ? in.u32() : start % 16u;
        sizes[f] = size == 255 ? in.u32() : size % 8u;
        for (int k = 0; k < 3; ++k) face_normals[3 * f + k] = in.f32(FloatKind::Signed);
    }
    const uint32_t n_corner = in.u8() % 17u;
    std::vector<uint32_t> corners(n_corner);
    for (uint32_t& v : corners) v = in.u8() % (n_vert + 3u);
    const uint8_t threads_byte = in.u8();
    const uint32_t threads = threads_byte == 255 ? in.u32() : threads_byte % 4u;
    const uint8_t nulls = in.u8();
    const float* p = (nulls & 1) ? nullptr : positions.data();
    const uint32_t* face_starts = (nulls & 2) ? nullptr : starts.data();
    const uint32_t* face_sizes = (nulls & 2) ? nullptr : sizes.data();
    const float* normals_in = (nulls & 2) ? nullptr : face_normals.data();
    const uint32_t* corner_vertices = (nulls & 4) ? nullptr : corners.data();
    std::vector<float> out(3 * size_t{n_vert}), one_thread(out.size());
    float* out_normals = (nulls & 8) ? nullptr : out.data();
    const auto call = [&](uint32_t thread_count, float* into) {
        return stratum_vertex_normals(n_vert, p, n_face, face_starts, face_sizes, normals_in, n_corner,
                                      corner_vertices, thread_count, into);
    };
    const StratumStatus status = checked(
        "stratum_vertex_normals", [&] { return call(threads, out_normals); },
        [&] {
            return std::to_string(n_vert) + ", (float[])" +
                   (p ? describe_floats(p, positions.size()) : "NULL") + ", " + std::to_string(n_face) +
                   ", (uint32_t[])" + describe_uints(face_starts, n_face) + ", (uint32_t[])" +
                   describe_uints(face_sizes, n_face) + ", (float[])" +
                   (normals_in ? describe_floats(normals_in, face_normals.size()) : "NULL") + ", " +
                   std::to_string(n_corner) + ", (uint32_t[])" + describe_uints(corner_vertices, n_corner) +
                   ", " + std::to_string(threads) + ", " + (out_normals ? "out" : "NULL");
        });
    if (status != STRATUM_OK) return;
    for (uint32_t v = 0; v < n_vert; ++v) {
        const float* n = &out[3 * v];
        const float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!(std::abs(length - 1.0f) < 1e-5f ||
              (length == 0.0f && positions[3 * v] == 0.0f && positions[3 * v + 1] == 0.0f &&
               positions[3 * v + 2] == 0.0f)))
            finding("stratum_vertex_normals: vertex " + std::to_string(v) + " normal " +
                    describe_floats(n, 3));
    }
    if (checked(
            "stratum_vertex_normals", [&] { return call(1, one_thread.data()); },
            [] { return std::string("the same arrays, 1, one_thread"); }) != STRATUM_OK ||
        (!out.empty() && std::memcmp(out.data(), one_thread.data(), out.size() * sizeof(float)) != 0))
        finding("stratum_vertex_normals: " + std::to_string(threads) + " threads and 1 thread differ");
}

}  // namespace stratum::fuzz
