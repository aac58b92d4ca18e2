#include "film/pixel_filter.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace stratum {

namespace {

constexpr size_t kTableSize = 1025;
// Buckets of the guide table: a power of two, so u × kGuideSize and b / kGuideSize are exact.
constexpr size_t kGuideSize = 1024;

const std::array kFilters = {
    RegistryEntry{"box", "Box", "Box filter: uniform offsets over a square of the filter width"},
    RegistryEntry{"blackman_harris", "Blackman-Harris",
                  "Blackman-Harris window, importance-sampled as in Cycles (support twice the filter width)"},
};

double profile(FilterType type, double x, double radius) {
    if (type == FilterType::Box) return 1.0;
    const double theta = 2.0 * 3.14159265358979323846 * (x / (2.0 * radius) + 0.5);
    return 0.35875 - 0.48829 * std::cos(theta) + 0.14128 * std::cos(2 * theta) -
           0.01168 * std::cos(3 * theta);
}

}  // namespace

std::span<const RegistryEntry> filter_registry() { return kFilters; }

bool parse_filter_type(std::string_view name, FilterType* out) {
    if (name == "box") {
        *out = FilterType::Box;
    } else if (name == "blackman_harris") {
        *out = FilterType::BlackmanHarris;
    } else {
        return false;
    }
    return true;
}

PixelFilter::PixelFilter(FilterType type, float width)
    : radius_(type == FilterType::Box ? 0.5f * width : width), cdf_(kTableSize) {
    // Trapezoid integration of the profile; the CDF is then piecewise linear, i.e. the pdf
    // piecewise constant between table points, and inverting it is exact for that pdf.
    const double step = 2.0 * radius_ / static_cast<double>(kTableSize - 1);
    double sum = 0.0, prev = profile(type, -radius_, radius_);
    std::vector<double> cdf(kTableSize, 0.0);
    for (size_t i = 1; i < kTableSize; ++i) {
        const double v = profile(type, -radius_ + step * static_cast<double>(i), radius_);
        sum += 0.5 * (prev + v) * step;
        cdf[i] = sum;
        prev = v;
    }
    for (size_t i = 0; i < kTableSize; ++i) cdf_[i] = static_cast<float>(cdf[i] / sum);
    cdf_.back() = 1.0f;
    // guide_[b] = the upper bound of u = b / G, monotone in b: the bound of any u in bucket b
    // lies between those of its two ends. The last entry covers u = 1 and beyond.
    guide_.resize(kGuideSize + 1);
    for (size_t b = 0; b < kGuideSize; ++b) {
        const float u = static_cast<float>(b) / static_cast<float>(kGuideSize);
        guide_[b] = static_cast<uint32_t>(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin());
    }
    guide_[kGuideSize] = static_cast<uint32_t>(kTableSize);
}

float PixelFilter::sample_1d(float u) const {
    const float scaled =
        u > 0.0f ? std::min(u * static_cast<float>(kGuideSize), static_cast<float>(kGuideSize - 1)) : 0.0f;
    const auto bucket = static_cast<size_t>(scaled);
    const auto it = std::upper_bound(cdf_.begin() + guide_[bucket], cdf_.begin() + guide_[bucket + 1], u);
    const size_t i = std::clamp<size_t>(static_cast<size_t>(it - cdf_.begin()), 1, kTableSize - 1) - 1;
    const float span = cdf_[i + 1] - cdf_[i];
    const float t = span > 0.0f ? (u - cdf_[i]) / span : 0.5f;
    const float step = 2.0f * radius_ / static_cast<float>(kTableSize - 1);
    return -radius_ + step * (static_cast<float>(i) + t);
}

float PixelFilter::pdf_1d(float x) const {
    if (!(std::abs(x) <= radius_)) return 0.0f;
    // sample_1d is uniform within table interval i with probability cdf[i+1] − cdf[i].
    const float step = 2.0f * radius_ / static_cast<float>(kTableSize - 1);
    const size_t i = std::min(static_cast<size_t>((x + radius_) / step), kTableSize - 2);
    return (cdf_[i + 1] - cdf_[i]) / step;
}

}  // namespace stratum
