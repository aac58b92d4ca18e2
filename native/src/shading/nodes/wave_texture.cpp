// Wave Texture (Blender's ShaderNodeTexWave), as Cycles' svm/wave.h, with its distortion's fBM in
// each generation (shading/fractal_noise.h).
//
// | node | modes                                   | inputs                             | outputs   |
// |------|-----------------------------------------|------------------------------------|-----------|
// | wave | 0 type (0 bands, 1 rings);              | 0 vector (3), 1 scale,             | 0 color 3 |
// |      | 1 bands direction (X, Y, Z, diagonal);  | 2 distortion, 3 detail,            | 1 fac     |
// |      | 2 rings direction (X, Y, Z, spherical); | 4 detail scale, 5 detail roughness |           |
// |      | 3 profile (sine, saw, tri);             | 6 phase offset                     |           |
// |      | 4 noise generation (below)              |                                    |           |
//
// On p = (vector x scale + 1e-6) x 0.999999: bands n = 20 x (x, y or z), or 10 x (x + y + z)
// diagonally; rings n = 20 |p| with the direction's axis zeroed (spherical: none). Then n +=
// phase, and with a distortion d != 0, n += d (2 fbm(p x detail scale) - 1). Sine: 1/2 + sin(n -
// pi/2) / 2; saw: the fraction of n / 2 pi; triangle: 2 |t - floor(t + 1/2)| of t = n / 2 pi.
//
// The fBM (lacunarity 2, normalised to [0, 1]) by Blender generation:
// | 0 | 3.x  | unsigned octaves, detail clamped to [0, 15], roughness to [0, 1]         |
// | 1 | 4.0  | signed octaves (fractal_noise_3d of 4.0): detail and roughness clamped   |
// | 2 | 4.1  | noise_fbm: roughness not clamped; detail clamped to [0, 15] here (Cycles |
// |   |      | does not clamp a linked detail; Blender's socket stops at 15)            |
// | 3 | 4.2+ | as 4.1, Perlin noise on coordinates wrapped every 100000 (noise.h)       |
#include <cmath>

#include "shading/fractal_noise.h"
#include "shading/node_registry.h"

namespace stratum {

namespace {

enum WaveType : int32_t { Bands, Rings, WaveTypeCount };
enum Direction : int32_t { AxisX, AxisY, AxisZ, AllAxes, DirectionCount };
enum Profile : int32_t { Sine, Saw, Triangle, ProfileCount };
enum Generation : int32_t { Blender3, Blender40, Blender41, Blender42, GenerationCount };

float distortion_noise(Vec3 p, float detail, float roughness, int32_t generation) {
    const fractal::Point<3> q = {p.x, p.y, p.z};
    switch (generation) {
        case Blender3:
            return fractal::fbm_3x<3>(q, detail, roughness);
        case Blender40:
            return fractal::fbm<3>(q, detail, fractal::cycles_clamp(roughness, 0.0f, 1.0f), 2.0f, true,
                                   fractal::Precision::Finite);
        case Blender41:
            return fractal::fbm<3>(q, detail, roughness, 2.0f, true, fractal::Precision::Finite);
        default:
            return fractal::fbm<3>(q, detail, roughness, 2.0f, true, fractal::Precision::Wrapped);
    }
}

float wave(const ShaderNode& n, Vec3 p, float distortion, float detail, float detail_scale, float roughness,
           float phase) {
    constexpr float pi = 3.14159265358979323846f, two_pi = 6.28318530717958647692f;
    p = Vec3{(p.x + 0.000001f) * 0.999999f, (p.y + 0.000001f) * 0.999999f, (p.z + 0.000001f) * 0.999999f};
    float v;
    if (n.modes[0] == Bands) {
        switch (n.modes[1]) {
            case AxisX:
                v = p.x * 20.0f;
                break;
            case AxisY:
                v = p.y * 20.0f;
                break;
            case AxisZ:
                v = p.z * 20.0f;
                break;
            default:
                v = (p.x + p.y + p.z) * 10.0f;
                break;
        }
    } else {
        Vec3 r = p;
        if (n.modes[2] == AxisX) r.x = 0.0f;
        if (n.modes[2] == AxisY) r.y = 0.0f;
        if (n.modes[2] == AxisZ) r.z = 0.0f;
        v = std::sqrt(r.x * r.x + r.y * r.y + r.z * r.z) * 20.0f;
    }
    v += phase;
    if (distortion != 0.0f)
        v += distortion * (distortion_noise(p * detail_scale, detail, roughness, n.modes[4]) * 2.0f - 1.0f);
    if (n.modes[3] == Sine) return 0.5f + 0.5f * std::sin(v - pi * 0.5f);
    v /= two_pi;
    if (n.modes[3] == Saw) return v - std::floor(v);
    return std::fabs(v - std::floor(v + 0.5f)) * 2.0f;
}

std::string check_wave(const ShaderNode& n, const ShaderProgram&) {
    std::string e = check_mode(n, 0, "type", WaveTypeCount);
    if (e.empty()) e = check_mode(n, 1, "bands direction", DirectionCount);
    if (e.empty()) e = check_mode(n, 2, "rings direction", DirectionCount);
    if (e.empty()) e = check_mode(n, 3, "profile", ProfileCount);
    if (e.empty()) e = check_mode(n, 4, "noise generation", GenerationCount);
    return e;
}

void evaluate_wave(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const Vec3 p = r.vec3(n.inputs[0]) * r[n.inputs[1]];
    const float f =
        wave(n, p, r[n.inputs[2]], r[n.inputs[3]], r[n.inputs[4]], r[n.inputs[5]], r[n.inputs[6]]);
    r.set(n.outputs[0], Rgb(f, f, f));
    r[n.outputs[1]] = f;
}

}  // namespace

const NodeRegistration kWaveNode{{.value = 21,
                                  .name = "wave",
                                  .input_widths = {3, 1, 1, 1, 1, 1, 1},
                                  .output_widths = {3, 1},
                                  .check = check_wave,
                                  .evaluate = evaluate_wave}};

}  // namespace stratum
