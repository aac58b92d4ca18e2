#include "render/render_settings.h"

namespace stratum {

std::string crop_region(const RenderSettings& s, PixelRegion* out) {
    if (s.crop_width == 0) {
        if (s.crop_height != 0 || s.crop_x != 0 || s.crop_y != 0) {
            return "border region: crop_width = 0 (the whole frame) but crop_x = " +
                   std::to_string(s.crop_x) + ", crop_y = " + std::to_string(s.crop_y) +
                   ", crop_height = " + std::to_string(s.crop_height) + " (all must be 0)";
        }
        *out = {0, 0, s.width, s.height};
        return {};
    }
    if (s.crop_height == 0)
        return "border region: crop_height = 0 with crop_width = " + std::to_string(s.crop_width);
    const auto outside = [](const char* axis, uint32_t start, uint32_t size, uint32_t frame) {
        return std::string("border region outside the frame: crop_") + axis + " = " + std::to_string(start) +
               " + crop_" + (axis[0] == 'x' ? "width" : "height") + " = " + std::to_string(size) +
               " exceeds " + (axis[0] == 'x' ? "width" : "height") + " = " + std::to_string(frame);
    };
    if (static_cast<uint64_t>(s.crop_x) + s.crop_width > s.width)
        return outside("x", s.crop_x, s.crop_width, s.width);
    if (static_cast<uint64_t>(s.crop_y) + s.crop_height > s.height)
        return outside("y", s.crop_y, s.crop_height, s.height);
    *out = {s.crop_x, s.crop_y, s.crop_width, s.crop_height};
    return {};
}

std::string sample_range(const RenderSettings& s, uint32_t* begin, uint32_t* end) {
    if (s.sample_offset >= s.samples)
        return "sample subset: sample_offset = " + std::to_string(s.sample_offset) +
               " is not below samples = " + std::to_string(s.samples);
    const uint64_t last = s.sample_count == 0 ? s.samples : uint64_t{s.sample_offset} + s.sample_count;
    if (last > s.samples)
        return "sample subset: sample_offset = " + std::to_string(s.sample_offset) +
               " + sample_count = " + std::to_string(s.sample_count) +
               " exceeds samples = " + std::to_string(s.samples);
    *begin = s.sample_offset;
    *end = static_cast<uint32_t>(last);
    return {};
}

}  // namespace stratum
