// Gradient Texture (Blender's ShaderNodeTexGradient), as Cycles' svm/gradient.h (3.4 and 5.0
// agree).
//
// | node     | modes                      | inputs      | outputs            |
// |----------|----------------------------|-------------|--------------------|
// | gradient | 0 type (GradientType, 0..6) | 0 vector (3) | 0 color (3), 1 fac |
//
// With (x, y, z) the vector: Linear x; Quadratic max(x, 0)^2; Easing 3 r^2 - 2 r^3 of r =
// saturate(x); Diagonal (x + y) / 2; Radial atan2(y, x) / 2 pi + 1/2; Quadratic Sphere r^2 and
// Spherical r of r = max(0.999999 - |p|, 0) (the bias makes a unit vector exactly 0). Fac is the
// value saturated (NaN to 0), color is (fac, fac, fac). The types are numbered as Cycles'
// NodeGradientType (svm/types.h).
#include <algorithm>
#include <cmath>

#include "shading/node_registry.h"
#include "shading/pattern_math.h"

namespace stratum {

namespace {

enum GradientType : int32_t {
    Linear,
    Quadratic,
    Easing,
    Diagonal,
    Radial,
    QuadraticSphere,
    Spherical,
    GradientTypeCount
};

float gradient(int32_t type, Vec3 p) {
    constexpr float two_pi = 6.28318530717958647692f;
    switch (type) {
        case Linear:
            return p.x;
        case Quadratic: {
            const float r = std::fmax(p.x, 0.0f);
            return r * r;
        }
        case Easing: {
            const float r = std::fmin(std::fmax(p.x, 0.0f), 1.0f);
            const float t = r * r;
            return 3.0f * t - 2.0f * t * r;
        }
        case Diagonal:
            return (p.x + p.y) * 0.5f;
        case Radial:
            return std::atan2(p.y, p.x) / two_pi + 0.5f;
        default:
            break;
    }
    const float r = std::fmax(0.999999f - std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z), 0.0f);
    return type == QuadraticSphere ? r * r : r;
}

std::string check_gradient(const ShaderNode& n, const ShaderProgram&) {
    return check_mode(n, 0, "type", GradientTypeCount);
}

void evaluate_gradient(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const float f = pattern_math::saturate(gradient(n.modes[0], r.vec3(n.inputs[0])));
    r.set(n.outputs[0], Rgb(f, f, f));
    r[n.outputs[1]] = f;
}

}  // namespace

const NodeRegistration kGradientNode{{.value = 24,
                                      .name = "gradient",
                                      .input_widths = {3},
                                      .output_widths = {3, 1},
                                      .check = check_gradient,
                                      .evaluate = evaluate_gradient}};

}  // namespace stratum
