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
// Channels: 1 grey, 2 grey + alpha, 3 RGB, 4 or more RGB + alpha (OIIO's alpha channel, else
// the fourth). Missing alpha reads 1. Alpha is returned straight: OIIO is asked to keep the
// file's unassociated alpha (PNG, TIFF), and associated data (OpenEXR) is divided by alpha
// where alpha > 0, as Blender's Straight/Premultiplied image handling gives the shader.
// Rows of the result run bottom to top (OIIO's top-to-bottom scanlines are flipped).
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace stratum {

// A file that cannot be read (STRATUM_ERROR_IO at the C ABI); the message names the file and
// carries OpenImageIO's own message.
class ImageReadError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct DecodedImage {
    uint32_t width = 0, height = 0;
    std::vector<float> rgba;  // width*height*4, row 0 at the bottom
};

DecodedImage read_image_file(const std::string& path);
// `file_name` (e.g. Blender's packed file's name) chooses the reader by its extension.
DecodedImage read_image_memory(const void* data, size_t size, const std::string& file_name);
// `pixels`: width*height*channels floats, rows bottom to top, channels 1..4.
DecodedImage image_from_pixels(const float* pixels, uint32_t width, uint32_t height, uint32_t channels);

}  // namespace stratum
