#include "render/image_output.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>

namespace stratum {

namespace {

bool is_float_format(const std::string& path) {
    const auto dot = path.rfind('.');
    if (dot == std::string::npos) return false;
    std::string ext = path.substr(dot + 1);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext == "exr" || ext == "hdr" || ext == "pfm";
}

// IEC 61966-2-1 sRGB encoding.
float srgb_encode(float v) {
    v = std::clamp(v, 0.0f, 1.0f);
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

}  // namespace

std::string write_image(const std::string& path, const std::vector<float>& rgba, uint32_t width,
                        uint32_t height) {
    auto out = OIIO::ImageOutput::create(path);
    if (!out) return "cannot write '" + path + "': " + OIIO::geterror();
    const bool linear = is_float_format(path);
    OIIO::ImageSpec spec(static_cast<int>(width), static_cast<int>(height), 4,
                         linear ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
    // Files store rows top to bottom; the render buffer runs bottom to top.
    std::vector<float> flipped(rgba.size());
    const size_t row = static_cast<size_t>(width) * 4;
    for (uint32_t y = 0; y < height; ++y) {
        const float* src = &rgba[static_cast<size_t>(height - 1 - y) * row];
        float* dst = &flipped[static_cast<size_t>(y) * row];
        for (size_t i = 0; i < row; ++i) dst[i] = (linear || i % 4 == 3) ? src[i] : srgb_encode(src[i]);
    }
    if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, flipped.data()) || !out->close()) {
        return "cannot write '" + path + "': " + out->geterror();
    }
    return {};
}

}  // namespace stratum
