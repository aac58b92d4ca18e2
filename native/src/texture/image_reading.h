// Reading a texture's pixels into linear-ready RGBA floats (before colour conversion), from a
// file OpenImageIO reads, from such a file's bytes in memory (Blender's packed images), or
// from a float array (Blender's Image.pixels).
//
// | source    | how                                                                     |
// |-----------|-------------------------------------------------------------------------|
// | path      | OIIO ImageInput, first subimage, mip level 0                            |
// | file_data | OIIO reads from an IOMemReader when the format's reader supports        |
// |           | "ioproxy" (in OIIO 2.4.7: PNG, JPEG, OpenEXR, HDR, TIFF, TGA, BMP, DDS, |
// |           | PNM, WebP, ...); otherwise (SGI, Cineon, HEIF, RAW, ...) the bytes go to |
// |           | a private temporary file that is read and removed                       |
// | pixels    | copied; rows already bottom to top                                      |
//
// The pixels are kept as the file stores them: 8-bit and 16-bit unsigned integers as such (a
// quarter or half of the memory of floats, and converted to scene linear through tables),
// everything else as 32-bit floats. Channels: 1 grey, 2 grey + alpha, 3 RGB, 4 or more RGB +
// alpha (OIIO's alpha channel, else the fourth). OIIO is asked to keep the file's unassociated
// alpha (PNG, TIFF); associated data (OpenEXR) is marked so and read as floats, to be divided by
// alpha as Blender's Straight/Premultiplied image handling gives the shader.
//
// Before any pixel memory is allocated, the header's size is checked against this machine's
// memory (kept image plus the float RGBA texture made from it, at most half of the physical
// memory): a 165-byte PNG may claim 65535 x 65535 pixels. Only regular files are opened: a
// FIFO or a device would block or never end.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/uninitialized_allocator.h"

namespace stratum {

// A file that cannot be read (STRATUM_ERROR_IO at the C ABI); the message names the file and
// carries OpenImageIO's own message.
class ImageReadError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

enum class StoredFormat { U8, U16, F32 };

struct StoredImage {
    uint32_t width = 0, height = 0;
    int channels = 0;
    int alpha_channel = -1;         // -1: none (alpha reads 1)
    bool associated_alpha = false;  // colour premultiplied by alpha (F32 only)
    bool top_to_bottom = true;      // row order of `data`
    StoredFormat format = StoredFormat::F32;
    UninitializedVector<unsigned char> storage;  // the pixels read from a file
    const void* data = nullptr;                  // the pixels: storage.data() or the caller's array
};

// Throws ImageReadError when decoding a width x height image of `channels` channels of
// `bytes_per_channel` bytes into a float RGBA texture, plus `reader_scratch_bytes` the image
// reader allocates on the way, needs more than the memory budget.
void check_decode_memory(const std::string& what, uint64_t width, uint64_t height, uint64_t channels,
                         uint64_t bytes_per_channel, double reader_scratch_bytes = 0.0);

StoredImage read_image_file(const std::string& path);
// `file_name` (e.g. Blender's packed file's name) chooses the reader by its extension.
StoredImage read_image_memory(const void* data, size_t size, const std::string& file_name);
// `pixels`: width*height*channels floats, rows bottom to top, channels 1..4; not copied.
StoredImage image_from_pixels(const float* pixels, uint32_t width, uint32_t height, uint32_t channels);

}  // namespace stratum
