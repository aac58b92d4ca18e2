// Voronoi Texture node (Blender's ShaderNodeTexVoronoi), as Cycles evaluates it
// (kernel/svm/voronoi.h at v3.4.0 and v5.0.0; the octave's features: shading/voronoi_features.h).
//
// | modes                                   | inputs                  | outputs              |
// |-----------------------------------------|-------------------------|----------------------|
// | 0 dimensions - 1 (0..3)                 | 0 vector (3), 1 w,      | 0 distance,          |
// | 1 feature: F1, F2, SMOOTH_F1,           | 2 scale, 3 detail,      | 1 color (3),         |
// |   DISTANCE_TO_EDGE, N_SPHERE_RADIUS     | 4 roughness,            | 2 position (3),      |
// | 2 metric: EUCLIDEAN, MANHATTAN,         | 5 lacunarity,           | 3 w, 4 radius        |
// |   CHEBYCHEV, MINKOWSKI                  | 6 smoothness,           |                      |
// | 3 generation (voronoi::Generation):     | 7 exponent,             |                      |
// |   3.x, 4.0-4.4, 4.5, 5.0+               | 8 randomness            |                      |
// | 4 normalize (4.0+)                      |                         |                      |
//
// 3.x: one octave of the feature at (vector, w) * scale; Position and W divided back by the
// scale. 4.0+: fractal Voronoi, fBM-like octaves (detail up to 15, each scaled by lacunarity and
// weighted by roughness^i, a fractional last octave blended in) whose distances and colours add
// and whose positions blend; normalize divides by the total weight and by the feature's largest
// distance. Smooth F1 with smoothness 0 is F1 in 4.0+ (3.x evaluates it with a zero width).
// Detail, roughness and lacunarity are read in 4.0+ only; Exponent by Minkowski only.
#include <cmath>

#include "shading/node_registry.h"
#include "shading/voronoi_features.h"

namespace stratum {

namespace {

using namespace voronoi;

enum Feature : int32_t { F1, F2, SmoothF1, DistanceToEdge, NSphereRadius, FeatureCount };

struct Inputs {
    Vec<3> vector;
    float w, scale, detail, roughness, lacunarity;
    bool normalize;
    Feature feature;
    Params params;
};

struct Outputs {
    float distance = 0.0f;
    Vec<3> color{};
    Vec<3> position{};
    float w = 0.0f, radius = 0.0f;
};

// The point at which the texture is evaluated in N dimensions: (x[, y[, z]]) of the vector, w as
// the fourth, or w alone in 1D.
template <int N>
Vec<N> coordinate(const Inputs& in) {
    if constexpr (N == 1) {
        return {in.w};
    } else {
        Vec<N> c;
        for (int i = 0; i < N && i < 3; ++i) c[i] = in.vector[i];
        if constexpr (N == 4) c[3] = in.w;
        return c;
    }
}

// 4.x keeps positions as float4: x, y[, z] from the vector, w in the fourth (1D: w only).
template <int N>
Vec<4> as_float4(const Vec<N>& p) {
    Vec<4> r{};
    if constexpr (N == 1) {
        r[3] = p[0];
    } else {
        for (int i = 0; i < N; ++i) r[i] = p[i];
    }
    return r;
}

template <int N>
Octave<N> octave(Feature feature, const Vec<N>& coord, const Params& p) {
    if (feature == F2) return f2<N>(coord, p);
    if (feature == SmoothF1) return smooth_f1<N>(coord, p);
    return f1<N>(coord, p);
}

// ---- Blender 3.x: one octave --------------------------------------------------------------------

template <int N>
Outputs evaluate_single(const Inputs& in) {
    Vec<N> coord = coordinate<N>(in);
    Outputs out;
    if (in.feature == DistanceToEdge) {
        out.distance = distance_to_edge<N>(coord, in.params);
        return out;
    }
    if (in.feature == NSphereRadius) {
        out.radius = n_sphere_radius<N>(coord, in.params);
        return out;
    }
    const Octave<N> o = octave<N>(in.feature, coord, in.params);
    out.distance = o.distance;
    out.color = o.color;
    // safe_divide by the scale, with the vector type's division.
    const Vec<N> position = in.scale != 0.0f ? divide<N>(o.position, in.scale) : Vec<N>{};
    if constexpr (N == 1) {
        out.w = position[0];
    } else {
        for (int i = 0; i < N && i < 3; ++i) out.position[i] = position[i];
        if constexpr (N == 4) out.w = position[3];
    }
    return out;
}

// ---- Blender 4.0+: fractal Voronoi ----------------------------------------------------------------

template <int N>
Outputs evaluate_fractal(const Inputs& in) {
    const Vec<N> coord = coordinate<N>(in);
    const Params& p = in.params;
    const bool zero_input = in.detail == 0.0f || in.roughness == 0.0f;
    const float remainder = in.detail - std::floor(in.detail);
    const float octaves = std::ceil(in.detail);
    Outputs out;
    if (in.feature == NSphereRadius) {
        out.radius = n_sphere_radius<N>(coord, p);
        return out;
    }
    if (in.feature == DistanceToEdge) {
        const float max_distance = 0.5f + 0.5f * p.randomness;
        float amplitude = 1.0f, max_amplitude = max_distance, scale = 1.0f, distance = 8.0f;
        for (int i = 0; static_cast<float>(i) <= octaves; ++i) {
            const float d = distance_to_edge<N>(coord * scale, p);
            if (zero_input) {
                distance = d;
                break;
            }
            if (static_cast<float>(i) <= in.detail) {
                max_amplitude = mix(max_amplitude, max_distance / scale, amplitude);
                distance = mix(distance, cmin(distance, d / scale), amplitude);
                scale *= in.lacunarity;
                amplitude *= in.roughness;
            } else if (remainder != 0.0f) {
                const float blended_amplitude = mix(max_amplitude, max_distance / scale, amplitude);
                max_amplitude = mix(max_amplitude, blended_amplitude, remainder);
                const float blended = mix(distance, cmin(distance, d / scale), amplitude);
                distance = mix(distance, cmin(distance, blended), remainder);
            }
        }
        out.distance = in.normalize ? distance / max_amplitude : distance;
        return out;
    }

    // The largest distance of the feature, for normalize.
    const float extent = 0.5f + 0.5f * p.randomness;
    float max_distance = extent;
    if constexpr (N >= 2) {
        Vec<N> corner;
        corner.fill(extent);
        max_distance = distance<N>(Vec<N>{}, corner, p.metric);
    }
    if (in.feature == F2) max_distance *= 2.0f;
    // Smooth F1 of smoothness 0 is F1.
    const Feature feature = in.feature == SmoothF1 && p.smoothness == 0.0f ? F1 : in.feature;

    float amplitude = 1.0f, max_amplitude = 0.0f, scale = 1.0f, distance = 0.0f;
    Vec<3> color{};
    Vec<4> position{};
    for (int i = 0; static_cast<float>(i) <= octaves; ++i) {
        const Octave<N> o = octave<N>(feature, coord * scale, p);
        if (zero_input) {
            max_amplitude = 1.0f;
            distance = o.distance;
            color = o.color;
            position = as_float4<N>(o.position);
            break;
        }
        const Vec<4> octave_position = divide<4>(as_float4<N>(o.position), scale);
        if (static_cast<float>(i) <= in.detail) {
            max_amplitude += amplitude;
            distance += o.distance * amplitude;
            for (int k = 0; k < 3; ++k) color[k] += o.color[k] * amplitude;
            position = mix<4>(position, octave_position, amplitude);
            scale *= in.lacunarity;
            amplitude *= in.roughness;
        } else if (remainder != 0.0f) {
            max_amplitude = mix(max_amplitude, max_amplitude + amplitude, remainder);
            distance = mix(distance, distance + o.distance * amplitude, remainder);
            for (int k = 0; k < 3; ++k)
                color[k] = mix(color[k], color[k] + o.color[k] * amplitude, remainder);
            position = mix<4>(position, mix<4>(position, octave_position, amplitude), remainder);
        }
    }
    if (in.normalize) {
        distance /= max_amplitude * max_distance;
        const float inverse = 1.0f / max_amplitude;  // float3 /= f multiplies by 1 / f
        for (int k = 0; k < 3; ++k) color[k] *= inverse;
    }
    position = in.scale != 0.0f ? divide<4>(position, in.scale) : Vec<4>{};
    out.distance = distance;
    out.color = color;
    out.position = {position[0], position[1], position[2]};
    out.w = position[3];
    return out;
}

template <int N>
Outputs evaluate_dimension(const Inputs& in) {
    return in.params.metric.generation == Blender3 ? evaluate_single<N>(in) : evaluate_fractal<N>(in);
}

std::string check_voronoi(const ShaderNode& n, const ShaderProgram&) {
    const char* names[] = {"dimensions", "feature", "metric", "generation", "normalize"};
    const int32_t counts[] = {4, FeatureCount, MetricCount, GenerationCount, 2};
    for (int i = 0; i < 5; ++i) {
        std::string e = check_mode(n, i, names[i], counts[i]);
        if (!e.empty()) return e;
    }
    return "";
}

void evaluate_voronoi(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    Inputs in;
    const Vec3 v = r.vec3(n.inputs[0]);
    in.w = r[n.inputs[1]];
    in.scale = r[n.inputs[2]];
    in.detail = r[n.inputs[3]];
    in.roughness = r[n.inputs[4]];
    in.lacunarity = r[n.inputs[5]];
    in.feature = static_cast<Feature>(n.modes[1]);
    in.normalize = n.modes[4] != 0;
    in.params.metric = {static_cast<Metric>(n.modes[2]), r[n.inputs[7]], static_cast<Generation>(n.modes[3])};
    in.params.randomness = clamp(r[n.inputs[8]], 0.0f, 1.0f);
    in.params.smoothness = clamp(r[n.inputs[6]] / 2.0f, 0.0f, 0.5f);
    if (in.params.metric.generation != Blender3) {
        in.detail = clamp(in.detail, 0.0f, 15.0f);
        in.roughness = clamp(in.roughness, 0.0f, 1.0f);
    }
    in.vector = {v.x * in.scale, v.y * in.scale, v.z * in.scale};
    in.w *= in.scale;

    Outputs out;
    switch (n.modes[0]) {
        case 0:
            out = evaluate_dimension<1>(in);
            break;
        case 1:
            out = evaluate_dimension<2>(in);
            break;
        case 2:
            out = evaluate_dimension<3>(in);
            break;
        default:
            out = evaluate_dimension<4>(in);
            break;
    }
    r[n.outputs[0]] = out.distance;
    r.set(n.outputs[1], Rgb(out.color[0], out.color[1], out.color[2]));
    r.set(n.outputs[2], Vec3(out.position[0], out.position[1], out.position[2]));
    r[n.outputs[3]] = out.w;
    r[n.outputs[4]] = out.radius;
}

}  // namespace

const NodeRegistration kVoronoiNode{{.value = 20,
                                     .name = "voronoi",
                                     .input_widths = {3, 1, 1, 1, 1, 1, 1, 1, 1},
                                     .output_widths = {1, 3, 3, 1, 1},
                                     .check = check_voronoi,
                                     .evaluate = evaluate_voronoi}};

}  // namespace stratum
