#include "texture_sources.h"

#include <OpenImageIO/imageio.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cstdlib>
#include <filesystem>

#include "descriptors.h"
#include "files.h"

namespace stratum::fuzz {

namespace {

namespace fs = std::filesystem;

struct ImageTemplate {
    std::string extension;  // without the dot
    std::string bytes;
};

std::string g_temp_dir;
std::vector<ImageTemplate> g_templates;

// Directories of fuzzer processes that died (a crash skips atexit) are removed by the next one.
void remove_stale_dirs(const fs::path& parent) {
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(parent, ec)) {
        const std::string name = e.path().filename().string();
        if (name.rfind("stratum-fuzz-", 0) != 0) continue;
        const long pid = std::strtol(name.c_str() + 13, nullptr, 10);
        if (pid > 0 && kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) fs::remove_all(e.path(), ec);
    }
}

void remove_temp_dir() {
    std::error_code ec;
    fs::remove_all(g_temp_dir, ec);
}

// A 3 x 2 image in each format OpenImageIO writes here, so the mutations start from files
// that decode.
void write_templates() {
    struct Format {
        const char* extension;
        int channels;
        OIIO::TypeDesc type;
    };
    const Format formats[] = {{"png", 4, OIIO::TypeDesc::UINT8}, {"png", 3, OIIO::TypeDesc::UINT16},
                              {"exr", 4, OIIO::TypeDesc::HALF},  {"hdr", 3, OIIO::TypeDesc::FLOAT},
                              {"tga", 3, OIIO::TypeDesc::UINT8}, {"bmp", 3, OIIO::TypeDesc::UINT8},
                              {"jpg", 3, OIIO::TypeDesc::UINT8}, {"tif", 1, OIIO::TypeDesc::FLOAT}};
    for (const Format& f : formats) {
        const fs::path path = fs::path(g_temp_dir) / (std::string("template.") + f.extension);
        std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(path.string());
        if (!out) continue;
        const OIIO::ImageSpec spec(3, 2, f.channels, f.type);
        std::vector<float> pixels(static_cast<size_t>(3 * 2 * f.channels));
        for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<float>(i % 7) / 6.0f;
        if (out->open(path.string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) &&
            out->close()) {
            g_templates.push_back({f.extension, read_file(path.string())});
        }
        std::error_code ec;
        fs::remove(path, ec);
    }
}

// CRC-32 (ISO 3309, as PNG chunks use), bitwise: only ever run on 17 bytes.
uint32_t crc32(const unsigned char* data, size_t size) {
    uint32_t crc = 0xffffffffu;
    for (size_t i = 0; i < size; ++i) {
        crc ^= data[i];
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

void put_be32(std::string& bytes, size_t at, uint32_t v) {
    for (size_t i = 0; i < 4; ++i) bytes[at + i] = static_cast<char>((v >> (24 - 8 * i)) & 0xffu);
}

// A PNG whose IHDR claims width x height, with a correct CRC so that readers believe it:
// the "165-byte file that claims 65535 x 65535" of the decompression-bomb case.
void patch_png_size(std::string& png, uint32_t width, uint32_t height) {
    // Signature (8 bytes), IHDR length (4), "IHDR" (4), width (4), height (4), 5 more bytes, CRC.
    if (png.size() < 33 || png.compare(12, 4, "IHDR") != 0) return;
    put_be32(png, 16, width);
    put_be32(png, 20, height);
    put_be32(png, 29, crc32(reinterpret_cast<const unsigned char*>(png.data()) + 12, 17));
}

// The bytes of a template after mutations: truncation, byte changes, a huge PNG header.
std::string draw_file_bytes(ByteReader& in, std::string* extension) {
    if (g_templates.empty()) return in.bytes(256);
    const ImageTemplate& t = g_templates[in.u8() % g_templates.size()];
    *extension = t.extension;
    std::string bytes = t.bytes;
    const uint8_t how = in.u8();
    if (how & 1) bytes.resize(1 + in.u16() % bytes.size());
    if ((how & 6) == 6) {
        const int64_t w = in.i64(), h = in.i64();
        patch_png_size(bytes, static_cast<uint32_t>(w), static_cast<uint32_t>(h));
    }
    const unsigned changes = in.u8() % 4;
    for (unsigned i = 0; i < changes; ++i) bytes[in.u16() % bytes.size()] = static_cast<char>(in.u8());
    return bytes;
}

// "image.<extension>", or a name whose extension is wrong, odd, or missing.
std::string draw_file_name(ByteReader& in, const std::string& extension, bool* null_name) {
    static const char* const kNames[] = {"image.png", "image.exr", "image.hdr", "image.tga",
                                         "image.jpg", "image.tif", "image.txt", "image",
                                         "image.",    "",          ".png",      "image.PNG"};
    const uint8_t s = in.u8();
    *null_name = s == 255;
    if (s < 128) return "image." + extension;
    return in.name(kNames);
}

}  // namespace

void init_texture_sources() {
    const fs::path parent = fs::temp_directory_path();
    remove_stale_dirs(parent);
    g_temp_dir = (parent / ("stratum-fuzz-" + std::to_string(getpid()))).string();
    fs::create_directories(g_temp_dir);
    std::atexit(remove_temp_dir);
    mkfifo((fs::path(g_temp_dir) / "fifo.png").c_str(), 0600);
    write_file((fs::path(g_temp_dir) / "garbage.ocio").string(),
               "ocio_profile_version: 2\nroles: [this is not a config\n");
    write_templates();
}

const std::string& temp_dir() { return g_temp_dir; }

void TextureArrays::bind() {
    desc.pixels = use_pixels ? pixels.data() : nullptr;
    desc.file_data = use_file_data ? file_bytes.data() : nullptr;
    desc.path = use_path ? path.c_str() : nullptr;
    desc.file_name = null_file_name ? nullptr : file_name.c_str();
    desc.color_space = null_color_space ? nullptr : color_space.c_str();
    desc.ocio_config = ocio_config.empty() ? nullptr : ocio_config.c_str();
}

TextureArrays draw_texture(ByteReader& in) {
    TextureArrays t;
    StratumTextureDesc& d = t.desc;
    std::string extension = "png";
    const uint8_t source = in.u8();
    switch (source % 6) {
        case 0:
        case 5: {  // pixels; selector 5 adds a second source, which must be refused
            d.width = in.u8() % 5;
            d.height = in.u8() % 5;
            d.channels = in.u8() % 6;
            t.pixels.assign(static_cast<size_t>(d.width) * d.height * std::max(1u, d.channels),
                            in.f32(FloatKind::Unit));
            const unsigned changes = in.u8() % 4;
            for (unsigned i = 0; i < changes && !t.pixels.empty(); ++i)
                t.pixels[in.u8() % t.pixels.size()] = in.f32(FloatKind::Unit);
            t.use_pixels = (source % 6 == 0) || (source & 0x80);
            t.use_path = source % 6 == 5;
            t.path = temp_dir() + "/missing.png";
            break;
        }
        case 1:
            t.file_bytes = draw_file_bytes(in, &extension);
            t.use_file_data = true;
            break;
        case 2:
            t.file_bytes = in.bytes(256);
            t.use_file_data = true;
            break;
        case 3: {
            const std::string bytes = draw_file_bytes(in, &extension);
            t.path = temp_dir() + "/texture." + extension;
            write_file(t.path, bytes);
            t.use_path = true;
            break;
        }
        default: {
            static const char* const kPaths[] = {"missing.png", "", "fifo.png", "garbage.ocio"};
            const uint8_t which = in.u8() % 8;
            t.path = which < 4    ? temp_dir() + "/" + kPaths[which]
                     : which == 4 ? temp_dir()
                     : which == 5 ? "/dev/zero"
                     : which == 6 ? "/dev/null"
                                  : "";
            t.use_path = true;
            break;
        }
    }
    t.file_name = draw_file_name(in, extension, &t.null_file_name);
    d.file_size = t.use_file_data && !(source & 0x40) ? t.file_bytes.size() : 0;
    if (!t.use_file_data && (source & 0x40)) d.file_size = 1;  // a size without data: refused
    if (!t.use_pixels && (source & 0x20)) {
        d.width = static_cast<uint32_t>(draw_small_int(in));
        d.height = static_cast<uint32_t>(draw_small_int(in));
        d.channels = static_cast<uint32_t>(draw_small_int(in));
    }
    static const char* const kColorSpaces[] = {"sRGB",           "Linear",     "Non-Color", "Raw",
                                               "Linear Rec.709", "Filmic Log", "XYZ",       "Filmic sRGB",
                                               "linear",         "srgb",       ""};
    t.color_space = in.name(kColorSpaces);
    const uint8_t config = in.u8();
    t.null_color_space = config == 255;
    switch (config % 8) {
        case 3:
            t.ocio_config = temp_dir() + "/fifo.png";
            break;
        case 4:
            t.ocio_config = "/usr/share/blender/datafiles/colormanagement/config.ocio";
            break;
        case 5:
            t.ocio_config = temp_dir() + "/missing.ocio";
            break;
        case 6:
            t.ocio_config = temp_dir();
            break;
        case 7:
            t.ocio_config = temp_dir() + "/garbage.ocio";
            break;
        default:
            break;  // NULL: the built-in colour spaces
    }
    d.interpolation = draw_enum(in, 2);
    d.extension = draw_enum(in, 4);
    return t;
}

}  // namespace stratum::fuzz
