// Musgrave Texture (Blender's ShaderNodeTexMusgrave, Blender 3.x and 4.0; 4.1 turns it into a
// Noise Texture when a file loads).
//
// | modes                                     | inputs                               | outputs |
// |-------------------------------------------|--------------------------------------|---------|
// | 0 dimensions: 0..3 = 1D..4D               | 0 vector (3), 1 w, 2 scale, 3 detail,| 0 fac   |
// | 1 type (Cycles' NodeMusgraveType):        | 4 dimension, 5 lacunarity, 6 offset, |         |
// |   0 multifractal, 1 fBM, 2 hybrid         | 7 gain                               |         |
// |   multifractal, 3 ridged multifractal,    |                                      |         |
// |   4 heterogeneous terrain                 |                                      |         |
//
// Cycles' svm/musgrave.h at v3.4.0: the point is (vector, w) x scale; dimension >= 1e-5,
// lacunarity >= 1e-5 and detail in [0, 15]; int(detail) whole octaves plus the fraction, each
// octave's amplitude lacunarity^-dimension times the last's (shading/fractal_noise.h).
#include <cmath>

#include "shading/fractal_noise.h"
#include "shading/node_registry.h"

namespace stratum {

namespace {

using fractal::Octaves;
using perlin::Point;
using perlin::Precision;

enum MusgraveType : int32_t {
    Multifractal,
    Fbm,
    HybridMultifractal,
    RidgedMultifractal,
    HeteroTerrain,
    TypeCount
};

template <int N>
float musgrave(const Point<N>& p, int32_t type, Octaves octaves, float roughness, float lacunarity,
               float offset, float gain) {
    constexpr Precision finite = Precision::Finite;
    switch (type) {
        case Multifractal:
            return fractal::multifractal<N>(p, octaves, roughness, lacunarity, finite);
        case HybridMultifractal:
            return fractal::hybrid_multifractal<N>(p, octaves, roughness, lacunarity, offset, gain, finite);
        case RidgedMultifractal:
            return fractal::ridged_multifractal<N>(p, octaves, roughness, lacunarity, offset, gain, finite);
        case HeteroTerrain:
            return fractal::hetero_terrain<N>(p, octaves, roughness, lacunarity, offset, finite);
        default:
            return fractal::musgrave_fbm<N>(p, octaves, roughness, lacunarity);
    }
}

std::string check_musgrave(const ShaderNode& n, const ShaderProgram&) {
    std::string e = check_mode(n, 0, "dimensions", 4);
    return e.empty() ? check_mode(n, 1, "type", TypeCount) : e;
}

void evaluate_musgrave(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const Vec3 v = r.vec3(n.inputs[0]);
    const float w = r[n.inputs[1]], scale = r[n.inputs[2]];
    const Octaves octaves = fractal::musgrave_octaves(r[n.inputs[3]]);
    const float dimension = std::fmax(r[n.inputs[4]], 1e-5f);
    const float lacunarity = std::fmax(r[n.inputs[5]], 1e-5f);
    const float offset = r[n.inputs[6]], gain = r[n.inputs[7]];
    const float roughness = std::pow(lacunarity, -dimension);
    const int32_t type = n.modes[1];
    float fac;
    switch (n.modes[0]) {
        case 0:
            fac = musgrave<1>({w * scale}, type, octaves, roughness, lacunarity, offset, gain);
            break;
        case 1:
            fac = musgrave<2>({v.x * scale, v.y * scale}, type, octaves, roughness, lacunarity, offset, gain);
            break;
        case 2:
            fac = musgrave<3>({v.x * scale, v.y * scale, v.z * scale}, type, octaves, roughness, lacunarity,
                              offset, gain);
            break;
        default:
            fac = musgrave<4>({v.x * scale, v.y * scale, v.z * scale, w * scale}, type, octaves, roughness,
                              lacunarity, offset, gain);
            break;
    }
    r[n.outputs[0]] = fac;
}

}  // namespace

const NodeRegistration kMusgraveNode{{.value = 27,
                                      .name = "musgrave",
                                      .input_widths = {3, 1, 1, 1, 1, 1, 1, 1},
                                      .output_widths = {1},
                                      .check = check_musgrave,
                                      .evaluate = evaluate_musgrave}};

}  // namespace stratum
