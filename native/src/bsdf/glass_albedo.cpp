#include "bsdf/glass_albedo.h"

#include <array>
#include <memory>

#include "bsdf/glass.h"
#include "bsdf/microfacet_ggx.h"
#include "sampling/warps.h"

namespace stratum {

namespace {

constexpr int kCos = 32, kRough = 32, kEta = 33, kStrata = 16;
constexpr float kMinCos = 1e-3f, kMaxX = 0.5f;

float eta_from_x(float x) { return (1.0f + x) / (1.0f - x); }

float integrate(float mu, float alpha, float eta) {
    const Vec3 wo(safe_sqrt(1.0f - mu * mu), 0.0f, mu);
    const float g1o = ggx_g1(wo, alpha);
    double sum = 0.0;
    for (int a = 0; a < kStrata; ++a) {
        for (int b = 0; b < kStrata; ++b) {
            const Vec2 u{(static_cast<float>(a) + 0.5f) / kStrata, (static_cast<float>(b) + 0.5f) / kStrata};
            const Vec3 h = sample_ggx_visible_normal(wo, alpha, u);
            const float cos_oh = dot(wo, h);
            if (cos_oh <= 0.0f) continue;
            const float f = fresnel_dielectric(cos_oh, eta);
            const Vec3 wr = h * (2.0f * cos_oh) - wo;
            if (wr.z > 0.0f) sum += f * ggx_g2_height_correlated(wo, wr, alpha) / g1o;
            Vec3 wt;
            if (f < 1.0f && refract_direction(wo, h, eta, &wt) && wt.z < 0.0f) {
                sum += (1.0f - f) * ggx_g2_height_correlated(wo, Vec3(wt.x, wt.y, -wt.z), alpha) / g1o;
            }
        }
    }
    return static_cast<float>(sum / (kStrata * kStrata));
}

using Table = std::array<float, kCos * kRough * kEta>;

std::unique_ptr<const Table> build() {
    auto t = std::make_unique<Table>();
    for (int k = 0; k < kEta; ++k) {
        const float eta = eta_from_x(-kMaxX + 2.0f * kMaxX * static_cast<float>(k) / (kEta - 1));
        for (int j = 0; j < kRough; ++j) {
            const float alpha = ggx_alpha_from_roughness(static_cast<float>(j) / (kRough - 1));
            for (int i = 0; i < kCos; ++i) {
                const float mu = std::max(static_cast<float>(i) / (kCos - 1), kMinCos);
                (*t)[(k * kRough + j) * kCos + i] = integrate(mu, alpha, eta);
            }
        }
    }
    return t;
}

struct Pos {
    int i;
    float f;
};
Pos pos(float x, int n) {
    const float p = std::clamp(x, 0.0f, 1.0f) * static_cast<float>(n - 1);
    const int i = std::min(static_cast<int>(p), n - 2);
    return {i, p - static_cast<float>(i)};
}

}  // namespace

float ggx_glass_albedo(float cos_o, float roughness, float eta) {
    static const std::unique_ptr<const Table> table = build();
    const float x = (eta - 1.0f) / (eta + 1.0f);
    const Pos m = pos(cos_o, kCos), r = pos(roughness, kRough), e = pos((x + kMaxX) / (2.0f * kMaxX), kEta);
    const auto at = [&](int k, int j, int i) { return (*table)[(k * kRough + j) * kCos + i]; };
    float result = 0.0f;
    for (int dk = 0; dk < 2; ++dk) {
        for (int dj = 0; dj < 2; ++dj) {
            for (int di = 0; di < 2; ++di) {
                const float w = (dk ? e.f : 1.0f - e.f) * (dj ? r.f : 1.0f - r.f) * (di ? m.f : 1.0f - m.f);
                result += w * at(e.i + dk, r.i + dj, m.i + di);
            }
        }
    }
    return result;
}

}  // namespace stratum
