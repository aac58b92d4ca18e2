// Vector Math node (Blender's ShaderNodeVectorMath).
//
// | node        | modes                                     | inputs                 | outputs           |
// |-------------|-------------------------------------------|------------------------|-------------------|
// | vector_math | 0 operation (VectorOperation), 1 revision | a 3, b 3, c 3, scale 1 | vector 3, value 1 |
//
// Operations are numbered as Cycles' NodeVectorMathType (kernel/svm/types.h): ADD 0 ... REFLECT 6
// ... SCALE 10 ... MULTIPLY_ADD 26, POWER 27, SIGN 28 (the last two new in Blender 5.0). The
// formulas are those of svm_vector_math (kernel/svm/math_util.h). An operation with a float
// result writes it to `value` and zero to `vector`; the others write zero to `value`.
//
// Revision (mode 1) selects the Cycles generation where the kernels differ:
//   0  Blender 3.x to 4.2: Reflect and Refract normalise b with a plain normalize (a zero b
//      gives NaN); Modulo is fmodf and Wrap wrapf per component.
//   1  Blender 4.3 to 4.5: Reflect and Refract use safe_normalize (a zero b stays zero).
//   2  Blender 5.0+: as 1, and Modulo is a - trunc(a / b) * b (the SSE fmod of
//      util/math_float3.h), Wrap the floored modulo of (value - min) by (max - min), plus min.
// Those multiply-subtracts are fused as in Cycles' AVX2 kernel (measured against Blender 3.4 and
// 5.0 renders: 1e9 wrapped to [0, 3) is -32 in both).
#include <algorithm>
#include <cmath>

#include "shading/node_registry.h"

namespace stratum {

namespace {

enum VectorOperation : int32_t {
    Add,
    Subtract,
    Multiply,
    Divide,
    CrossProduct,
    Project,
    Reflect,
    DotProduct,
    Distance,
    Length,
    Scale,
    Normalize,
    Snap,
    Floor,
    Ceil,
    Modulo,
    Fraction,
    Absolute,
    Minimum,
    Maximum,
    Wrap,
    Sine,
    Cosine,
    Tangent,
    Refract,
    Faceforward,
    MultiplyAdd,
    Power,
    Sign,
    VectorOperationCount
};

enum Revision : int32_t { Blender34, Blender43, Blender50, RevisionCount };

template <typename F>
Vec3 each(Vec3 a, F f) {
    return {f(a.x), f(a.y), f(a.z)};
}

template <typename F>
Vec3 each(Vec3 a, Vec3 b, F f) {
    return {f(a.x, b.x), f(a.y, b.y), f(a.z, b.z)};
}

template <typename F>
Vec3 each(Vec3 a, Vec3 b, Vec3 c, F f) {
    return {f(a.x, b.x, c.x), f(a.y, b.y, c.y), f(a.z, b.z, c.z)};
}

float divide_or_zero(float a, float b) { return b != 0.0f ? a / b : 0.0f; }

// The length-normalised vector, or the vector itself when its length is 0 (safe_normalize).
Vec3 unit_or_same(Vec3 v) {
    const float l = length(v);
    return l != 0.0f ? v * (1.0f / l) : v;
}

// a raised to b; a negative base takes integer exponents only, 0^0 is 1 (safe_powf).
float power(float a, float b) {
    if (a < 0.0f && b != static_cast<float>(static_cast<int>(b))) return 0.0f;
    if (b == 0.0f) return 1.0f;
    if (a == 0.0f) return 0.0f;
    return std::pow(a, b);
}

Vec3 refraction(Vec3 incident, Vec3 n, float eta) {
    const float cos_i = dot(n, incident);
    const float k = 1.0f - eta * eta * (1.0f - cos_i * cos_i);
    if (k < 0.0f) return {};
    return eta * incident - (eta * cos_i + std::sqrt(k)) * n;
}

// Cycles' CPU kernels (built with FMA for AVX2) fuse the multiply-subtract of its modulo and
// wrap: the remainder is rounded once, which matters when the quotient is large (1e9 mod 3 is
// -32 there, 1 by fmodf). std::fma rounds as they do.
float wrap_3x(float value, float max, float min) {
    const float range = max - min;
    return range != 0.0f ? std::fma(-range, std::floor((value - min) / range), value) : min;
}

float wrap_5x(float value, float max, float min) {
    const float offset = value - min, range = max - min;
    return (range != 0.0f ? std::fma(-std::floor(offset / range), range, offset) : 0.0f) + min;
}

float truncated_modulo_5x(float a, float b) { return b != 0.0f ? std::fma(-std::trunc(a / b), b, a) : 0.0f; }

// Returns the vector result and writes a float result to `value`.
Vec3 vector_math(int32_t op, int32_t revision, Vec3 a, Vec3 b, Vec3 c, float scale, float& value) {
    value = 0.0f;
    const auto unit_b = [&] { return revision == Blender34 ? normalize(b) : unit_or_same(b); };
    switch (op) {
        case Add:
            return a + b;
        case Subtract:
            return a - b;
        case Multiply:
            return each(a, b, [](float x, float y) { return x * y; });
        case Divide:
            return each(a, b, divide_or_zero);
        case CrossProduct:
            return cross(a, b);
        case Project: {
            const float l2 = dot(b, b);
            return l2 != 0.0f ? b * (dot(a, b) / l2) : Vec3{};
        }
        case Reflect: {
            const Vec3 n = unit_b();
            return a - 2.0f * n * dot(a, n);
        }
        case Refract:
            return refraction(a, unit_b(), scale);
        case Faceforward:
            return dot(c, b) < 0.0f ? a : -a;
        case MultiplyAdd:
            return each(a, b, c, [](float x, float y, float z) { return x * y + z; });
        case DotProduct:
            value = dot(a, b);
            return {};
        case Distance:
            value = length(a - b);
            return {};
        case Length:
            value = length(a);
            return {};
        case Scale:
            return a * scale;
        case Normalize:
            return unit_or_same(a);
        case Snap:
            return each(a, b, [](float x, float y) { return std::floor(divide_or_zero(x, y)) * y; });
        case Floor:
            return each(a, [](float x) { return std::floor(x); });
        case Ceil:
            return each(a, [](float x) { return std::ceil(x); });
        case Modulo:
            if (revision == Blender50) return each(a, b, truncated_modulo_5x);
            return each(a, b, [](float x, float y) { return y != 0.0f ? std::fmod(x, y) : 0.0f; });
        case Wrap:
            return each(a, b, c, revision == Blender50 ? wrap_5x : wrap_3x);
        case Fraction:
            return each(a, [](float x) { return x - std::floor(x); });
        case Absolute:
            return each(a, [](float x) { return std::fabs(x); });
        case Power:
            return each(a, b, power);
        case Sign:
            return each(a, [](float x) { return x == 0.0f ? 0.0f : (x > 0.0f ? 1.0f : -1.0f); });
        case Minimum:
            return each(a, b, [](float x, float y) { return x < y ? x : y; });
        case Maximum:
            return each(a, b, [](float x, float y) { return x > y ? x : y; });
        case Sine:
            return each(a, [](float x) { return std::sin(x); });
        case Cosine:
            return each(a, [](float x) { return std::cos(x); });
        case Tangent:
            return each(a, [](float x) { return std::tan(x); });
        default:
            return {};
    }
}

std::string check_vector_math(const ShaderNode& n, const ShaderProgram&) {
    std::string e = check_mode(n, 0, "operation", VectorOperationCount);
    return e.empty() ? check_mode(n, 1, "revision", RevisionCount) : e;
}

void evaluate_vector_math(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    float value = 0.0f;
    const Vec3 v = vector_math(n.modes[0], n.modes[1], r.vec3(n.inputs[0]), r.vec3(n.inputs[1]),
                               r.vec3(n.inputs[2]), r[n.inputs[3]], value);
    r.set(n.outputs[0], v);
    r[n.outputs[1]] = value;
}

}  // namespace

const NodeRegistration kVectorMathNode{{.value = 1,
                                        .name = "vector_math",
                                        .input_widths = {3, 3, 3, 1},
                                        .output_widths = {3, 1},
                                        .check = check_vector_math,
                                        .evaluate = evaluate_vector_math}};

}  // namespace stratum
