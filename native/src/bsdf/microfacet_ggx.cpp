#include "bsdf/microfacet_ggx.h"

#include <array>
#include <memory>

#include "sampling/warps.h"

namespace stratum {

bool ggx_sample_reflection(Vec3 wo, float alpha, Vec2 u, Vec3* wi) {
    if (wo.z <= 0.0f) return false;
    const Vec3 h = sample_ggx_visible_normal(wo, alpha, u);
    *wi = h * (2.0f * dot(wo, h)) - wo;
    return wi->z > 0.0f;
}

namespace {

// Table axes: cos(theta_o) and roughness on uniform grids over [0, 1]; the dielectric axis is
// s = sqrt(F0) = (eta - 1)/(eta + 1) on [0, sqrt(0.99)] (F0 <= 0.99 as in ior_from_f0), on
// which the albedo is smooth (it grows like s^2 from 0 at eta = 1).
constexpr int kCosCount = 32, kRoughnessCount = 32, kRootF0Count = 32;
constexpr int kStrataPerAxis = 32;  // 1024 stratified VNDF samples per table entry
constexpr float kMinTableCos = 1e-3f;
const float kMaxRootF0 = std::sqrt(0.99f);

struct AlbedoTables {
    std::array<float, kCosCount * kRoughnessCount> unit;                            // E(mu, r)
    std::array<float, kCosCount * kRoughnessCount * kRootF0Count> dielectric;       // E_F(mu, r, s)
    std::array<float, kCosCount * kRoughnessCount * kRootF0Count> visible_fresnel;  // F_v(mu, r, s)
    std::array<float, kRoughnessCount> unit_average;                                // E_avg(r)
    std::array<float, kRootF0Count> fresnel_average;                                // F_avg(s)
};

float eta_from_root_f0(float s) { return (1.0f + s) / (1.0f - s); }

std::unique_ptr<const AlbedoTables> build_albedo_tables() {
    auto t = std::make_unique<AlbedoTables>();
    std::array<float, kRootF0Count> eta{};
    for (int k = 0; k < kRootF0Count; ++k)
        eta[k] = eta_from_root_f0(kMaxRootF0 * static_cast<float>(k) / static_cast<float>(kRootF0Count - 1));
    for (int j = 0; j < kRoughnessCount; ++j) {
        const float alpha = ggx_alpha_from_roughness(float(j) / (kRoughnessCount - 1));
        for (int i = 0; i < kCosCount; ++i) {
            const float mu = std::max(float(i) / (kCosCount - 1), kMinTableCos);
            const Vec3 wo(safe_sqrt(1.0f - mu * mu), 0.0f, mu);
            // VNDF importance sampling: f cos / pdf = F G2(wo, wi) / G1(wo), a bounded integrand,
            // so stratified midpoints converge fast and the table is deterministic.
            double unit_sum = 0.0;
            std::array<double, kRootF0Count> dielectric_sum{}, schlick_sum{};
            const float g1_o = ggx_g1(wo, alpha);
            for (int a = 0; a < kStrataPerAxis; ++a) {
                for (int b = 0; b < kStrataPerAxis; ++b) {
                    const Vec2 u{(static_cast<float>(a) + 0.5f) / static_cast<float>(kStrataPerAxis),
                                 (static_cast<float>(b) + 0.5f) / static_cast<float>(kStrataPerAxis)};
                    const Vec3 h = sample_ggx_visible_normal(wo, alpha, u);
                    const float cos_oh = dot(wo, h);
                    const Vec3 wi = h * (2.0f * cos_oh) - wo;
                    if (wi.z <= 0.0f) continue;
                    const float w = ggx_g2_height_correlated(wo, wi, alpha) / g1_o;
                    unit_sum += w;
                    for (int k = 0; k < kRootF0Count; ++k) {
                        const float f = fresnel_dielectric(cos_oh, eta[k]), f0 = f0_from_ior(eta[k]);
                        dielectric_sum[k] += w * f;
                        // Position of F between F0 and 1, unweighted by G2/G1 (see the header).
                        if (f0 < 1.0f) schlick_sum[k] += std::clamp((f - f0) / (1.0f - f0), 0.0f, 1.0f);
                    }
                }
            }
            const double n = double(kStrataPerAxis) * kStrataPerAxis;
            t->unit[j * kCosCount + i] = float(unit_sum / n);
            for (int k = 0; k < kRootF0Count; ++k) {
                const int at = (k * kRoughnessCount + j) * kCosCount + i;
                t->dielectric[at] = float(dielectric_sum[k] / n);
                const float f0 = f0_from_ior(eta[k]);
                t->visible_fresnel[at] = f0 + (1.0f - f0) * float(schlick_sum[k] / n);
            }
        }
        // E_avg = 2 int_0^1 E(mu) mu dmu by the trapezoid rule on the table nodes.
        double avg = 0.0;
        for (int i = 0; i < kCosCount; ++i) {
            const float mu = float(i) / (kCosCount - 1);
            const float w = (i == 0 || i == kCosCount - 1) ? 0.5f : 1.0f;
            avg += w * mu * t->unit[j * kCosCount + i];
        }
        t->unit_average[j] = float(2.0 * avg / (kCosCount - 1));
    }
    constexpr int kFresnelSteps = 1024;
    for (int k = 0; k < kRootF0Count; ++k) {
        double sum = 0.0;
        for (int i = 0; i < kFresnelSteps; ++i) {
            const float mu = (static_cast<float>(i) + 0.5f) / static_cast<float>(kFresnelSteps);
            sum += fresnel_dielectric(mu, eta[k]) * mu;
        }
        t->fresnel_average[k] = float(2.0 * sum / kFresnelSteps);
    }
    return t;
}

const AlbedoTables& albedo_tables() {
    static const std::unique_ptr<const AlbedoTables> tables = build_albedo_tables();  // thread-safe init
    return *tables;
}

// Position x in [0, 1] on a grid of n nodes -> lower node and fraction.
struct GridPos {
    int i;
    float f;
};
GridPos grid_pos(float x, int n) {
    const float p = std::clamp(x, 0.0f, 1.0f) * static_cast<float>(n - 1);
    const int i = std::min(int(p), n - 2);
    return {i, p - static_cast<float>(i)};
}

float bilinear(const float* table, GridPos mu, GridPos r) {
    const auto at = [&](int j, int i) { return table[j * kCosCount + i]; };
    const float lo = at(r.i, mu.i) * (1 - mu.f) + at(r.i, mu.i + 1) * mu.f;
    const float hi = at(r.i + 1, mu.i) * (1 - mu.f) + at(r.i + 1, mu.i + 1) * mu.f;
    return lo * (1 - r.f) + hi * r.f;
}

GridPos root_f0_pos(float eta) {
    const float s = (std::max(eta, 1.0f) - 1.0f) / (std::max(eta, 1.0f) + 1.0f);
    return grid_pos(s / kMaxRootF0, kRootF0Count);
}

}  // namespace

float ggx_albedo_unit_fresnel(float cos_o, float roughness) {
    return bilinear(albedo_tables().unit.data(), grid_pos(cos_o, kCosCount),
                    grid_pos(roughness, kRoughnessCount));
}

float ggx_average_albedo_unit_fresnel(float roughness) {
    const auto& t = albedo_tables().unit_average;
    const GridPos r = grid_pos(roughness, kRoughnessCount);
    return t[r.i] * (1 - r.f) + t[r.i + 1] * r.f;
}

float ggx_albedo_dielectric(float cos_o, float roughness, float eta) {
    const float* table = albedo_tables().dielectric.data();
    const GridPos mu = grid_pos(cos_o, kCosCount), r = grid_pos(roughness, kRoughnessCount);
    const GridPos s = root_f0_pos(eta);
    constexpr int kSlice = kCosCount * kRoughnessCount;
    return bilinear(table + s.i * kSlice, mu, r) * (1 - s.f) +
           bilinear(table + (s.i + 1) * kSlice, mu, r) * s.f;
}

float ggx_visible_fresnel_dielectric(float cos_o, float roughness, float eta) {
    const float* table = albedo_tables().visible_fresnel.data();
    const GridPos mu = grid_pos(cos_o, kCosCount), r = grid_pos(roughness, kRoughnessCount);
    const GridPos s = root_f0_pos(eta);
    constexpr int kSlice = kCosCount * kRoughnessCount;
    return bilinear(table + s.i * kSlice, mu, r) * (1 - s.f) +
           bilinear(table + (s.i + 1) * kSlice, mu, r) * s.f;
}

float fresnel_dielectric_average(float eta) {
    const auto& t = albedo_tables().fresnel_average;
    const GridPos s = root_f0_pos(eta);
    return t[s.i] * (1 - s.f) + t[s.i + 1] * s.f;
}

}  // namespace stratum
