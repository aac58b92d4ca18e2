#include "lights/world_program.h"

#include <cmath>
#include <limits>
#include <utility>

namespace stratum {

void write_world_inputs(Vec3 d, float* r) {
    write_objectless_inputs(r);
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

WorldProgram::WorldProgram(std::shared_ptr<const ShaderProgram> program, uint32_t color,
                           std::vector<std::shared_ptr<const Texture>> textures)
    : program_(std::move(program)), color_(color), textures_(std::move(textures)) {}

Rgb WorldProgram::radiance(Vec3 d, const LightPathState& path) const {
    ShaderRegisters r(*program_);
    write_world_inputs(d, r.data());
    path.write(r.data());
    evaluate(*program_, ShaderEvalContext{program_.get(), &textures_}, r);
    const auto limited = [](float v) { return std::isfinite(v) && v > 0.0f ? v : 0.0f; };
    return {limited(r[color_]), limited(r[color_ + 1]), limited(r[color_ + 2])};
}

}  // namespace stratum
