#pragma once

#include "core/math.h"

namespace stratum {

// The frame a tangent-space normal map perturbs the normal in (render_scene/material_texturing.h).
// With the mesh's MikkTSpace corner tangents (Cycles' svm_node_normal_map): the interpolated,
// unnormalised object-space tangent T, B = sign cross(N, T) and normal N, each mapped to world
// space by the instance's normal transform (the cofactor matrix: linear, so mapping T, B and N
// and then combining them is Cycles' combining in object space and mapping the result).
// Without them: the triangle's world dpdu and the UV orientation's sign.
struct TangentFrame {
    bool mikktspace = false;
    Vec3 tangent{0.0f, 0.0f, 0.0f}, bitangent{0.0f, 0.0f, 0.0f}, normal{0.0f, 0.0f, 0.0f};
    Vec3 dpdu{0.0f, 0.0f, 0.0f};  // world-space tangent along +u (0 if no UVs)
    float bitangent_sign = 1.0f;  // -1 where the triangle's UVs are mirrored
};

}  // namespace stratum
