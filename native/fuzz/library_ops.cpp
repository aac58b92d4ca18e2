// The entry points that need no scene: sampler points, hemisphere warps, the blue-noise
// texture, dimension names and the model listings. Their outputs have mathematical invariants:
// sample values in [0, 1), unit directions in the upper hemisphere with finite densities.
#include <cmath>
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
    const int32_t kind = draw_enum(in, STRATUM_MODEL_CLOSURE + 2);
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

}  // namespace stratum::fuzz
