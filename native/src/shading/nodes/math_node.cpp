// Math node (Blender's ShaderNodeMath) and Copy, the compiler's reroute and socket conversion.
//
// | node | modes                                  | inputs        | outputs |
// |------|----------------------------------------|---------------|---------|
// | math | 0 operation (MathOperation), 1 clamp   | a, b, c       | value   |
// | copy | 0 CopyKind, 1 luminance weights of     | value (1 / 3) | value   |
// |      |   ColorToFloat (node_registry.h)       |               |         |
//
// Operations and their guards as Cycles' svm_math (kernel/svm/math_util.h, identical in 3.4 and
// 5.0 except FLOORED_MODULO, new in 4.2, which 3.4 files cannot hold): a division by 0, a power of
// a negative base to a fractional exponent, a logarithm of a non-positive value give 0; arcsine
// and arccosine clamp their argument to [-1, 1]; clamp (the node's Clamp option) saturates the
// result to [0, 1]. Colour to float is Cycles' rgb_to_gray (the luminance with the colour
// configuration's weights) and vector to float the mean of the components (svm/convert.h).
#include <algorithm>
#include <cmath>
#include <limits>

#include "shading/node_registry.h"

namespace stratum {

namespace {

enum MathOperation : int32_t {
    Add,
    Subtract,
    Multiply,
    Divide,
    Sine,
    Cosine,
    Tangent,
    Arcsine,
    Arccosine,
    Arctangent,
    Power,
    Logarithm,
    Minimum,
    Maximum,
    Round,
    LessThan,
    GreaterThan,
    Modulo,
    Absolute,
    Arctan2,
    Floor,
    Ceil,
    Fraction,
    Sqrt,
    InverseSqrt,
    Sign,
    Exponent,
    Radians,
    Degrees,
    Sinh,
    Cosh,
    Tanh,
    Trunc,
    Snap,
    Wrap,
    Compare,
    MultiplyAdd,
    PingPong,
    SmoothMin,
    SmoothMax,
    FlooredModulo,
    MathOperationCount
};

float safe_divide(float a, float b) { return b != 0.0f ? a / b : 0.0f; }

float compatible_pow(float x, float y) {
    if (y == 0.0f) return 1.0f;  // x^0 = 1, 0^0 included
    if (x == 0.0f) return 0.0f;
    return std::pow(x, y);
}

float safe_pow(float a, float b) {
    // A negative base takes integer exponents only (float_to_int truncates).
    if (a < 0.0f && b != static_cast<float>(static_cast<int>(b))) return 0.0f;
    return compatible_pow(a, b);
}

float fract(float x) { return x - std::floor(x); }

float smooth_min(float a, float b, float k) {
    if (k != 0.0f) {
        const float h = std::max(k - std::fabs(a - b), 0.0f) / k;
        return std::min(a, b) - h * h * h * k * (1.0f / 6.0f);
    }
    return std::min(a, b);
}

float math(int32_t op, float a, float b, float c) {
    constexpr float pi = 3.14159265358979323846f;
    switch (op) {
        case Add:
            return a + b;
        case Subtract:
            return a - b;
        case Multiply:
            return a * b;
        case Divide:
            return safe_divide(a, b);
        case Power:
            return safe_pow(a, b);
        case Logarithm:
            return (a <= 0.0f || b <= 0.0f) ? 0.0f : safe_divide(std::log(a), std::log(b));
        case Sqrt:
            return std::sqrt(std::max(a, 0.0f));
        case InverseSqrt:
            return a > 0.0f ? 1.0f / std::sqrt(a) : 0.0f;
        case Absolute:
            return std::fabs(a);
        case Radians:
            return a * (pi / 180.0f);
        case Degrees:
            return a * (180.0f / pi);
        case Minimum:
            return std::fmin(a, b);
        case Maximum:
            return std::fmax(a, b);
        case LessThan:
            return a < b ? 1.0f : 0.0f;
        case GreaterThan:
            return a > b ? 1.0f : 0.0f;
        case Round:
            return std::floor(a + 0.5f);
        case Floor:
            return std::floor(a);
        case Ceil:
            return std::ceil(a);
        case Fraction:
            return a - std::floor(a);
        case Modulo:
            return b != 0.0f ? std::fmod(a, b) : 0.0f;
        case FlooredModulo:
            // Cycles' CPU kernels contract this and Wrap's product and difference into one fused
            // multiply-add: Wrap(1e9, 3, 0) renders -32 in 3.4 and 5.0, not 1 (measured).
            return b != 0.0f ? std::fma(-std::floor(a / b), b, a) : 0.0f;
        case Trunc:
            return a >= 0.0f ? std::floor(a) : std::ceil(a);
        case Snap:
            return std::floor(safe_divide(a, b)) * b;
        case Wrap: {
            // wrapf(value, max, min)
            const float range = b - c;
            return range != 0.0f ? std::fma(-range, std::floor((a - c) / range), a) : c;
        }
        case PingPong:
            return b != 0.0f ? std::fabs(fract((a - b) / (b * 2.0f)) * b * 2.0f - b) : 0.0f;
        case Sine:
            return std::sin(a);
        case Cosine:
            return std::cos(a);
        case Tangent:
            return std::tan(a);
        case Sinh:
            return std::sinh(a);
        case Cosh:
            return std::cosh(a);
        case Tanh:
            return std::tanh(a);
        case Arcsine:
            return std::asin(std::clamp(a, -1.0f, 1.0f));
        case Arccosine:
            return std::acos(std::clamp(a, -1.0f, 1.0f));
        case Arctangent:
            return std::atan(a);
        case Arctan2:
            return std::atan2(a, b);
        case Sign:
            return a == 0.0f ? 0.0f : (a > 0.0f ? 1.0f : -1.0f);
        case Exponent:
            return std::exp(a);
        case Compare:
            return (a == b || std::fabs(a - b) <= std::fmax(c, std::numeric_limits<float>::epsilon())) ? 1.0f
                                                                                                       : 0.0f;
        case MultiplyAdd:
            return a * b + c;
        case SmoothMin:
            return smooth_min(a, b, c);
        case SmoothMax:
            return -smooth_min(-a, -b, c);
        default:
            return 0.0f;
    }
}

std::string check_math(const ShaderNode& n, const ShaderProgram&) {
    std::string e = check_mode(n, 0, "operation", MathOperationCount);
    return e.empty() ? check_mode(n, 1, "clamp", 2) : e;
}

void evaluate_math(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    float v = math(n.modes[0], r[n.inputs[0]], r[n.inputs[1]], r[n.inputs[2]]);
    // saturate() keeps NaN out: Cycles' clamp node returns min(max(v, 0), 1), which maps NaN to 0.
    if (n.modes[1]) v = std::fmin(std::fmax(v, 0.0f), 1.0f);
    r[n.outputs[0]] = v;
}

// Copy kinds: the compiler's value moves and socket conversions.
// ColorToFloat is the luminance with mode 1's weights (node_registry.h luminance()).
enum CopyKind : int32_t { Float, Vector, FloatToVector, VectorToFloat, ColorToFloat, CopyKindCount };

std::string check_copy(const ShaderNode& n, const ShaderProgram& program) {
    std::string e = check_mode(n, 0, "kind", CopyKindCount);
    if (e.empty() && n.modes[0] == ColorToFloat)
        e = check_mode(n, 1, "luminance weights", kLuminanceWeightsCount);
    if (!e.empty()) return e;
    const bool vector_in = n.modes[0] == Vector || n.modes[0] == VectorToFloat || n.modes[0] == ColorToFloat;
    const bool vector_out = n.modes[0] == Vector || n.modes[0] == FloatToVector;
    const size_t count = program.registers.size();
    if (vector_in && static_cast<uint64_t>(n.inputs[0]) + 3 > count) return "input register is not 3 wide";
    if (vector_out && static_cast<uint64_t>(n.outputs[0]) + 3 > count) return "output register is not 3 wide";
    return "";
}

void evaluate_copy(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const uint32_t in = n.inputs[0], out = n.outputs[0];
    switch (n.modes[0]) {
        case Float:
            r[out] = r[in];
            break;
        case Vector:
            r.set(out, r.vec3(in));
            break;
        case FloatToVector:
            r.set(out, Vec3(r[in], r[in], r[in]));
            break;
        case VectorToFloat:
            r[out] = (r[in] + r[in + 1] + r[in + 2]) * (1.0f / 3.0f);
            break;
        default:
            r[out] = luminance(r.rgb(in), n.modes[1]);
            break;
    }
}

}  // namespace

const NodeRegistration kMathNode{{.value = 0,
                                  .name = "math",
                                  .input_widths = {1, 1, 1},
                                  .output_widths = {1},
                                  .check = check_math,
                                  .evaluate = evaluate_math}};

// The widths depend on the kind: 1 here, and check_copy checks the vector ones.
const NodeRegistration kCopyNode{{.value = 35,
                                  .name = "copy",
                                  .input_widths = {1},
                                  .output_widths = {1},
                                  .check = check_copy,
                                  .evaluate = evaluate_copy}};

}  // namespace stratum
