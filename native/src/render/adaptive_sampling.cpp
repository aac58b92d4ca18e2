#include "render/adaptive_sampling.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>

namespace stratum {

namespace {

// Cycles' scale of the threshold ("makes the threshold more similar to what it was before").
constexpr double kThresholdScale = 5.0;
// Cycles' epsilon of the error's normaliser.
constexpr double kNormaliserEpsilon = 1e-4;

}  // namespace

AdaptiveSampling AdaptiveSampling::resolve(const AdaptiveSettings& settings, uint32_t samples) {
    AdaptiveSampling a;
    a.enabled = settings.enabled;
    a.threshold =
        settings.threshold > 0.0f ? settings.threshold : std::max(0.001, 1.0 / std::max(1u, samples));
    const double automatic = std::ceil(16.0 / std::pow(a.threshold, 0.3));
    const uint32_t wanted =
        settings.min_samples > 0 ? settings.min_samples : static_cast<uint32_t>(std::min(automatic, 1e9));
    a.min_samples = std::bit_ceil(std::max(4u, std::min(wanted, 1u << 30)));
    return a;
}

double relative_error(const Film& film, size_t pixel) {
    const Rgb mean = film.mean(pixel);
    const double s = static_cast<double>(mean.r) + mean.g + mean.b;
    const double normaliser = s < 1.0 ? std::sqrt(std::max(0.0, s)) : s;
    double sigma = 0.0;
    for (uint32_t c = 0; c < 3; ++c) sigma += film.standard_error(pixel, c);
    return std::sqrt(2.0 / std::numbers::pi) * sigma / (kNormaliserEpsilon + normaliser);
}

void stop_converged_pixels(const Film& film, const AdaptiveSampling& adaptive,
                           std::vector<uint8_t>& stopped) {
    const PixelRegion& region = film.region();
    const uint32_t w = region.width, h = region.height;
    const double limit = kThresholdScale * adaptive.threshold;
    // Unconverged: a sampling pixel without an estimate, or whose error is at the limit or above.
    std::vector<uint8_t> unconverged(region.pixel_count(), 0);
    for (size_t p = 0; p < unconverged.size(); ++p)
        unconverged[p] =
            !stopped[p] && (film.error_estimate(p).count == 0 || !(relative_error(film, p) < limit));
    // Cycles' box dilation: rows, then columns.
    std::vector<uint8_t> rows(unconverged.size(), 0);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const size_t p = static_cast<size_t>(y) * w + x;
            rows[p] = unconverged[p] || (x > 0 && unconverged[p - 1]) || (x + 1 < w && unconverged[p + 1]);
        }
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const size_t p = static_cast<size_t>(y) * w + x;
            const bool active = rows[p] || (y > 0 && rows[p - w]) || (y + 1 < h && rows[p + w]);
            if (!active) stopped[p] = 1;
        }
}

}  // namespace stratum
