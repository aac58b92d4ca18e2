#include "render_scene/world_baking.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace stratum {

namespace {

Vec3 texel_direction(double col, double row, uint32_t width, uint32_t height) {
    // The environment's mapping (lights/environment_light.h): u = 0.5 - phi/(2 pi) left to
    // right, theta = pi (row + 0.5)/height from +Z down; (col, row) continuous texel coordinates.
    const double u = col / width;
    const double theta = kPi * row / height;
    const double phi = (0.5 - u) * 2.0 * kPi;
    return Vec3(static_cast<float>(std::sin(theta) * std::cos(phi)),
                static_cast<float>(std::sin(theta) * std::sin(phi)), static_cast<float>(std::cos(theta)));
}

// The program's colour at `d`, a value that is NaN, infinite or negative read as 0.
void radiance(const ShaderProgram& program, const ShaderEvalContext& context, ShaderRegisters& r,
              uint32_t color, Vec3 d, double* sum, double weight) {
    std::copy(program.registers.begin(), program.registers.end(), r.data());
    write_world_inputs(d, r.data());
    // Cycles bakes its importance map with PATH_RAY_EMISSION and no path (kernel/bake/bake.h):
    // no ray kind, Ray Depth 0 + 1, the other depths 0.
    kDirectLightPath.write(r.data());
    evaluate(program, context, r);
    for (int k = 0; k < 3; ++k) {
        const float v = r[color + k];
        if (std::isfinite(v) && v > 0.0f) sum[k] += weight * v;
    }
}

// A texel is integrated again with kRefine x kRefine directions weighted by solid angle when
// the brightest of the 2 x 2 samples in it and its 8 neighbours exceeds kContrast times the
// dimmest (and an absolute floor): a feature smaller than the sample spacing, such as the Sky
// Texture's sun disc (0.545 degrees against 0.35-degree texels at 1024 x 512), is then integrated
// to about 1% instead of being caught or missed by 4 points.
constexpr int kRefine = 16;
constexpr float kContrast = 8.0f;

}  // namespace

Environment bake_environment(const ShaderProgram& program,
                             const std::vector<std::shared_ptr<const Texture>>& textures, uint32_t color,
                             uint32_t width, uint32_t height) {
    Environment e;
    e.width = width;
    e.height = height;
    e.rgb.assign(static_cast<size_t>(width) * height * 3, 0.0f);
    // Per texel, the luminance of its brightest and dimmest sample.
    std::vector<float> brightest(static_cast<size_t>(width) * height, 0.0f);
    std::vector<float> dimmest(static_cast<size_t>(width) * height, 0.0f);
    const ShaderEvalContext context{&program, &textures};
    const auto luminance = [](const double* c) {
        return static_cast<float>(kLuminanceR * c[0] + kLuminanceG * c[1] + kLuminanceB * c[2]);
    };
    tbb::parallel_for(uint32_t(0), height, [&](uint32_t row) {
        ShaderRegisters r(program);
        for (uint32_t col = 0; col < width; ++col) {
            double sum[3] = {0.0, 0.0, 0.0};
            float hi = 0.0f, lo = std::numeric_limits<float>::infinity();
            for (int sy = 0; sy < 2; ++sy) {
                for (int sx = 0; sx < 2; ++sx) {
                    double one[3] = {0.0, 0.0, 0.0};
                    radiance(program, context, r, color,
                             texel_direction(col + 0.25 + 0.5 * sx, row + 0.25 + 0.5 * sy, width, height),
                             one, 1.0);
                    for (int k = 0; k < 3; ++k) sum[k] += one[k];
                    hi = std::max(hi, luminance(one));
                    lo = std::min(lo, luminance(one));
                }
            }
            const size_t at = static_cast<size_t>(row) * width + col;
            brightest[at] = hi;
            dimmest[at] = lo;
            float* out = &e.rgb[at * 3];
            for (int k = 0; k < 3; ++k) out[k] = static_cast<float>(std::min(sum[k] * 0.25, 3.0e38));
        }
    });
    tbb::parallel_for(uint32_t(0), height, [&](uint32_t row) {
        ShaderRegisters r(program);
        for (uint32_t col = 0; col < width; ++col) {
            float hi = 0.0f, lo = std::numeric_limits<float>::infinity();
            for (int dy = -1; dy <= 1; ++dy) {
                const int64_t y = static_cast<int64_t>(row) + dy;
                if (y < 0 || y >= static_cast<int64_t>(height)) continue;
                for (int dx = -1; dx <= 1; ++dx) {
                    const size_t x = (col + width + dx) % width;
                    const size_t at = static_cast<size_t>(y) * width + x;
                    hi = std::max(hi, brightest[at]);
                    lo = std::min(lo, dimmest[at]);
                }
            }
            if (!(hi > kContrast * lo + 1e-6f)) continue;
            // Solid-angle weighted: the texel's rows are narrower toward the poles.
            double sum[3] = {0.0, 0.0, 0.0}, weights = 0.0;
            for (int sy = 0; sy < kRefine; ++sy) {
                const double y = row + (sy + 0.5) / kRefine;
                const double w = std::sin(kPi * y / height);
                for (int sx = 0; sx < kRefine; ++sx)
                    radiance(program, context, r, color,
                             texel_direction(col + (sx + 0.5) / kRefine, y, width, height), sum, w);
                weights += w * kRefine;
            }
            float* out = &e.rgb[(static_cast<size_t>(row) * width + col) * 3];
            if (weights > 0.0)
                for (int k = 0; k < 3; ++k) out[k] = static_cast<float>(std::min(sum[k] / weights, 3.0e38));
        }
    });
    return e;
}

}  // namespace stratum
