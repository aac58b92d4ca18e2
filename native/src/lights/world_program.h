// The world's node program run for each ray that leaves the scene, as Cycles shades its
// background (kernel/integrator/shade_background.h, light/background.h): used in place of the
// baked map's value when the program reads the Light Path node, whose outputs a baked map cannot
// hold (docs/cycles_models.md "Light Path node"). The map, baked with Cycles' importance-map
// state, still chooses the directions of light samples and gives their pdf.
//
// | input      | value                                                                      |
// |------------|----------------------------------------------------------------------------|
// | direction  | write_world_inputs: POSITION = d, the normals and INCOMING = -d, ...       |
// | Light Path | a ray that leaves the scene: its kind and depths, one bounce further        |
// |            | (LightPathState::background); a light sample: LightPathState::emission     |
//
// A channel that is NaN, infinite or negative reads 0, as the baked map reads it.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/math.h"
#include "shading/light_path_state.h"
#include "shading/shader_program.h"

namespace stratum {

// Writes the input registers a world program reads for direction `d` (unit): POSITION, and
// (what Cycles' background shader sees) normals and INCOMING = -d, GENERATED and OBJECT = d.
// The Light Path inputs are 0.
void write_world_inputs(Vec3 d, float* registers);

class WorldProgram {
public:
    WorldProgram(std::shared_ptr<const ShaderProgram> program, uint32_t color,
                 std::vector<std::shared_ptr<const Texture>> textures);

    // The world's radiance toward -d (d unit, world space) for a path in state `path`.
    Rgb radiance(Vec3 d, const LightPathState& path) const;

private:
    std::shared_ptr<const ShaderProgram> program_;
    uint32_t color_;
    std::vector<std::shared_ptr<const Texture>> textures_;
};

}  // namespace stratum
