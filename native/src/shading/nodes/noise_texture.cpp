// Noise Texture (Blender's ShaderNodeTexNoise), all Blender generations.
//
// | modes                                   | inputs                         | outputs      |
// |-----------------------------------------|--------------------------------|--------------|
// | 0 dimensions: 0..3 = 1D..4D             | 0 vector (3), 1 w, 2 scale,    | 0 fac,       |
// | 1 type (Cycles' NodeNoiseType):         | 3 detail, 4 roughness,         | 1 color (3)  |
// |   0 multifractal, 1 fBM, 2 hybrid       | 5 lacunarity, 6 offset,        |              |
// |   multifractal, 3 ridged multifractal,  | 7 gain, 8 distortion           |              |
// |   4 heterogeneous terrain               |                                |              |
// | 2 normalize (fBM)                       |                                |              |
// | 3 generation: 0 Blender 3.x, 1 4.0,     |                                |              |
// |   2 4.1, 3 4.2 and later                |                                |              |
// | 4 color: 1 when the Color output is read|                                |              |
//
// Cycles' svm/noisetex.h: the point is (vector, w) x scale, in as many dimensions as the node
// has; Distortion adds signed noise of the point shifted by seeded offsets (each component in
// [100, 200], a hash of the seed); Color is (fac, the texture at the point shifted by two more
// offsets). Generations: 3.x sums unsigned fBM with lacunarity 2 and roughness clamped to [0, 1]
// (fractal_noise.h at v3.4.0); 4.0 adds Lacunarity and Normalize (roughness still clamped);
// 4.1 adds the types, Offset and Gain (Musgrave merged in) and only keeps roughness >= 0;
// 4.2 wraps coordinates (perlin_noise.h). Generations 0 and 1 take fBM only. Detail is clamped
// to [0, 15].
#include <cmath>

#include "shading/cycles_hash.h"
#include "shading/fractal_noise.h"
#include "shading/node_registry.h"

namespace stratum {

namespace {

using fractal::Octaves;
using perlin::Point;
using perlin::Precision;

enum NoiseType : int32_t {
    Multifractal,
    Fbm,
    HybridMultifractal,
    RidgedMultifractal,
    HeteroTerrain,
    TypeCount
};
enum Generation : int32_t { Blender3, Blender40, Blender41, Blender42, GenerationCount };

// Cycles' random_floatN_offset(seed): component k of seed s is 100 + 100 hash(s, k); a 1D
// offset hashes the seed alone. Seeds 0..N-1 shift Distortion, N and N + 1 the colour.
struct SeedOffsets {
    float one[3];
    float many[6][4];
};
const SeedOffsets& seed_offsets() {
    static const SeedOffsets offsets = [] {
        SeedOffsets o{};
        for (int s = 0; s < 3; ++s)
            o.one[s] = 100.0f + cycles_hash::hash_float(static_cast<float>(s)) * 100.0f;
        for (int s = 0; s < 6; ++s)
            for (int k = 0; k < 4; ++k)
                o.many[s][k] =
                    100.0f + cycles_hash::hash_float2(static_cast<float>(s), static_cast<float>(k)) * 100.0f;
        return o;
    }();
    return offsets;
}

template <int N>
Point<N> shifted(const Point<N>& p, int seed) {
    const SeedOffsets& o = seed_offsets();
    Point<N> q = p;
    if constexpr (N == 1) {
        q[0] += o.one[seed];
    } else {
        for (int i = 0; i < N; ++i) q[i] += o.many[seed][i];
    }
    return q;
}

struct NoiseParams {
    float detail, roughness, lacunarity, offset, gain, distortion;
    int32_t type, generation;
    bool normalize;
    Precision precision;
};

template <int N>
float fractal_sum(const Point<N>& p, const NoiseParams& k) {
    if (k.generation == Blender3) return fractal::fbm_3x<N>(p, k.detail, k.roughness);
    const Octaves octaves = fractal::noise_octaves(k.detail);
    switch (k.type) {
        case Multifractal:
            return fractal::multifractal<N>(p, octaves, k.roughness, k.lacunarity, k.precision);
        case HybridMultifractal:
            return fractal::hybrid_multifractal<N>(p, octaves, k.roughness, k.lacunarity, k.offset, k.gain,
                                                   k.precision);
        case RidgedMultifractal:
            return fractal::ridged_multifractal<N>(p, octaves, k.roughness, k.lacunarity, k.offset, k.gain,
                                                   k.precision);
        case HeteroTerrain:
            return fractal::hetero_terrain<N>(p, octaves, k.roughness, k.lacunarity, k.offset, k.precision);
        default:
            return fractal::fbm<N>(p, k.detail, k.roughness, k.lacunarity, k.normalize, k.precision);
    }
}

template <int N>
void noise_texture(Point<N> p, const NoiseParams& k, bool color_needed, ShaderRegisters& r,
                   const ShaderNode& n) {
    if (k.distortion != 0.0f) {
        Point<N> d;
        for (int i = 0; i < N; ++i) d[i] = perlin::snoise<N>(shifted<N>(p, i), k.precision) * k.distortion;
        for (int i = 0; i < N; ++i) p[i] += d[i];
    }
    const float value = fractal_sum<N>(p, k);
    r[n.outputs[0]] = value;
    if (color_needed)
        r.set(n.outputs[1],
              Rgb(value, fractal_sum<N>(shifted<N>(p, N), k), fractal_sum<N>(shifted<N>(p, N + 1), k)));
}

std::string check_noise(const ShaderNode& n, const ShaderProgram&) {
    for (const auto& [index, what, count] :
         {std::tuple{0, "dimensions", 4}, std::tuple{1, "type", int{TypeCount}},
          std::tuple{2, "normalize", 2}, std::tuple{3, "generation", int{GenerationCount}},
          std::tuple{4, "color", 2}}) {
        std::string e = check_mode(n, index, what, count);
        if (!e.empty()) return e;
    }
    if (n.modes[3] < Blender41 && n.modes[1] != Fbm)
        return "mode 1 (type) is " + std::to_string(n.modes[1]) +
               "; generations 0 and 1 (Blender < 4.1) take " + "only 1 (fBM)";
    return "";
}

void evaluate_noise(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    NoiseParams k{};
    k.generation = n.modes[3];
    k.type = n.modes[1];
    k.normalize = n.modes[2] != 0;
    k.precision = k.generation >= Blender42 ? Precision::Wrapped : Precision::Finite;
    k.detail = fractal::cycles_clamp(r[n.inputs[3]], 0.0f, 15.0f);
    k.roughness = r[n.inputs[4]];
    if (k.generation == Blender40) k.roughness = fractal::cycles_clamp(k.roughness, 0.0f, 1.0f);
    if (k.generation >= Blender41) k.roughness = std::fmax(k.roughness, 0.0f);
    k.lacunarity = r[n.inputs[5]];
    k.offset = r[n.inputs[6]];
    k.gain = r[n.inputs[7]];
    k.distortion = r[n.inputs[8]];
    const float scale = r[n.inputs[2]];
    const Vec3 v = r.vec3(n.inputs[0]);
    const float w = r[n.inputs[1]] * scale;
    const float x = v.x * scale, y = v.y * scale, z = v.z * scale;
    const bool color = n.modes[4] != 0;
    switch (n.modes[0]) {
        case 0:
            noise_texture<1>({w}, k, color, r, n);
            break;
        case 1:
            noise_texture<2>({x, y}, k, color, r, n);
            break;
        case 2:
            noise_texture<3>({x, y, z}, k, color, r, n);
            break;
        default:
            noise_texture<4>({x, y, z, w}, k, color, r, n);
            break;
    }
}

}  // namespace

const NodeRegistration kNoiseNode{{.value = 19,
                                   .name = "noise",
                                   .input_widths = {3, 1, 1, 1, 1, 1, 1, 1, 1},
                                   .output_widths = {1, 3},
                                   .check = check_noise,
                                   .evaluate = evaluate_noise}};

}  // namespace stratum
