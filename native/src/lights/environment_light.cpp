#include "lights/environment_light.h"

#include <algorithm>
#include <cmath>

#include "sampling/warps.h"

namespace stratum {

namespace {

// In double: the weights of an image near FLT_MAX (strength 3e38) must not overflow.
double luminance(Rgb c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

// Index k with cdf[k] <= u < cdf[k+1], skipping empty intervals.
uint32_t find_interval(const float* cdf, uint32_t n, float u) {
    const float* it = std::upper_bound(cdf, cdf + n + 1, u);
    uint32_t k = static_cast<uint32_t>(std::clamp<std::ptrdiff_t>(it - cdf - 1, 0, n - 1));
    while (k + 1 < n && cdf[k + 1] <= cdf[k]) ++k;  // u landed on an empty interval's edge
    while (k > 0 && cdf[k + 1] <= cdf[k]) --k;
    return k;
}

}  // namespace

EnvironmentLight::EnvironmentLight(std::vector<float> rgb, uint32_t width, uint32_t height,
                                   const std::array<float, 9>& rotation)
    : rgb_(std::move(rgb)), width_(width), height_(height), rotation_(rotation) {
    const size_t w = width_, h = height_;
    std::vector<double> weight(w * h);
    double total = 0.0;
    double sum[3] = {0.0, 0.0, 0.0};
    double solid_angle = 0.0;
    for (size_t j = 0; j < h; ++j) {
        const double sin_theta = std::sin(kPi * (static_cast<double>(j) + 0.5) / static_cast<double>(h));
        for (size_t i = 0; i < w; ++i) {
            const Rgb c = at(static_cast<uint32_t>(i), static_cast<uint32_t>(j));
            weight[j * w + i] = luminance(c) * sin_theta;
            total += weight[j * w + i];
            sum[0] += c.r * sin_theta;
            sum[1] += c.g * sin_theta;
            sum[2] += c.b * sin_theta;
        }
        solid_angle += sin_theta * static_cast<double>(w);
    }
    average_ = Rgb(saturate_to_float(sum[0] / solid_angle), saturate_to_float(sum[1] / solid_angle),
                   saturate_to_float(sum[2] / solid_angle));
    if (!(total > 0.0)) {  // black image: sample by solid angle
        total = 0.0;
        for (size_t j = 0; j < h; ++j) {
            const double sin_theta = std::sin(kPi * (static_cast<double>(j) + 0.5) / static_cast<double>(h));
            for (size_t i = 0; i < w; ++i) total += weight[j * w + i] = sin_theta;
        }
    }
    row_cdf_.assign(h + 1, 0.0f);
    column_cdf_.assign(h * (w + 1), 0.0f);
    density_.assign(w * h, 0.0f);
    double rows = 0.0;
    for (size_t j = 0; j < h; ++j) {
        double row = 0.0;
        for (size_t i = 0; i < w; ++i) row += weight[j * w + i];
        double running = 0.0;
        float* cdf = &column_cdf_[j * (w + 1)];
        for (size_t i = 0; i < w; ++i) {
            running += weight[j * w + i];
            cdf[i + 1] = row > 0.0 ? static_cast<float>(running / row)
                                   : static_cast<float>(i + 1) / static_cast<float>(w);
            density_[j * w + i] = static_cast<float>(weight[j * w + i] / total * static_cast<double>(w * h));
        }
        cdf[w] = 1.0f;
        rows += row;
        row_cdf_[j + 1] = static_cast<float>(rows / total);
    }
    row_cdf_[h] = 1.0f;
}

namespace {

// floor(x) clamped to [0, n): a NaN x (a direction that is not a number reaches no texel
// sensibly, but must not index outside the image either) reads texel 0.
uint32_t texel_index(float x, uint32_t n) {
    if (!(x > 0.0f)) return 0;
    return x >= static_cast<float>(n) ? n - 1 : static_cast<uint32_t>(x);
}

}  // namespace

EnvironmentLight::Texel EnvironmentLight::texel(Vec3 world_dir) const {
    const auto& r = rotation_;
    const Vec3 d(r[0] * world_dir.x + r[1] * world_dir.y + r[2] * world_dir.z,
                 r[3] * world_dir.x + r[4] * world_dir.y + r[5] * world_dir.z,
                 r[6] * world_dir.x + r[7] * world_dir.y + r[8] * world_dir.z);
    // θ by atan2 rather than Cycles' acos(z): the same angle, accurate near the poles, where
    // sin θ (the pdf's Jacobian) must be precise.
    const float rho = std::hypot(d.x, d.y);
    float u = 0.5f - std::atan2(d.y, d.x) / (2.0f * kPi);
    const float v = 1.0f - std::atan2(rho, d.z) / kPi;
    u -= std::floor(u);
    const uint32_t i = texel_index(u * static_cast<float>(width_), width_);
    const uint32_t j = texel_index((1.0f - v) * static_cast<float>(height_), height_);
    return {i, j, u, v, rho / length(d)};
}

Rgb EnvironmentLight::radiance(Vec3 world_dir) const {
    const Texel t = texel(world_dir);
    return at(t.i, t.j);
}

float EnvironmentLight::pdf(Vec3 world_dir) const {
    const Texel t = texel(world_dir);
    if (!(t.sin_theta > 0.0f)) return 0.0f;
    return density_[static_cast<size_t>(t.j) * width_ + t.i] / (2.0f * kPi * kPi * t.sin_theta);
}

bool EnvironmentLight::sample(Vec3 /*p*/, Vec3 /*n*/, Vec2 u, TriangleSampling /*triangle_sampling*/,
                              LightSample* out) const {
    return sample_direction(u, out);
}

bool EnvironmentLight::sample_direction(Vec2 u, LightSample* out) const {
    const uint32_t j = find_interval(row_cdf_.data(), height_, u.y);
    const float* cdf = &column_cdf_[static_cast<size_t>(j) * (width_ + 1)];
    const uint32_t i = find_interval(cdf, width_, u.x);
    // Reuse the remainder of each coordinate within its interval as the position in the texel.
    const float row_width = row_cdf_[j + 1] - row_cdf_[j];
    const float column_width = cdf[i + 1] - cdf[i];
    const float fy = row_width > 0.0f ? std::clamp((u.y - row_cdf_[j]) / row_width, 0.0f, 1.0f) : 0.5f;
    const float fx = column_width > 0.0f ? std::clamp((u.x - cdf[i]) / column_width, 0.0f, 1.0f) : 0.5f;
    const float tu = (static_cast<float>(i) + fx) / static_cast<float>(width_);
    const float tv = 1.0f - (static_cast<float>(j) + fy) / static_cast<float>(height_);
    // Inverse of texel(); θ kept off the poles (u = 0 exactly is a common sample), a shift of
    // measure zero.
    const float theta = std::clamp(kPi * (1.0f - tv), 1e-6f, kPi - 1e-6f), phi = kPi - 2.0f * kPi * tu;
    const float sin_theta = std::sin(theta);
    if (!(sin_theta > 0.0f)) return false;
    const Vec3 d(sin_theta * std::cos(phi), sin_theta * std::sin(phi), std::cos(theta));
    // Environment to world: the transpose of the rotation.
    const auto& r = rotation_;
    const Vec3 wi = normalize(Vec3(r[0] * d.x + r[3] * d.y + r[6] * d.z, r[1] * d.x + r[4] * d.y + r[7] * d.z,
                                   r[2] * d.x + r[5] * d.y + r[8] * d.z));
    // Radiance and pdf of the chosen texel: exactly the density this procedure sampled from. It
    // equals pdf(wi) except on texel edges, where the lookup may round to the neighbour.
    const float pdf = density_[static_cast<size_t>(j) * width_ + i] / (2.0f * kPi * kPi * sin_theta);
    if (!(pdf > 0.0f)) return false;
    *out = {wi, kInfinity, at(i, j), pdf, true};
    return true;
}

bool EnvironmentLight::sample_emission(Vec2 u_position, Vec2 u_direction, Vec3 center, float radius,
                                       EmissionSample* out) const {
    LightSample s;
    if (!sample_direction(u_direction, &s)) return false;
    const Frame frame = Frame::from_normal(s.wi);
    const Vec2 d = sample_uniform_disk_concentric(u_position);
    out->position = center + s.wi * radius + (frame.s * d.x + frame.t * d.y) * radius;
    out->direction = -s.wi;
    out->normal = s.wi;
    out->weight = s.radiance * (kPi * radius * radius / s.pdf);
    out->soft_radius = 0.0f;
    return true;
}

}  // namespace stratum
