// Writes a linear RGBA float image through OpenImageIO: float EXR for data, and 8-bit formats
// (PNG, ...) with the sRGB transfer function applied, since those store display values.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace stratum {

// rgba: width*height*4 floats, rows bottom to top. Returns "" on success, else the error.
std::string write_image(const std::string& path, const std::vector<float>& rgba, uint32_t width,
                        uint32_t height);

}  // namespace stratum
