#include "lights/lamp_program.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <utility>

namespace stratum {

LampProgram::LampProgram(std::shared_ptr<const ShaderProgram> program, uint32_t register_index,
                         std::vector<std::shared_ptr<const Texture>> textures, bool at_infinity)
    : program_(std::move(program)),
      register_(register_index),
      textures_(std::move(textures)),
      at_infinity_(at_infinity) {}

Rgb LampProgram::scale(float distance, const LightPathState& path) const {
    ShaderRegisters r(*program_);
    write_objectless_inputs(r.data());
    r[shader_input::kRayLength] = at_infinity_ ? FLT_MAX : std::min(distance, FLT_MAX);
    path.write(r.data());
    evaluate(*program_, ShaderEvalContext{program_.get(), &textures_}, r);
    const auto limited = [](float v) { return std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, FLT_MAX); };
    return {limited(r[register_]), limited(r[register_ + 1]), limited(r[register_ + 2])};
}

}  // namespace stratum
