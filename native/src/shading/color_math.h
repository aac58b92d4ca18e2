// Colour-model conversions the colour nodes share (Mix's Hue/Saturation/Value/Color blends,
// Hue/Saturation/Value, Separate/Combine Color, Color Ramp's HSV/HSL stops are baked by the host):
// RGB <-> HSV and RGB <-> HSL as Cycles defines them (util/color.h, the same in 3.4 and 5.0),
// including their edge cases: hue in [0, 1), a grey gives hue and saturation 0, HSV's hue 1 is
// hue 0, and HSV's sector index comes from floor(6 h) (a hue outside [0, 1] lands in the last
// sector, as Cycles' does). Components are not clamped: a negative colour converts as the
// formulas give.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/math.h"

namespace stratum {

// (hue, saturation, value) of an RGB colour, each a component of the returned Rgb.
inline Rgb rgb_to_hsv(Rgb c) {
    const float hi = std::fmax(c.r, std::fmax(c.g, c.b));
    const float lo = std::min(c.r, std::min(c.g, c.b));
    const float range = hi - lo;
    const float saturation = hi != 0.0f ? range / hi : 0.0f;
    if (saturation == 0.0f) return {0.0f, 0.0f, hi};
    // Distance of each component below the maximum, in units of the range.
    const float dr = (hi - c.r) / range, dg = (hi - c.g) / range, db = (hi - c.b) / range;
    float hue;
    if (c.r == hi)
        hue = db - dg;
    else if (c.g == hi)
        hue = 2.0f + dr - db;
    else
        hue = 4.0f + dg - dr;
    hue /= 6.0f;
    if (hue < 0.0f) hue += 1.0f;
    return {hue, saturation, hi};
}

inline Rgb hsv_to_rgb(Rgb hsv) {
    float h = hsv.r;
    const float s = hsv.g, v = hsv.b;
    if (s == 0.0f) return Rgb(v);
    if (h == 1.0f) h = 0.0f;
    h *= 6.0f;
    const float sector = std::floor(h);
    const float f = h - sector;
    const float p = v * (1.0f - s);
    const float q = v * (1.0f - s * f);
    const float t = v * (1.0f - s * (1.0f - f));
    if (sector == 0.0f) return {v, t, p};
    if (sector == 1.0f) return {q, v, p};
    if (sector == 2.0f) return {p, v, t};
    if (sector == 3.0f) return {p, q, v};
    if (sector == 4.0f) return {t, p, v};
    return {v, p, q};
}

// (hue, saturation, lightness); lightness is limited to 1 as Cycles limits it.
inline Rgb rgb_to_hsl(Rgb c) {
    const float hi = std::fmax(c.r, std::fmax(c.g, c.b));
    const float lo = std::min(c.r, std::min(c.g, c.b));
    const float lightness = std::min(1.0f, (hi + lo) / 2.0f);
    if (hi == lo) return {0.0f, 0.0f, lightness};
    const float range = hi - lo;
    const float saturation = lightness > 0.5f ? range / (2.0f - hi - lo) : range / (hi + lo);
    float hue;
    if (hi == c.r)
        hue = (c.g - c.b) / range + (c.g < c.b ? 6.0f : 0.0f);
    else if (hi == c.g)
        hue = (c.b - c.r) / range + 2.0f;
    else
        hue = (c.r - c.g) / range + 4.0f;
    return {hue / 6.0f, saturation, lightness};
}

inline Rgb hsl_to_rgb(Rgb hsl) {
    const float h6 = hsl.r * 6.0f, s = hsl.g, l = hsl.b;
    const float nr = std::clamp(std::fabs(h6 - 3.0f) - 1.0f, 0.0f, 1.0f);
    const float ng = std::clamp(2.0f - std::fabs(h6 - 2.0f), 0.0f, 1.0f);
    const float nb = std::clamp(2.0f - std::fabs(h6 - 4.0f), 0.0f, 1.0f);
    const float chroma = (1.0f - std::fabs(2.0f * l - 1.0f)) * s;
    return {(nr - 0.5f) * chroma + l, (ng - 0.5f) * chroma + l, (nb - 0.5f) * chroma + l};
}

}  // namespace stratum
