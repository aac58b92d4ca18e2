// stratum_vertex_normals: the angle-weighted vertex normals follow their definition (stratum.h)
// to float rounding, are the same bits for any thread count, take the position's direction
// where the sum is zero, and every bad input is refused naming the value.
#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace {

struct PolygonMesh {
    std::vector<float> positions;
    std::vector<uint32_t> starts, sizes, corners;
    std::vector<float> face_normals;

    uint32_t vertex_count() const { return static_cast<uint32_t>(positions.size() / 3); }
    uint32_t face_count() const { return static_cast<uint32_t>(sizes.size()); }
    uint32_t corner_count() const { return static_cast<uint32_t>(corners.size()); }
    void add_face(std::vector<uint32_t> vertices, float nx, float ny, float nz) {
        starts.push_back(corner_count());
        sizes.push_back(static_cast<uint32_t>(vertices.size()));
        corners.insert(corners.end(), vertices.begin(), vertices.end());
        face_normals.insert(face_normals.end(), {nx, ny, nz});
    }
};

StratumStatus normals_of(const PolygonMesh& m, uint32_t threads, std::vector<float>& out) {
    out.assign(m.positions.size(), -7.0f);
    return stratum_vertex_normals(m.vertex_count(), m.positions.data(), m.face_count(), m.starts.data(),
                                  m.sizes.data(), m.face_normals.data(), m.corner_count(), m.corners.data(),
                                  threads, out.data());
}

// Faces of 1 to 6 corners over random vertices at scales 1e-3 .. 1e3, with repeated vertices
// (zero edges), zero face normals, and vertices without faces (the last one at the origin).
PolygonMesh random_mesh(uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> normal;
    const float scales[] = {1e-3f, 1.0f, 1e3f};
    PolygonMesh m;
    const uint32_t n_vert = 3000, n_used = 2500;
    for (uint32_t v = 0; v < n_vert; ++v) {
        const float s = scales[rng() % 3];
        for (int k = 0; k < 3; ++k) m.positions.push_back(v + 1 == n_vert ? 0.0f : normal(rng) * s);
    }
    for (uint32_t f = 0; f < 6000; ++f) {
        std::vector<uint32_t> face(1 + rng() % 6);
        for (uint32_t& v : face) v = static_cast<uint32_t>(rng() % n_used);
        if (f % 50 == 0) face.back() = face.front();
        float n[3] = {normal(rng), normal(rng), normal(rng)};
        const float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        const float scale = f % 97 == 0 ? 0.0f : 1.0f / length;
        m.add_face(face, n[0] * scale, n[1] * scale, n[2] * scale);
    }
    return m;
}

// The definition as stratum.h words it (acos of the unit edges' dot product) evaluated face by
// face in long double (64-bit mantissa on x86-64), with a bound per vertex on the difference
// from the library's double evaluation.
struct Reference {
    std::vector<long double> normal;  // 3 per vertex
    std::vector<double> bound;        // per vertex, on |library - reference|
};

Reference reference_normals(const PolygonMesh& m) {
    using L = long double;
    const size_t n = m.vertex_count();
    std::vector<L> sum(3 * n, 0.0L), weight(n, 0.0L), slack(n, 0.0L);
    const auto p = [&](uint32_t v, int k) { return static_cast<L>(m.positions[3 * v + k]); };
    for (uint32_t f = 0; f < m.face_count(); ++f) {
        const uint32_t s = m.starts[f], size = m.sizes[f];
        for (uint32_t k = 0; k < size; ++k) {
            const uint32_t v = m.corners[s + k], prev = m.corners[s + (k + size - 1) % size],
                           next = m.corners[s + (k + 1) % size];
            L a[3], b[3], aa = 0, bb = 0, ab = 0;
            for (int i = 0; i < 3; ++i) {
                a[i] = p(prev, i) - p(v, i);
                b[i] = p(next, i) - p(v, i);
                aa += a[i] * a[i];
                bb += b[i] * b[i];
                ab += a[i] * b[i];
            }
            const L cosine = (aa > 0 && bb > 0) ? ab / std::sqrt(aa * bb) : 0.0L;
            const L theta = std::acos(std::clamp(cosine, -1.0L, 1.0L));
            for (int i = 0; i < 3; ++i) sum[3 * v + i] += static_cast<L>(m.face_normals[3 * f + i]) * theta;
            // The library's theta, atan2(|a x b|, a . b) in double (u = 2^-53): the rounded
            // differences, cross and dot products perturb both arguments by about 4 u |a| |b|,
            // so the angle by about 8 u, plus its rounding u theta; bounded here by 16 u + u theta.
            // This reference's acos of a cosine off by about 10 u_L (u_L = 2^-64) is off by
            // 10 u_L / sin(theta) (acos' derivative), at most sqrt(20 u_L) (acos(1 - d) =
            // sqrt(2 d) near 0 and pi).
            const L u = std::ldexp(1.0L, -53), u_long = std::ldexp(1.0L, -64);
            const L sine = std::sqrt(std::max(L(0), 1 - cosine * cosine));
            const L acos_error = std::sqrt(20 * u_long);
            slack[v] +=
                16 * u + u * theta + (sine > 0 ? std::min(acos_error, 10 * u_long / sine) : acos_error);
            weight[v] += theta;
        }
    }
    Reference r{std::vector<long double>(3 * n), std::vector<double>(n)};
    for (size_t v = 0; v < n; ++v) {
        L* s = &sum[3 * v];
        L length = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
        // The sums' own rounding: (corners + 2) u of each term's size, generously 64 u.
        L delta = slack[v] + 64 * std::ldexp(1.0L, -53) * weight[v];
        if (length == 0) {  // the fallback: the position's direction
            for (int i = 0; i < 3; ++i) s[i] = p(static_cast<uint32_t>(v), i);
            length = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
            delta = 0;
        }
        for (int i = 0; i < 3; ++i) r.normal[3 * v + i] = length > 0 ? s[i] / length : 0.0L;
        // Normalising moves a unit vector by at most 2 |delta| / |s|; the result is then
        // rounded to float: at most half an ulp, 2^-25 for components below 1 in magnitude.
        r.bound[v] =
            static_cast<double>(length > 0 ? 2 * delta / length : 0.0L) + std::ldexp(1.0, -25) + 1e-15;
    }
    return r;
}

TEST(AngleWeightedNormals, CubeCornersPointAlongTheDiagonals) {
    PolygonMesh m;
    for (int v = 0; v < 8; ++v)
        m.positions.insert(m.positions.end(),
                           {v & 1 ? 1.0f : -1.0f, v & 2 ? 1.0f : -1.0f, v & 4 ? 1.0f : -1.0f});
    m.add_face({0, 2, 3, 1}, 0, 0, -1);
    m.add_face({4, 5, 7, 6}, 0, 0, 1);
    m.add_face({0, 1, 5, 4}, 0, -1, 0);
    m.add_face({2, 6, 7, 3}, 0, 1, 0);
    m.add_face({0, 4, 6, 2}, -1, 0, 0);
    m.add_face({1, 3, 7, 5}, 1, 0, 0);
    std::vector<float> out;
    ASSERT_EQ(normals_of(m, 0, out), STRATUM_OK);
    const float c = static_cast<float>(1.0 / std::sqrt(3.0));
    for (int v = 0; v < 8; ++v) {
        EXPECT_EQ(out[3 * v], v & 1 ? c : -c) << "vertex " << v;
        EXPECT_EQ(out[3 * v + 1], v & 2 ? c : -c) << "vertex " << v;
        EXPECT_EQ(out[3 * v + 2], v & 4 ? c : -c) << "vertex " << v;
    }
}

// A wedge: vertex 0's two faces meet at angles pi/2 and pi/4, so its normal leans 2:1 towards
// the first face's normal, not 1:1 (no weighting) or by area.
TEST(AngleWeightedNormals, CornersWeighByTheirInteriorAngle) {
    PolygonMesh m;
    m.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 0, 1};
    m.add_face({0, 1, 2}, 0, 0, 1);  // right angle at vertex 0
    m.add_face({0, 3, 1}, 0, 1, 0);  // pi/4 at vertex 0
    std::vector<float> out;
    ASSERT_EQ(normals_of(m, 0, out), STRATUM_OK);
    const double length = std::sqrt(0.25 * 0.25 + 0.5 * 0.5);  // pi/2 (0,0,1) + pi/4 (0,1,0), / pi
    // Within one float ulp (2^-24 below 1): the exact value rounded, the double evaluation's
    // own error (about 1e-16) can tip the rounding only by that.
    const double ulp = std::ldexp(1.0, -24);
    EXPECT_EQ(out[0], 0.0f);
    EXPECT_NEAR(out[1], 0.25 / length, ulp);
    EXPECT_NEAR(out[2], 0.5 / length, ulp);
}

TEST(AngleWeightedNormals, FollowTheDefinitionToFloatRounding) {
    for (uint32_t seed : {1u, 2u, 3u}) {
        const PolygonMesh m = random_mesh(seed);
        std::vector<float> out;
        ASSERT_EQ(normals_of(m, 0, out), STRATUM_OK) << stratum_last_error();
        const Reference r = reference_normals(m);
        for (uint32_t v = 0; v < m.vertex_count(); ++v) {
            double error = 0;
            for (int i = 0; i < 3; ++i)
                error = std::max(error, std::abs(static_cast<double>(out[3 * v + i] - r.normal[3 * v + i])));
            ASSERT_LE(error, r.bound[v])
                << "seed " << seed << " vertex " << v << ": (" << out[3 * v] << ", " << out[3 * v + 1] << ", "
                << out[3 * v + 2] << ") vs (" << static_cast<double>(r.normal[3 * v]) << ", "
                << static_cast<double>(r.normal[3 * v + 1]) << ", "
                << static_cast<double>(r.normal[3 * v + 2]) << "), position (" << m.positions[3 * v] << ", "
                << m.positions[3 * v + 1] << ", " << m.positions[3 * v + 2] << ")";
        }
        // Vertices without faces take their position's direction (checked above); the origin's
        // stays zero.
        const size_t origin = m.positions.size() - 3;
        EXPECT_EQ(out[origin], 0.0f);
        EXPECT_EQ(out[origin + 1], 0.0f);
        EXPECT_EQ(out[origin + 2], 0.0f);
    }
}

TEST(AngleWeightedNormals, TheSameBitsForAnyThreadCount) {
    const PolygonMesh m = random_mesh(4);
    std::vector<float> first, other;
    ASSERT_EQ(normals_of(m, 1, first), STRATUM_OK);
    for (uint32_t threads : {2u, 7u, 0u}) {
        ASSERT_EQ(normals_of(m, threads, other), STRATUM_OK);
        EXPECT_EQ(std::memcmp(first.data(), other.data(), first.size() * sizeof(float)), 0)
            << threads << " threads";
    }
}

// Each bad input returns INVALID_ARGUMENT, names the value, and leaves the output untouched.
void expect_refused(const PolygonMesh& m, uint32_t threads, const std::string& named) {
    std::vector<float> out;
    EXPECT_EQ(normals_of(m, threads, out), STRATUM_ERROR_INVALID_ARGUMENT);
    const std::string error = stratum_last_error();
    EXPECT_NE(error.find(named), std::string::npos) << error;
    EXPECT_TRUE(std::all_of(out.begin(), out.end(), [](float x) { return x == -7.0f; }));
}

TEST(AngleWeightedNormals, BadInputIsRefusedNamingTheValue) {
    PolygonMesh good;
    good.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    good.add_face({0, 1, 3, 2}, 0, 0, 1);
    std::vector<float> out;
    ASSERT_EQ(normals_of(good, 0, out), STRATUM_OK);

    PolygonMesh m = good;
    m.corners[2] = 4;
    expect_refused(m, 0, "corner 2 vertex index 4 out of range [0, 4)");
    m = good;
    m.positions[4] = NAN;
    expect_refused(m, 0, "vertex 1 has a non-finite position");
    m = good;
    m.face_normals[2] = INFINITY;
    expect_refused(m, 0, "face 0 has a non-finite normal");
    m = good;
    m.sizes[0] = 0;
    expect_refused(m, 0, "face 0 (corners 0 .. +0) has no corners");
    m = good;
    m.starts[0] = 1;
    expect_refused(m, 0, "face 0 (corners 1 .. +4) runs past corner_count 4");
    m = good;
    m.starts[0] = 0xFFFFFFFFu;  // start + size overflows 32 bits
    expect_refused(m, 0, "runs past corner_count 4");
    m = good;
    m.add_face({0, 1, 2}, 0, 0, 1);
    m.starts[1] = 0;  // two faces over the same corners: 7 face corners of 7 ...
    m.sizes[1] = 4;
    m.corners.resize(4);  // ... but only 4 corners
    expect_refused(m, 0, "face 1 (corners 0 .. +4) brings the faces' corners past corner_count 4");
    expect_refused(good, 1025, "threads = 1025 out of range [0, 1024]");

    EXPECT_EQ(stratum_vertex_normals(4, nullptr, 1, good.starts.data(), good.sizes.data(),
                                     good.face_normals.data(), 4, good.corners.data(), 0, out.data()),
              STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(stratum_vertex_normals(4, good.positions.data(), 1, good.starts.data(), good.sizes.data(),
                                     good.face_normals.data(), 4, good.corners.data(), 0, nullptr),
              STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("out_normals is NULL"), std::string::npos);
    // Zero counts need no arrays.
    EXPECT_EQ(stratum_vertex_normals(0, nullptr, 0, nullptr, nullptr, nullptr, 0, nullptr, 0, nullptr),
              STRATUM_OK);
}

}  // namespace
