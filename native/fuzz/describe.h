// Readable text of the ABI's descriptors, for the fuzzer's call trace: C designated
// initialisers that can be pasted into a GoogleTest case (non-finite values print as
// INFINITY / NAN, which <cmath> defines).
#pragma once

#include <cstdint>
#include <string>

#include "stratum/stratum.h"

namespace stratum::fuzz {

std::string describe_float(float v);
std::string describe_floats(const float* v, size_t n);
// {1, 2, 3}, or NULL.
std::string describe_uints(const uint32_t* v, size_t n);
std::string describe_string(const char* s);
std::string describe(const StratumMaterialDesc& d);
std::string describe(const StratumCameraDesc& d);
std::string describe(const StratumLightDesc& d);
std::string describe(const StratumInstanceDesc& d);
std::string describe(const StratumMeshDesc& d);
std::string describe(const StratumTextureDesc& d);
std::string describe(const StratumTextureBinding& d);

}  // namespace stratum::fuzz
