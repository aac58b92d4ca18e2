// The primitive checks the C ABI's validators share (api/validation.cpp,
// api/geometry_validation.cpp): each throws ValidationError with a message naming the value.
#pragma once

#include <sstream>
#include <string>

#include "api/validation.h"

namespace stratum::abi_checks {

inline std::string fmt(float v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

// For checks made once per call. Per-element loops test first and build the message only on
// failure: composing it eagerly cost seconds on a 200k-triangle mesh.
inline void check(bool ok, const std::string& message) {
    if (!ok) throw ValidationError(message);
}

inline std::string triple(const float* v) {
    return "(" + fmt(v[0]) + ", " + fmt(v[1]) + ", " + fmt(v[2]) + ")";
}

}  // namespace stratum::abi_checks
