// Voronoi and White Noise texture nodes (shading/nodes/voronoi_texture.cpp,
// white_noise_texture.cpp), through the C ABI: properties every Voronoi must have (F1 <= F2, the
// distance to the returned position is the distance, Chebychev <= Euclidean <= Manhattan), the
// regular lattice of randomness 0 in closed form, the fractal octaves recombined by hand from
// single octaves, the cell colour re-derived from the hashes (lookup3 and an independently written
// PCG), white noise as the hash of the point, and the checks and hostile inputs.
#include <gtest/gtest.h>
#include <stratum/shader_nodes.h>

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "node_types.h"
#include "scene_handle.h"
#include "shading/cycles_hash.h"

namespace {

using stratum_test::node_type;

enum Feature { F1, F2, SmoothF1, Edge, Radius };
enum Metric { Euclidean, Manhattan, Chebychev, Minkowski };

struct VoronoiSetup {
    int dimensions = 3, feature = F1, metric = Euclidean, generation = 0, normalize = 0;
    float w = 0.0f, scale = 1.0f, detail = 0.0f, roughness = 0.5f, lacunarity = 2.0f;
    float smoothness = 1.0f, exponent = 0.5f, randomness = 1.0f;
};

struct VoronoiResult {
    float distance;
    std::array<float, 3> color, position;
    float w, radius;
};

constexpr uint32_t kIn = STRATUM_SHADER_INPUT_REGISTERS;

// One scene for all the programs of this file (programs are only added, never rendered).
StratumScene* shared_scene() {
    static stratum_test::SceneHandle handle;
    return handle.scene;
}

// One program holding one node; evaluates it with GENERATED = p.
class NodeProgram {
public:
    NodeProgram(StratumShaderNode node, std::vector<float> constants, uint32_t outputs) : node_(node) {
        registers_.assign(kIn, 0.0f);
        registers_.insert(registers_.end(), constants.begin(), constants.end());
        registers_.resize(registers_.size() + outputs, 0.0f);
        StratumShaderProgramDesc desc{&node_,  1, registers_.data(), static_cast<uint32_t>(registers_.size()),
                                      nullptr, 0};
        status_ = stratum_scene_add_shader_program(shared_scene(), &desc, &id_);
        if (status_ != STRATUM_OK) error_ = stratum_last_error();
    }
    StratumStatus status() const { return status_; }
    const std::string& error() const { return error_; }
    std::vector<float> run(std::array<float, 3> p, uint32_t first, uint32_t count) const {
        std::vector<float> inputs(kIn, 0.0f), out(count, -1.0f);
        for (int i = 0; i < 3; ++i) inputs[STRATUM_INPUT_GENERATED + i] = p[i];
        EXPECT_EQ(
            stratum_scene_evaluate_program(shared_scene(), id_, inputs.data(), first, count, out.data()),
            STRATUM_OK);
        return out;
    }

private:
    StratumShaderNode node_;
    std::vector<float> registers_;
    StratumStatus status_;
    uint32_t id_ = 0;
    std::string error_;
};

StratumShaderNode voronoi_node(const VoronoiSetup& s) {
    StratumShaderNode n{};
    n.type = node_type("voronoi");
    const int modes[] = {s.dimensions - 1, s.feature, s.metric, s.generation, s.normalize};
    for (int i = 0; i < 5; ++i) n.modes[i] = modes[i];
    n.inputs[0] = STRATUM_INPUT_GENERATED;
    for (uint32_t i = 1; i < 9; ++i) n.inputs[i] = kIn + i - 1;  // the 8 constants
    const uint32_t out = kIn + 8;
    n.outputs[0] = out, n.outputs[1] = out + 1, n.outputs[2] = out + 4, n.outputs[3] = out + 7,
    n.outputs[4] = out + 8;
    return n;
}

VoronoiResult voronoi(const VoronoiSetup& s, std::array<float, 3> p) {
    NodeProgram program(
        voronoi_node(s),
        {s.w, s.scale, s.detail, s.roughness, s.lacunarity, s.smoothness, s.exponent, s.randomness}, 9);
    EXPECT_EQ(program.status(), STRATUM_OK) << program.error();
    const std::vector<float> o = program.run(p, kIn + 8, 9);
    return {o[0], {o[1], o[2], o[3]}, {o[4], o[5], o[6]}, o[7], o[8]};
}

// Deterministic points spread over a few cells, negative coordinates included.
std::vector<std::array<float, 3>> points(int count) {
    std::vector<std::array<float, 3>> r;
    uint32_t state = 12345u;
    const auto next = [&] {
        state = state * 1664525u + 1013904223u;
        return static_cast<float>(state >> 8) / 16777216.0f * 6.0f - 3.0f;
    };
    for (int i = 0; i < count; ++i) r.push_back({next(), next(), next()});
    return r;
}

// The N-dimensional point the node sees (x[, y[, z]][, w]) and its distance helpers.
std::vector<float> coord(int dims, std::array<float, 3> p, float w) {
    if (dims == 1) return {w};
    std::vector<float> c(p.begin(), p.begin() + std::min(dims, 3));
    if (dims == 4) c.push_back(w);
    return c;
}
std::vector<float> returned_position(int dims, const VoronoiResult& r) {
    if (dims == 1) return {r.w};
    std::vector<float> c(r.position.begin(), r.position.begin() + std::min(dims, 3));
    if (dims == 4) c.push_back(r.w);
    return c;
}
double euclidean(const std::vector<float>& a, const std::vector<float>& b) {
    double s = 0.0;
    for (size_t i = 0; i < a.size(); ++i) s += (double(a[i]) - b[i]) * (double(a[i]) - b[i]);
    return std::sqrt(s);
}

constexpr int kGenerations = 4;

TEST(VoronoiNodes, F1IsAtMostF2AndTheDistanceToItsPosition) {
    for (int gen = 0; gen < kGenerations; ++gen)
        for (int dims = 1; dims <= 4; ++dims)
            for (const auto& p : points(12)) {
                VoronoiSetup s;
                s.dimensions = dims, s.generation = gen, s.scale = 1.5f, s.w = p[0] * 0.7f - 0.3f;
                const VoronoiResult f1 = voronoi(s, p);
                s.feature = F2;
                const VoronoiResult f2 = voronoi(s, p);
                EXPECT_LE(f1.distance, f2.distance) << "gen " << gen << " dims " << dims;
                // Position (and W) are in the unscaled space: distance = |scale (p - position)|.
                const auto c = coord(dims, p, s.w);
                for (const VoronoiResult* r : {&f1, &f2}) {
                    const double d = s.scale * euclidean(c, returned_position(dims, *r));
                    EXPECT_NEAR(d, r->distance, 2e-5 * (1.0 + d)) << "gen " << gen << " dims " << dims;
                }
                EXPECT_GT(f2.distance, 0.0f);
                EXPECT_LT(f2.distance, 2.0f * std::sqrt(static_cast<float>(dims)));
            }
}

TEST(VoronoiNodes, MetricsAreOrderedAndMinkowskiMatchesTheOthers) {
    for (int gen = 0; gen < kGenerations; ++gen)
        for (int dims = 2; dims <= 4; ++dims)
            for (const auto& p : points(10)) {
                VoronoiSetup s;
                s.dimensions = dims, s.generation = gen, s.w = p[1] - p[0];
                std::array<float, 4> d{};
                for (int m = 0; m < 4; ++m) {
                    s.metric = m, s.exponent = 1.0f;
                    d[m] = voronoi(s, p).distance;
                }
                EXPECT_LE(d[Chebychev], d[Euclidean]);
                EXPECT_LE(d[Euclidean], d[Manhattan]);
                EXPECT_NEAR(d[Minkowski], d[Manhattan], 1e-5f);  // exponent 1
                s.metric = Minkowski, s.exponent = 2.0f;
                EXPECT_NEAR(voronoi(s, p).distance, d[Euclidean], 1e-5f);
                // Exponent 8: between Chebychev and dims^(1/8) times it.
                s.metric = Minkowski, s.exponent = 8.0f;
                const float m8 = voronoi(s, p).distance;
                EXPECT_GE(m8, d[Chebychev] * (1.0f - 1e-6f));
                EXPECT_LE(m8, std::pow(static_cast<float>(dims), 0.125f) * d[Chebychev] * (1.0f + 1e-6f));
            }
}

TEST(VoronoiNodes, RandomnessZeroIsTheRegularLattice) {
    for (int gen = 0; gen < kGenerations; ++gen)
        for (int dims = 1; dims <= 4; ++dims) {
            VoronoiSetup s;
            s.dimensions = dims, s.generation = gen, s.randomness = 0.0f, s.w = 2.0f;
            // At a lattice point: F1 = 0, the position is the point, F2 = 1, radius 1/2, edge 1/2.
            const std::array<float, 3> lattice{3.0f, -2.0f, 1.0f};
            const VoronoiResult f1 = voronoi(s, lattice);
            EXPECT_EQ(f1.distance, 0.0f);
            EXPECT_EQ(returned_position(dims, f1), coord(dims, lattice, s.w));
            for (const auto& p : points(8)) {
                s.w = p[2] * 0.9f;
                const auto c = coord(dims, p, s.w);
                // Nearest lattice point: the rounded coordinates; Voronoi cells are unit cubes.
                std::vector<float> nearest(c.size());
                double sq = 0.0, worst = 0.0;
                for (size_t i = 0; i < c.size(); ++i) {
                    nearest[i] = std::floor(c[i] + 0.5f);
                    const double f = std::fabs(double(c[i]) - nearest[i]);
                    sq += f * f, worst = std::max(worst, f);
                }
                s.feature = F1;
                const VoronoiResult r = voronoi(s, p);
                EXPECT_NEAR(r.distance, std::sqrt(sq), 1e-5);
                for (size_t i = 0; i < c.size(); ++i)
                    EXPECT_NEAR(returned_position(dims, r)[i], nearest[i], 1e-6);
                s.feature = Edge;
                EXPECT_NEAR(voronoi(s, p).distance, 0.5 - worst, 1e-5) << "gen " << gen << " dims " << dims;
                s.feature = Radius;
                EXPECT_NEAR(voronoi(s, p).radius, 0.5f, 1e-6f);
            }
        }
}

// PCG2D/3D/4D (Jarzynski and Olano 2020) in 64-bit arithmetic reduced to 32 bits, written apart
// from the renderer's; the 31-bit results scaled by 2^-31.
int64_t wrap(int64_t v) { return static_cast<int32_t>(static_cast<uint32_t>(v & 0xffffffff)); }
std::array<float, 4> pcg(std::vector<int64_t> v) {
    for (auto& x : v) x = wrap(x * 1664525 + 1013904223);
    const auto rounds = [&] {
        if (v.size() == 3) {
            v[0] = wrap(v[0] + v[1] * v[2]), v[1] = wrap(v[1] + v[2] * v[0]), v[2] = wrap(v[2] + v[0] * v[1]);
        } else {
            v[0] = wrap(v[0] + v[1] * v[3]), v[1] = wrap(v[1] + v[2] * v[0]);
            v[2] = wrap(v[2] + v[0] * v[1]), v[3] = wrap(v[3] + v[1] * v[2]);
        }
    };
    rounds();
    for (auto& x : v) x = x ^ (x >> 16);  // arithmetic shift of the signed value
    rounds();
    std::array<float, 4> r{};
    for (size_t i = 0; i < v.size(); ++i) r[i] = static_cast<float>(v[i] & 0x7fffffff) / 2147483648.0f;
    return r;
}

TEST(VoronoiNodes, F1ColourIsTheHashOfTheNearestCell) {
    namespace h = stratum::cycles_hash;
    for (int gen = 0; gen < kGenerations; ++gen)
        for (int dims = 1; dims <= 4; ++dims)
            for (const auto& p : points(8)) {
                VoronoiSetup s;
                s.dimensions = dims, s.generation = gen, s.randomness = 0.5f, s.w = p[0] + p[1];
                const VoronoiResult r = voronoi(s, p);
                // With randomness 1/2 the point lies in [cell, cell + 1/2]: its floor is the cell.
                std::vector<float> cell = returned_position(dims, r);
                for (float& x : cell) x = std::floor(x);
                std::array<float, 3> expected{};
                if (gen == 3 && dims >= 2) {
                    std::vector<int64_t> k(cell.begin(), cell.end());
                    if (dims == 2) k.push_back(0);
                    const auto v = pcg(k);
                    expected = {v[0], v[1], v[2]};
                } else {
                    h::Hash3 v{};
                    if (dims == 1) v = h::hash_float_to_float3(cell[0]);
                    if (dims == 2) v = h::hash_float2_to_float3(cell[0], cell[1]);
                    if (dims == 3) v = h::hash_float3_to_float3(cell[0], cell[1], cell[2]);
                    if (dims == 4) v = h::hash_float4_to_float3(cell[0], cell[1], cell[2], cell[3]);
                    expected = {v.x, v.y, v.z};
                }
                for (int i = 0; i < 3; ++i)
                    EXPECT_EQ(r.color[i], expected[i]) << "gen " << gen << " dims " << dims;
            }
}

TEST(VoronoiNodes, SmoothF1LiesBelowF1AndIsF1WithoutSmoothness) {
    for (int gen = 0; gen < kGenerations; ++gen)
        for (int dims = 1; dims <= 3; ++dims)
            for (const auto& p : points(6)) {
                VoronoiSetup s;
                s.dimensions = dims, s.generation = gen, s.w = p[2];
                const float f1 = voronoi(s, p).distance;
                s.feature = SmoothF1, s.smoothness = 0.6f;
                const VoronoiResult smooth = voronoi(s, p);
                EXPECT_LE(smooth.distance, f1 + 1e-6f);
                EXPECT_GT(smooth.distance, f1 - 0.6f);  // the smooth minimum is within the width
                for (float c : smooth.color) EXPECT_TRUE(c > -0.5f && c < 1.5f);
                s.smoothness = 0.0f;
                // 4.0+ evaluates F1; 3.x the smooth minimum of zero width, F1 up to rounding.
                if (gen > 0)
                    EXPECT_EQ(voronoi(s, p).distance, f1);
                else
                    EXPECT_NEAR(voronoi(s, p).distance, f1, 1e-6f);
            }
}

TEST(VoronoiNodes, FractalOctavesRecombineSingleOctaves) {
    for (int gen = 1; gen < kGenerations; ++gen)
        for (int feature : {F1, F2})
            for (int dims : {1, 2, 3}) {
                for (const auto& p : points(5)) {
                    VoronoiSetup s;
                    s.dimensions = dims, s.generation = gen, s.feature = feature, s.w = p[0] * 0.5f;
                    const VoronoiResult o0 = voronoi(s, p);
                    VoronoiSetup twice = s;
                    twice.scale = 2.0f, twice.w = s.w;  // the second octave: lacunarity 2
                    const VoronoiResult o1 = voronoi(twice, p);
                    s.detail = 1.0f, s.roughness = 0.5f;
                    const VoronoiResult full = voronoi(s, p);
                    EXPECT_NEAR(full.distance, o0.distance + 0.5f * o1.distance, 1e-5f);
                    for (int i = 0; i < 3; ++i) {
                        EXPECT_NEAR(full.color[i], o0.color[i] + 0.5f * o1.color[i], 1e-5f);
                        // Positions blend: mix(position0, position1, roughness).
                        EXPECT_NEAR(full.position[i],
                                    o0.position[i] + 0.5f * (o1.position[i] - o0.position[i]), 1e-5f);
                    }
                    EXPECT_NEAR(full.w, o0.w + 0.5f * (o1.w - o0.w), 1e-5f);
                    // A fractional detail blends the last octave in by its fraction.
                    s.detail = 0.25f;
                    const VoronoiResult part = voronoi(s, p);
                    EXPECT_NEAR(part.distance, o0.distance + 0.25f * 0.5f * o1.distance, 1e-5f);
                    // normalize divides by the weights (1.5) and the largest distance.
                    s.detail = 1.0f, s.normalize = 1;
                    const float extent = dims == 1 ? 1.0f : std::sqrt(static_cast<float>(dims));
                    const float largest = extent * (feature == F2 ? 2.0f : 1.0f);
                    EXPECT_NEAR(voronoi(s, p).distance, full.distance / (1.5f * largest), 1e-5f);
                    EXPECT_NEAR(voronoi(s, p).color[0], full.color[0] / 1.5f, 1e-5f);
                }
            }
}

TEST(VoronoiNodes, FractalDistanceToEdgeTakesTheMinimumOfOctaves) {
    for (int dims : {1, 2, 3})
        for (const auto& p : points(5)) {
            VoronoiSetup s;
            s.dimensions = dims, s.generation = 3, s.feature = Edge, s.w = p[1];
            const float e0 = voronoi(s, p).distance;
            VoronoiSetup twice = s;
            twice.scale = 2.0f;
            const float e1 = voronoi(twice, p).distance;  // in units of the scaled-by-2 lattice
            s.detail = 1.0f, s.roughness = 1.0f;          // amplitude 1: the plain minimum
            EXPECT_NEAR(voronoi(s, p).distance, std::min(e0, e1 / 2.0f), 3e-6f);
            s.normalize = 1;  // max amplitude mix(1, 1/2, 1) = 1/2 at randomness 1
            EXPECT_NEAR(voronoi(s, p).distance, std::min(e0, e1 / 2.0f) / 0.5f, 6e-6f);
        }
}

TEST(VoronoiNodes, GenerationsAgreeWhereTheirFormulasDo) {
    for (int dims = 1; dims <= 4; ++dims)
        for (const auto& p : points(6)) {
            VoronoiSetup s;
            s.dimensions = dims, s.w = p[0];
            for (int feature : {F1, F2, Edge, Radius}) {
                s.feature = feature;
                s.generation = 0;
                const VoronoiResult g0 = voronoi(s, p);
                s.generation = 1;
                const VoronoiResult g1 = voronoi(s, p);
                s.generation = 2;
                const VoronoiResult g2 = voronoi(s, p);
                s.generation = 3;
                const VoronoiResult g3 = voronoi(s, p);
                EXPECT_NEAR(g0.distance, g1.distance, 1e-6f);
                EXPECT_NEAR(g1.distance, g2.distance, 1e-6f);
                EXPECT_NEAR(g1.radius, g2.radius, 1e-6f);
                EXPECT_NEAR(g0.radius, g1.radius, 1e-6f);
                for (int i = 0; i < 3; ++i) EXPECT_NEAR(g1.position[i], g2.position[i], 1e-6f);
                // 5.0 hashes cells differently except in 1D.
                if (dims == 1) {
                    EXPECT_EQ(g3.distance, g2.distance);
                } else if (feature != Radius) {
                    EXPECT_NE(g3.distance, g2.distance);
                }
            }
        }
}

TEST(WhiteNoiseNodes, IsTheHashOfThePoint) {
    namespace h = stratum::cycles_hash;
    for (int dims = 1; dims <= 4; ++dims)
        for (const auto& p : points(10)) {
            const float w = p[0] * 3.0f + 0.5f;
            StratumShaderNode n{};
            n.type = node_type("white_noise");
            n.modes[0] = dims - 1;
            n.inputs[0] = STRATUM_INPUT_GENERATED, n.inputs[1] = kIn;
            n.outputs[0] = kIn + 1, n.outputs[1] = kIn + 2;
            NodeProgram program(n, {w}, 4);
            ASSERT_EQ(program.status(), STRATUM_OK) << program.error();
            const std::vector<float> o = program.run(p, kIn + 1, 4);
            float value = 0.0f;
            h::Hash3 c{};
            if (dims == 1) value = h::hash_float(w), c = h::hash_float_to_float3(w);
            if (dims == 2) value = h::hash_float2(p[0], p[1]), c = h::hash_float2_to_float3(p[0], p[1]);
            if (dims == 3)
                value = h::hash_float3(p[0], p[1], p[2]), c = h::hash_float3_to_float3(p[0], p[1], p[2]);
            if (dims == 4)
                value = h::hash_float4(p[0], p[1], p[2], w),
                c = h::hash_float4_to_float3(p[0], p[1], p[2], w);
            EXPECT_EQ(o[0], value);
            EXPECT_EQ(o[1], c.x);
            EXPECT_EQ(o[2], c.y);
            EXPECT_EQ(o[3], c.z);
        }
}

TEST(VoronoiNodes, BadModesAreRejectedByName) {
    const char* fields[] = {"dimensions", "feature", "metric", "generation", "normalize"};
    const int limits[] = {4, 5, 4, 4, 2};
    for (int mode = 0; mode < 5; ++mode)
        for (int bad : {-1, limits[mode]}) {
            StratumShaderNode n = voronoi_node({});
            n.modes[mode] = bad;
            NodeProgram program(n, std::vector<float>(8, 1.0f), 9);
            EXPECT_NE(program.status(), STRATUM_OK);
            EXPECT_NE(program.error().find("voronoi"), std::string::npos) << program.error();
            EXPECT_NE(program.error().find(fields[mode]), std::string::npos) << program.error();
        }
    StratumShaderNode n{};
    n.type = node_type("white_noise");
    n.modes[0] = 4;
    n.inputs[1] = kIn, n.outputs[0] = kIn + 1, n.outputs[1] = kIn + 2;
    NodeProgram program(n, {0.0f}, 4);
    EXPECT_NE(program.status(), STRATUM_OK);
    EXPECT_NE(program.error().find("white_noise"), std::string::npos) << program.error();
}

TEST(VoronoiNodes, HostileInputsGiveValuesWithoutCrashing) {
    // Constants must be finite, so every input reads the renderer's GENERATED registers: the
    // scalars its x, the vector (x, 1, -x).
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    for (int gen = 0; gen < kGenerations; ++gen)
        for (int feature = 0; feature < 5; ++feature)
            for (int dims : {2, 4})
                for (float bad : {nan, inf, -inf, 3e38f, -3e38f, 0.0f, 16.0f}) {
                    VoronoiSetup s;
                    s.dimensions = dims, s.generation = gen, s.feature = feature,
                    s.metric = dims == 2 ? Minkowski : 0;
                    StratumShaderNode n = voronoi_node(s);
                    for (int i = 1; i < 9; ++i) n.inputs[i] = STRATUM_INPUT_GENERATED;
                    NodeProgram program(n, std::vector<float>(8, 1.0f), 9);
                    ASSERT_EQ(program.status(), STRATUM_OK) << program.error();
                    program.run({bad, 1.0f, -bad}, kIn + 8, 9);
                }
}

}  // namespace
