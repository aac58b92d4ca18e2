// What the C ABI's validators (api/validation.cpp, api/geometry_validation.cpp) share besides
// `require` (api/validation.h): the text of the values their messages name.
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

inline std::string triple(const float* v) {
    return "(" + fmt(v[0]) + ", " + fmt(v[1]) + ", " + fmt(v[2]) + ")";
}

}  // namespace stratum::abi_checks
