// Small float helpers the pattern textures share, with Cycles' behaviour on the edges (util/math
// of Cycles 3.4 and 5.0): float to int as the x86 conversion Cycles' CPU kernel compiles to (a
// NaN or out-of-range value gives INT_MIN, never undefined behaviour here), saturate mapping NaN
// to 0, and both generations of smoothstep (3.4's is not clamped).
#pragma once

#include <climits>
#include <cmath>
#include <cstdint>

namespace stratum::pattern_math {

// (int)f as an x86 cvttss2si: truncation, and INT_MIN for NaN or a value outside int's range.
inline int32_t float_to_int(float f) {
    if (!(f >= -2147483648.0f && f < 2147483648.0f)) return INT32_MIN;
    return static_cast<int32_t>(f);
}

inline int32_t floor_to_int(float f) { return float_to_int(std::floor(f)); }

// min(max(v, 0), 1) with fminf/fmaxf: NaN reads 0.
inline float saturate(float v) { return std::fmin(std::fmax(v, 0.0f), 1.0f); }

// Cycles 3.4's smoothstepf: 3 f^2 - 2 f^3 without clamping.
inline float smoothstep_unclamped(float f) {
    const float ff = f * f;
    return 3.0f * ff - 2.0f * ff * f;
}

// Cycles 3.5+'s smoothstepf: 0 at or below 0, 1 at or above 1.
inline float smoothstep_clamped(float f) {
    if (f <= 0.0f) return 0.0f;
    if (f >= 1.0f) return 1.0f;
    return smoothstep_unclamped(f);
}

}  // namespace stratum::pattern_math
