// Pixel reconstruction filter by importance sampling (as Cycles): each camera sample is
// offset from the pixel centre by a draw from the filter's 1D profile on each axis and
// weighted 1, so the pixel value is a plain mean and no sample touches another pixel.
//
// | filter          | profile on x ∈ [−R, R] | R (width w in pixels, Blender's filter_width) |
// |-----------------|------------------------|------------------------------------------------|
// | box             | 1                      | w / 2 |
// | blackman_harris | 0.35875 − 0.48829 cos(θ) + 0.14128 cos(2θ) − 0.01168 cos(3θ), θ = 2π(x/(2R) + ½) | w
// (Cycles doubles the width of this filter) |
//
// Blackman-Harris window: Harris 1978, "On the use of windows for harmonic analysis with the
// discrete Fourier transform", 4-term. The profile is tabulated and its CDF inverted.
#pragma once

#include <span>
#include <string_view>
#include <vector>

#include "core/math.h"
#include "core/registry.h"

namespace stratum {

enum class FilterType { Box, BlackmanHarris };

std::span<const RegistryEntry> filter_registry();
// Returns false when the name is not a filter.
bool parse_filter_type(std::string_view name, FilterType* out);

class PixelFilter {
public:
    PixelFilter(FilterType type, float width);
    // Offset from the pixel centre, in pixels.
    Vec2 sample(Vec2 u) const { return {sample_1d(u.x), sample_1d(u.y)}; }
    float radius() const { return radius_; }
    // The density sample() draws offsets from (per pixel², 0 outside [−R, R]²): the light
    // tracer splats a film point at offset d from a pixel centre with weight pdf(d), so a
    // pixel's splats and its camera samples estimate the same ∫ h(x − p) L(x) dx.
    float pdf(Vec2 offset) const { return pdf_1d(offset.x) * pdf_1d(offset.y); }

private:
    float sample_1d(float u) const;
    float pdf_1d(float x) const;
    float radius_;
    std::vector<float> cdf_;  // cdf_[i] = CDF at x_i = −R + 2R i / (n − 1)
    // Guide table: u in [b/G, (b+1)/G) has its upper bound in cdf_ between guide_[b] and
    // guide_[b + 1] (inclusive), so sample_1d searches a few entries instead of all n.
    std::vector<uint32_t> guide_;
};

}  // namespace stratum
