// Texture descriptions for the fuzzer: in-memory pixels, small image files in memory (valid
// ones written by OpenImageIO at start-up, then mutated, truncated, or given a PNG header
// that claims a huge size), files in the fuzzer's own temporary directory, and paths that are
// not regular files (a directory, a FIFO, /dev/zero, /dev/null, a missing file).
#pragma once

#include <string>
#include <vector>

#include "byte_reader.h"
#include "stratum/stratum.h"

namespace stratum::fuzz {

// Creates the temporary directory, its FIFO and the image templates. Called once.
void init_texture_sources();
// The fuzzer's private temporary directory (removed at exit).
const std::string& temp_dir();

// A texture description and the storage it points into.
struct TextureArrays {
    std::vector<float> pixels;
    std::string file_bytes, path, file_name, color_space, ocio_config;  // ocio_config "" = NULL
    bool use_pixels = false, use_file_data = false, use_path = false;
    bool null_file_name = false, null_color_space = false;
    StratumTextureDesc desc{};
    // Points desc at the storage: call it where the object will stay (a move of the short
    // strings moves their characters).
    void bind();
};

TextureArrays draw_texture(ByteReader& in);

}  // namespace stratum::fuzz
