// The rendered region of a frame: a border render's rectangle, or the whole frame.
#pragma once

#include <cstddef>
#include <cstdint>

namespace stratum {

// In pixels of the full frame, bottom-left origin.
struct PixelRegion {
    uint32_t x = 0, y = 0, width = 0, height = 0;

    size_t pixel_count() const { return static_cast<size_t>(width) * height; }
    // Index of full-frame pixel (fx, fy) in the region's buffers (rows bottom to top).
    size_t index(uint32_t fx, uint32_t fy) const { return static_cast<size_t>(fy - y) * width + (fx - x); }
    bool contains(uint32_t fx, uint32_t fy) const {
        return fx >= x && fy >= y && fx - x < width && fy - y < height;
    }
};

}  // namespace stratum
