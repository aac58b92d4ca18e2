#include "render_scene/world_baking.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace stratum {

void write_world_inputs(Vec3 d, float* r) {
    std::fill(r, r + kShaderInputRegisters, 0.0f);
    const auto put = [&](uint32_t at, Vec3 v) {
        r[at] = v.x;
        r[at + 1] = v.y;
        r[at + 2] = v.z;
    };
    put(shader_input::kPosition, d);
    put(shader_input::kNormal, -d);
    put(shader_input::kTrueNormal, -d);
    put(shader_input::kIncoming, -d);
    put(shader_input::kGenerated, d);
    put(shader_input::kObject, d);
    put(shader_input::kObjectNormal, -d);
    put(shader_input::kReflection, d);
    put(shader_input::kObjectColor, Vec3(1.0f, 1.0f, 1.0f));
    r[shader_input::kObjectAlpha] = 1.0f;
    r[shader_input::kRayLength] = std::numeric_limits<float>::infinity();
}

Environment bake_environment(const ShaderProgram& program,
                             const std::vector<std::shared_ptr<const Texture>>& textures, uint32_t color,
                             uint32_t width, uint32_t height) {
    Environment e;
    e.width = width;
    e.height = height;
    e.rgb.assign(static_cast<size_t>(width) * height * 3, 0.0f);
    const ShaderEvalContext context{&program, &textures};
    tbb::parallel_for(uint32_t(0), height, [&](uint32_t row) {
        ShaderRegisters r(program);
        for (uint32_t col = 0; col < width; ++col) {
            double sum[3] = {0.0, 0.0, 0.0};
            for (int sy = 0; sy < 2; ++sy) {
                for (int sx = 0; sx < 2; ++sx) {
                    // The environment's mapping (lights/environment_light.h): u = 0.5 - phi/(2 pi)
                    // left to right, theta = pi (row + 0.5)/height from +Z down.
                    const double u = (col + 0.25 + 0.5 * sx) / width;
                    const double theta = kPi * (row + 0.25 + 0.5 * sy) / height;
                    const double phi = (0.5 - u) * 2.0 * kPi;
                    const Vec3 d(static_cast<float>(std::sin(theta) * std::cos(phi)),
                                 static_cast<float>(std::sin(theta) * std::sin(phi)),
                                 static_cast<float>(std::cos(theta)));
                    std::copy(program.registers.begin(), program.registers.end(), r.data());
                    write_world_inputs(d, r.data());
                    evaluate(program, context, r);
                    for (int k = 0; k < 3; ++k) {
                        const float v = r[color + k];
                        if (std::isfinite(v) && v > 0.0f) sum[k] += v;
                    }
                }
            }
            float* out = &e.rgb[(static_cast<size_t>(row) * width + col) * 3];
            for (int k = 0; k < 3; ++k) out[k] = static_cast<float>(std::min(sum[k] * 0.25, 3.0e38));
        }
    });
    return e;
}

}  // namespace stratum
