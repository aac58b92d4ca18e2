#include "texture/image_reading.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <new>
#include <system_error>

#include "core/memory_budget.h"

namespace stratum {

namespace {

int alpha_channel_of(const OIIO::ImageSpec& spec) {
    if (spec.alpha_channel >= 0 && spec.alpha_channel < spec.nchannels) return spec.alpha_channel;
    if (spec.nchannels == 2) return 1;
    if (spec.nchannels >= 4) return 3;
    return -1;
}

// What ImageInput::read_scanlines (OIIO 2.4, imageinput.cpp) allocates when it converts: a
// buffer of max(2^26 / scanline bytes, oiio_read_chunk = 256) native scanlines, rounded up to
// a multiple of 64, whatever the image's height. A 66-byte BMP claiming rows of 218 million
// pixels (2 rows) made it ask for 167 GB (found by the fuzzer). An upper bound: the reader may
// read in place instead.
double oiio_conversion_buffer_bytes(const OIIO::ImageSpec& spec) {
    const double scanline = static_cast<double>(spec.scanline_bytes(true));
    if (scanline <= 0.0) return 0.0;
    const double rows =
        std::ceil(std::max(std::floor(static_cast<double>(1 << 26) / scanline), 256.0) / 64.0) * 64.0;
    return rows * scanline;
}

// Reads the first subimage of an opened input; `what` names the image in messages.
StoredImage read_opened(OIIO::ImageInput& in, const std::string& what) {
    const OIIO::ImageSpec& spec = in.spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth > 1) {
        throw ImageReadError("image '" + what + "' has an unsupported shape (" + std::to_string(spec.width) +
                             " x " + std::to_string(spec.height) + " x " + std::to_string(spec.depth) + ", " +
                             std::to_string(spec.nchannels) + " channels)");
    }
    StoredImage image;
    image.width = static_cast<uint32_t>(spec.width);
    image.height = static_cast<uint32_t>(spec.height);
    image.channels = spec.nchannels;
    image.alpha_channel = alpha_channel_of(spec);
    // With oiio:UnassociatedAlpha requested, readers of straight-alpha formats report 1 here;
    // formats that store associated alpha (OpenEXR) do not.
    image.associated_alpha =
        image.alpha_channel >= 0 && spec.get_int_attribute("oiio:UnassociatedAlpha", 0) == 0;
    const OIIO::TypeDesc::BASETYPE base = static_cast<OIIO::TypeDesc::BASETYPE>(spec.format.basetype);
    image.format = image.associated_alpha           ? StoredFormat::F32
                   : base == OIIO::TypeDesc::UINT8  ? StoredFormat::U8
                   : base == OIIO::TypeDesc::UINT16 ? StoredFormat::U16
                                                    : StoredFormat::F32;
    const OIIO::TypeDesc type = image.format == StoredFormat::U8    ? OIIO::TypeDesc::UINT8
                                : image.format == StoredFormat::U16 ? OIIO::TypeDesc::UINT16
                                                                    : OIIO::TypeDesc::FLOAT;
    check_decode_memory(what, image.width, image.height, static_cast<uint64_t>(spec.nchannels), type.size(),
                        oiio_conversion_buffer_bytes(spec));
    try {
        image.storage.resize(static_cast<size_t>(image.width) * image.height * spec.nchannels * type.size());
    } catch (const std::bad_alloc&) {
        throw ImageReadError("not enough memory to read image '" + what + "' (" + std::to_string(spec.width) +
                             " x " + std::to_string(spec.height) + ")");
    }
    if (!in.read_image(0, 0, 0, spec.nchannels, type, image.storage.data())) {
        throw ImageReadError("cannot read image '" + what + "': " + in.geterror());
    }
    image.data = image.storage.data();
    image.top_to_bottom = true;
    return image;
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

void check_decode_memory(const std::string& what, uint64_t width, uint64_t height, uint64_t channels,
                         uint64_t bytes_per_channel, double reader_scratch_bytes) {
    // Sides are at most 2^31 (OIIO's int), so the products below stay under 2^64 / 16.
    const double texels = static_cast<double>(width) * static_cast<double>(height);
    const double needed =
        texels * static_cast<double>(channels * bytes_per_channel + 4 * sizeof(float)) + reader_scratch_bytes;
    const double budget = memory_budget_bytes();
    if (needed > budget) {
        throw ImageReadError("image '" + what + "' is " + std::to_string(width) + " x " +
                             std::to_string(height) + " with " + std::to_string(channels) +
                             " channels: reading it as a texture needs " + gib(needed) +
                             ", more than half of this machine's " + gib(2.0 * budget) + " of memory");
    }
}

StoredImage read_image_file(const std::string& path) {
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(path, ec);
    if (!std::filesystem::exists(status)) throw ImageReadError("image file '" + path + "' does not exist");
    if (!std::filesystem::is_regular_file(status)) {
        throw ImageReadError("image '" + path + "' is not a regular file (a directory, device or pipe)");
    }
    const OIIO::ImageSpec config = read_config();
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path, &config);
    if (!in) throw ImageReadError("cannot open image '" + path + "': " + OIIO::geterror());
    return read_opened(*in, path);
}

StoredImage read_image_memory(const void* data, size_t size, const std::string& file_name) {
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

StoredImage image_from_pixels(const float* pixels, uint32_t width, uint32_t height, uint32_t channels) {
    StoredImage image;
    image.width = width;
    image.height = height;
    image.channels = static_cast<int>(channels);
    image.alpha_channel = (channels == 2 || channels == 4) ? static_cast<int>(channels) - 1 : -1;
    image.top_to_bottom = false;
    image.format = StoredFormat::F32;
    image.data = pixels;
    return image;
}

}  // namespace stratum
