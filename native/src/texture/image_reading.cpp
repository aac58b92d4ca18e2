#include "texture/image_reading.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <stdlib.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <memory>

namespace stratum {

namespace {

// Copies interleaved `channels`-channel pixels (rows in `top_to_bottom` order or not) into
// RGBA with row 0 at the bottom. alpha_channel < 0: no alpha (reads 1).
DecodedImage to_rgba(const float* src, uint32_t width, uint32_t height, int channels, int alpha_channel,
                     bool top_to_bottom, bool associated_alpha) {
    DecodedImage image;
    image.width = width;
    image.height = height;
    image.rgba.resize(static_cast<size_t>(width) * height * 4);
    const int colour_channels = channels - (alpha_channel >= 0 ? 1 : 0);
    // The colour channels are the first ones other than alpha.
    int colour[3] = {0, 0, 0};
    for (int c = 0, k = 0; c < channels && k < 3; ++c) {
        if (c != alpha_channel) colour[k++] = c;
    }
    if (colour_channels < 3) colour[1] = colour[2] = colour[0];  // grey
    for (uint32_t y = 0; y < height; ++y) {
        const uint32_t src_row = top_to_bottom ? height - 1 - y : y;
        for (uint32_t x = 0; x < width; ++x) {
            const float* p = src + (static_cast<size_t>(src_row) * width + x) * channels;
            float* q = &image.rgba[(static_cast<size_t>(y) * width + x) * 4];
            const float a = alpha_channel >= 0 ? p[alpha_channel] : 1.0f;
            const float unassociate = (associated_alpha && a > 0.0f) ? 1.0f / a : 1.0f;
            for (int k = 0; k < 3; ++k) q[k] = p[colour[k]] * unassociate;
            q[3] = a;
        }
    }
    return image;
}

int alpha_channel_of(const OIIO::ImageSpec& spec) {
    if (spec.alpha_channel >= 0 && spec.alpha_channel < spec.nchannels) return spec.alpha_channel;
    if (spec.nchannels == 2) return 1;
    if (spec.nchannels >= 4) return 3;
    return -1;
}

// Reads the first subimage of an opened input; `what` names the image in messages.
DecodedImage read_opened(OIIO::ImageInput& in, const std::string& what) {
    const OIIO::ImageSpec& spec = in.spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth > 1) {
        throw ImageReadError("image '" + what + "' has an unsupported shape (" + std::to_string(spec.width) +
                             " x " + std::to_string(spec.height) + " x " + std::to_string(spec.depth) + ", " +
                             std::to_string(spec.nchannels) + " channels)");
    }
    std::vector<float> pixels(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
    if (!in.read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data())) {
        throw ImageReadError("cannot read image '" + what + "': " + in.geterror());
    }
    const int alpha = alpha_channel_of(spec);
    // With oiio:UnassociatedAlpha requested, readers of straight-alpha formats report 1 here;
    // formats that store associated alpha (OpenEXR) do not.
    const bool associated = alpha >= 0 && spec.get_int_attribute("oiio:UnassociatedAlpha", 0) == 0;
    return to_rgba(pixels.data(), static_cast<uint32_t>(spec.width), static_cast<uint32_t>(spec.height),
                   spec.nchannels, alpha, true, associated);
}

OIIO::ImageSpec read_config() {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    return config;
}

// A private temporary file holding `size` bytes, removed when this object goes away.
class TemporaryFile {
public:
    TemporaryFile(const void* data, size_t size, const std::string& extension) {
        path_ = (std::filesystem::temp_directory_path() / ("stratum-texture-XXXXXX" + extension)).string();
        const int fd = mkstemps(path_.data(), static_cast<int>(extension.size()));  // mode 0600
        if (fd < 0) throw ImageReadError("cannot create a temporary file for an in-memory image");
        FILE* f = fdopen(fd, "wb");
        const bool written = f && std::fwrite(data, 1, size, f) == size;
        if (f ? std::fclose(f) != 0 : close(fd) != 0) {
            std::remove(path_.c_str());
            throw ImageReadError("cannot write a temporary file for an in-memory image");
        }
        if (!written) {
            std::remove(path_.c_str());
            throw ImageReadError("cannot write a temporary file for an in-memory image");
        }
    }
    ~TemporaryFile() { std::remove(path_.c_str()); }
    TemporaryFile(const TemporaryFile&) = delete;
    TemporaryFile& operator=(const TemporaryFile&) = delete;
    const std::string& path() const { return path_; }

private:
    std::string path_;
};

}  // namespace

DecodedImage read_image_file(const std::string& path) {
    const OIIO::ImageSpec config = read_config();
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path, &config);
    if (!in) throw ImageReadError("cannot open image '" + path + "': " + OIIO::geterror());
    return read_opened(*in, path);
}

DecodedImage read_image_memory(const void* data, size_t size, const std::string& file_name) {
    const std::string extension = std::filesystem::path(file_name).extension().string();
    const std::string what = file_name + " (in memory, " + std::to_string(size) + " bytes)";
    OIIO::Filesystem::IOMemReader proxy(const_cast<void*>(data), size);
    // Created by format (the extension alone): given the file name, OIIO would look for the file.
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::create(extension.substr(1));
    if (!in) throw ImageReadError("no image reader for '" + what + "': " + OIIO::geterror());
    if (in->supports("ioproxy")) {
        OIIO::ImageSpec config = read_config();
        OIIO::Filesystem::IOProxy* proxy_ptr = &proxy;
        config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy_ptr);
        OIIO::ImageSpec spec;
        if (!in->open(file_name, spec, config)) {
            throw ImageReadError("cannot open image '" + what + "': " + in->geterror());
        }
        return read_opened(*in, what);
    }
    // This format's reader only reads files.
    const TemporaryFile file(data, size, extension);
    const OIIO::ImageSpec config = read_config();
    std::unique_ptr<OIIO::ImageInput> from_file = OIIO::ImageInput::open(file.path(), &config);
    if (!from_file) throw ImageReadError("cannot open image '" + what + "': " + OIIO::geterror());
    return read_opened(*from_file, what);
}

DecodedImage image_from_pixels(const float* pixels, uint32_t width, uint32_t height, uint32_t channels) {
    const int c = static_cast<int>(channels);
    const int alpha = (c == 2 || c == 4) ? c - 1 : -1;
    return to_rgba(pixels, width, height, c, alpha, false, false);
}

}  // namespace stratum
