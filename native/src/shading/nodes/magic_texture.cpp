// Magic Texture (Blender's ShaderNodeTexMagic), as Cycles' svm/magic.h (3.4 and 5.0 agree).
//
// | node  | modes                        | inputs                               | outputs            |
// |-------|------------------------------|--------------------------------------|--------------------|
// | magic | 0 turbulence depth (0..10)   | 0 vector (3), 1 scale, 2 distortion  | 0 color (3), 1 fac |
//
// The vector's components are first reduced modulo 2 pi (fmod, keeping the sign), then
// x = sin((px + py + pz) 5 s), y = cos((-px + py - pz) 5 s), z = -cos((-px - py + pz) 5 s); each
// depth level past 0 folds the three through one more sine or cosine (the sequence below, from
// Cycles), scaled by the distortion d; last the colour is 1/2 - (x, y, z) / 2d (d != 0). Fac is
// the colour's mean. Blender limits the depth to 0..10.
#include <cmath>

#include "shading/node_registry.h"

namespace stratum {

namespace {

constexpr int32_t kMaxDepth = 10;

Vec3 magic(Vec3 p, float scale, int32_t depth, float d) {
    constexpr float two_pi = 6.28318530717958647692f;
    const float px = std::fmod(p.x, two_pi), py = std::fmod(p.y, two_pi), pz = std::fmod(p.z, two_pi);
    float x = std::sin((px + py + pz) * 5.0f * scale);
    float y = std::cos((-px + py - pz) * 5.0f * scale);
    float z = -std::cos((-px - py + pz) * 5.0f * scale);
    if (depth > 0) {
        x *= d;
        y *= d;
        z *= d;
        y = -std::cos(x - y + z) * d;
        // Level k (k = 1..9) updates one component from the three; the table is Cycles' order.
        for (int32_t level = 1; level < depth; ++level) {
            switch (level) {
                case 1:
                    x = std::cos(x - y - z) * d;
                    break;
                case 2:
                    z = std::sin(-x - y - z) * d;
                    break;
                case 3:
                    x = -std::cos(-x + y - z) * d;
                    break;
                case 4:
                    y = -std::sin(-x + y + z) * d;
                    break;
                case 5:
                    y = -std::cos(-x + y + z) * d;
                    break;
                case 6:
                    x = std::cos(x + y + z) * d;
                    break;
                case 7:
                    z = std::sin(x + y - z) * d;
                    break;
                case 8:
                    x = -std::cos(-x - y + z) * d;
                    break;
                default:
                    y = -std::sin(x - y + z) * d;
                    break;
            }
        }
    }
    if (d != 0.0f) {
        const float twice = d * 2.0f;
        x /= twice;
        y /= twice;
        z /= twice;
    }
    return {0.5f - x, 0.5f - y, 0.5f - z};
}

std::string check_magic(const ShaderNode& n, const ShaderProgram&) {
    return check_mode(n, 0, "turbulence depth", kMaxDepth + 1);
}

void evaluate_magic(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const Vec3 c = magic(r.vec3(n.inputs[0]), r[n.inputs[1]], n.modes[0], r[n.inputs[2]]);
    r.set(n.outputs[0], c);
    r[n.outputs[1]] = (c.x + c.y + c.z) * (1.0f / 3.0f);
}

}  // namespace

const NodeRegistration kMagicNode{{.value = 25,
                                   .name = "magic",
                                   .input_widths = {3, 1, 1},
                                   .output_widths = {3, 1},
                                   .check = check_magic,
                                   .evaluate = evaluate_magic}};

}  // namespace stratum
