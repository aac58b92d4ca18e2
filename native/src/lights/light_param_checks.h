// Range checks for a light model's check_own_params (lights/light.h): each returns the value or
// throws std::invalid_argument with a message that names it, worded as the C ABI's other checks
// (api/validation.cpp), which report it as an invalid argument.
#pragma once

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace stratum {

inline std::string light_param_text(float v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

inline void require_light_param(bool ok, const std::string& message) {
    if (!ok) throw std::invalid_argument(message);
}

// v in [lo, hi].
inline float light_param_in(float v, float lo, float hi, const char* what) {
    require_light_param(std::isfinite(v) && v >= lo && v <= hi,
                        std::string(what) + " = " + light_param_text(v) + " must be in [" +
                            light_param_text(lo) + ", " + light_param_text(hi) + "]");
    return v;
}

// v in (lo, hi].
inline float light_param_in_open(float v, float lo, float hi, const char* what) {
    require_light_param(std::isfinite(v) && v > lo && v <= hi,
                        std::string(what) + " = " + light_param_text(v) + " must be in (" +
                            light_param_text(lo) + ", " + light_param_text(hi) + "]");
    return v;
}

}  // namespace stratum
