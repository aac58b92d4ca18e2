// Textures a hostile scene can hold (issue 12): non-finite texels (from pixels, from files, and
// made by a colour conversion that overflows), headers that claim more pixels than the machine
// has memory for, paths that are no regular file (a FIFO would block a reader forever), an OCIO
// config that is a FIFO, and 8/16-bit files converted through tables agreeing with the floats.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "api/texture_validation.h"
#include "stratum/stratum.h"
#include "texture/color_conversion.h"
#include "texture/texture.h"

using namespace stratum;

namespace {

struct Added {
    StratumStatus status = STRATUM_OK;
    std::string message;
    StratumTextureInfo info{};
    std::vector<float> texel0;  // first texel (bottom-left), read back through a saved scene
};

StratumTextureDesc describe(const char* space) {
    StratumTextureDesc d{};
    d.color_space = space;
    d.interpolation = STRATUM_TEXTURE_CLOSEST;
    return d;
}

Added add(const StratumTextureDesc& d) {
    StratumScene* scene = nullptr;
    EXPECT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    Added out;
    uint32_t id = 0;
    out.status = stratum_scene_add_texture(scene, &d, &id);
    out.message = stratum_last_error();
    if (out.status == STRATUM_OK) {
        EXPECT_EQ(stratum_scene_texture_info(scene, id, &out.info), STRATUM_OK);
    }
    stratum_scene_destroy(scene);
    return out;
}

std::string temp_path(const std::string& name) {
    const std::string path = ::testing::TempDir() + name;
    std::filesystem::remove(path);
    return path;
}

uint32_t crc32(const unsigned char* data, size_t size) {
    // CRC-32 of PNG chunks (ISO 3309, polynomial 0xEDB88320 reflected), bit by bit.
    uint32_t crc = 0xFFFFFFFFu;
    for (size_t i = 0; i < size; ++i) {
        crc ^= data[i];
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return crc ^ 0xFFFFFFFFu;
}

void put_be32(unsigned char* p, uint32_t v) {
    p[0] = static_cast<unsigned char>(v >> 24);
    p[1] = static_cast<unsigned char>(v >> 16);
    p[2] = static_cast<unsigned char>(v >> 8);
    p[3] = static_cast<unsigned char>(v);
}

// A real 1x1 PNG whose IHDR is then rewritten to claim width x height (with a valid CRC): a
// reader that trusts the header asks for width*height pixels before it decodes one.
std::string lying_png(uint32_t width, uint32_t height) {
    const std::string path = temp_path("lying.png");
    auto out = OIIO::ImageOutput::create(path);
    const OIIO::ImageSpec spec(1, 1, 3, OIIO::TypeDesc::UINT8);
    const unsigned char pixel[3] = {10, 20, 30};
    EXPECT_TRUE(out && out->open(path, spec) && out->write_image(OIIO::TypeDesc::UINT8, pixel) &&
                out->close());
    std::ifstream in(path, std::ios::binary);
    std::vector<unsigned char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    // Signature (8), IHDR length (4), "IHDR" (4), width (4), height (4), 5 more bytes, CRC.
    put_be32(&bytes[16], width);
    put_be32(&bytes[20], height);
    put_be32(&bytes[29], crc32(&bytes[12], 17));
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    return path;
}

}  // namespace

// Cycles (scene/image.cpp, "Make sure we don't have buggy values") zeroes all four channels of
// an RGBA texel with any non-finite channel; the texture counts them for the host's warning.
TEST(TextureHostile, NonFinitePixelsBecomeTransparentBlackAndAreCounted) {
    const std::vector<float> pixels = {0.5f,     NAN,  0.5f, 1.0f, 0.25f, 0.5f, 0.75f, 1.0f,
                                       INFINITY, 0.0f, 0.0f, 1.0f, 0.1f,  0.2f, 0.3f,  -INFINITY};
    StratumTextureDesc d = describe("Non-Color");
    d.pixels = pixels.data();
    d.width = 2;
    d.height = 2;
    d.channels = 4;
    const Added a = add(d);
    ASSERT_EQ(a.status, STRATUM_OK) << a.message;
    EXPECT_EQ(a.info.width, 2u);
    EXPECT_EQ(a.info.height, 2u);
    EXPECT_EQ(a.info.replaced_texels, 3u);
}

// A conversion that overflows: 3e38 through Blender 3.4's "Linear ACES" (an AP0 -> Rec.709
// matrix with coefficients up to 2.5) exceeds FLT_MAX; the texel is replaced (a saved scene
// holding Inf could not be loaded back).
TEST(TextureHostile, ColourConversionOverflowIsReplaced) {
    const char* config = "/usr/share/blender/datafiles/colormanagement/config.ocio";
    if (!std::filesystem::exists(config)) GTEST_SKIP() << "no Blender 3.4 OCIO config at " << config;
    const std::vector<float> pixels = {3e38f, 3e38f, 3e38f, 1.0f, 0.5f, 0.5f, 0.5f, 1.0f};
    StratumTextureDesc d = describe("Linear ACES");
    d.ocio_config = config;
    d.pixels = pixels.data();
    d.width = 2;
    d.height = 1;
    d.channels = 4;
    const Added a = add(d);
    ASSERT_EQ(a.status, STRATUM_OK) << a.message;
    EXPECT_EQ(a.info.replaced_texels, 1u);

    StratumScene* scene = nullptr;
    ASSERT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    ASSERT_EQ(stratum_scene_add_texture(scene, &d, nullptr), STRATUM_OK);
    const std::string saved = temp_path("overflow_texture.json");
    ASSERT_EQ(stratum_scene_save(scene, saved.c_str()), STRATUM_OK) << stratum_last_error();
    stratum_scene_destroy(scene);
    StratumScene* loaded = nullptr;
    EXPECT_EQ(stratum_scene_load(saved.c_str(), &loaded), STRATUM_OK) << stratum_last_error();
    stratum_scene_destroy(loaded);
}

// sRGB images stay encoded and decode after interpolation (Cycles' compress_as_srgb), yet a
// texel whose decoding is infinite (1e19: (1e19 / 1.055)^2.4 > FLT_MAX) is not finite in scene
// linear, so it is replaced and counted like one converted at load; 1e15 decodes to ~1e36, kept.
TEST(TextureHostile, SrgbTexelDecodingBeyondFloatMaxIsReplaced) {
    EXPECT_TRUE(std::isinf(srgb_to_linear(1e19f)));
    const std::vector<float> pixels = {1e19f, 0.5f, -0.25f, 1.0f, 1e15f, 0.5f, -0.25f, 1.0f};
    StratumTextureDesc d = describe("sRGB");
    d.pixels = pixels.data();
    d.width = 2;
    d.height = 1;
    d.channels = 4;
    const auto texture = load_texture(d);
    EXPECT_TRUE(texture->srgb_encoded);
    EXPECT_EQ(texture->replaced_texels, 1u);
    const Rgba replaced = texture_lookup(*texture, {0.25f, 0.5f});
    EXPECT_EQ(replaced.r, 0.0f);
    EXPECT_EQ(replaced.a, 0.0f);
    const Rgba kept = texture_lookup(*texture, {0.75f, 0.5f});
    EXPECT_FLOAT_EQ(kept.r, srgb_to_linear(1e15f));
    EXPECT_TRUE(std::isfinite(kept.r));
    EXPECT_FLOAT_EQ(kept.g, srgb_to_linear(0.5f));
    EXPECT_EQ(kept.b, 0.0f);  // negative encoded values decode to 0, as in Cycles
    EXPECT_EQ(kept.a, 1.0f);
}

TEST(TextureHostile, NonFiniteTexelsOfAFileAreReplaced) {
    const std::string path = temp_path("nan_texels.exr");
    auto out = OIIO::ImageOutput::create(path);
    const OIIO::ImageSpec spec(3, 1, 4, OIIO::TypeDesc::FLOAT);
    const float pixels[12] = {NAN, NAN, NAN, NAN, 0.5f, 0.5f, 0.5f, 1.0f, 1.0f, INFINITY, 1.0f, 1.0f};
    ASSERT_TRUE(out && out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels) &&
                out->close());
    StratumTextureDesc d = describe("Non-Color");
    d.path = path.c_str();
    const Added a = add(d);
    ASSERT_EQ(a.status, STRATUM_OK) << a.message;
    EXPECT_EQ(a.info.replaced_texels, 2u);
    // Blender 3.4's OCIO sRGB turns a NaN into 0 before the check; the file's NaN still counts.
    const char* config = "/usr/share/blender/datafiles/colormanagement/config.ocio";
    if (std::filesystem::exists(config)) {
        d.color_space = "sRGB";
        d.ocio_config = config;
        const Added converted = add(d);
        ASSERT_EQ(converted.status, STRATUM_OK) << converted.message;
        EXPECT_EQ(converted.info.replaced_texels, 2u);
    }
}

// A 66-byte in-memory BMP whose rows claim 218103811 pixels (2 rows, 24 bits): its texels alone
// fit the budget (8 GiB), but OIIO's read_scanlines converts through a buffer of 256 native rows
// whatever the height, 167 GB: counted in the budget and refused before reading (the fuzzer
// found the abort; regressions/texture-bmp-row-of-218-million-pixels).
TEST(TextureHostile, ReaderBufferOfVeryWideRowsIsCountedInTheBudget) {
    const unsigned char bmp[66] = {0x42, 0x4d, 0x4e, 0,    0,    0,    0,    0,    0,    0, 0x36,
                                   0,    0,    0,  // file header, pixels at 54
                                   0x28, 0,    0,    0,    0x03, 0,    0,    0x0d, 0x02, 0, 0,
                                   0,    0x01, 0,  // info header: 0x0d000003 x 2, 1 plane
                                   0x18, 0,    0,    0,    0,    0,    0x06, 0,    0,    0, 0,
                                   0,    0,    0,    0,    0,  // 24 bits, no compression
                                   0,    0,    0,    0,    0,    0,    0,    0,    0,    0, 0xaa,
                                   0x80, 0x55, 0,    0xff, 0xd5, 0x80, 0x55, 0x2b, 0,    0, 0};
    StratumTextureDesc d = describe("Non-Color");
    d.file_data = bmp;
    d.file_size = sizeof bmp;
    d.file_name = "image.bmp";
    const Added a = add(d);
    EXPECT_EQ(a.status, STRATUM_ERROR_IO);
    EXPECT_NE(a.message.find("218103811 x 2"), std::string::npos) << a.message;
    EXPECT_NE(a.message.find("memory"), std::string::npos) << a.message;
}

// 65535 x 65535 RGB decodes to 65535^2 * (3 + 16) bytes = 76 GiB: refused from the header,
// before any pixel memory, with a message naming the image (this test runs under ASan, whose
// allocator would abort on a 64 GiB request).
TEST(TextureHostile, HeaderClaimingMoreThanMemoryIsRefusedBeforeAllocating) {
    const std::string path = lying_png(65535, 65535);
    StratumTextureDesc d = describe("sRGB");
    d.path = path.c_str();
    const Added a = add(d);
    EXPECT_EQ(a.status, STRATUM_ERROR_IO);
    EXPECT_NE(a.message.find("lying.png"), std::string::npos) << a.message;
    EXPECT_NE(a.message.find("65535 x 65535"), std::string::npos) << a.message;
    EXPECT_NE(a.message.find("GiB"), std::string::npos) << a.message;
}

TEST(TextureHostile, PathsThatAreNoRegularFileAreRefusedWithoutBeingRead) {
    const std::string fifo = temp_path("texture.fifo");
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    const std::string directory = temp_path("texture_directory.png");
    std::filesystem::create_directory(directory);
    for (const std::string& path : {fifo, directory, std::string("/dev/zero")}) {
        StratumTextureDesc d = describe("sRGB");
        d.path = path.c_str();
        const auto started = std::chrono::steady_clock::now();
        const Added a = add(d);
        EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(5)) << path;
        EXPECT_EQ(a.status, STRATUM_ERROR_IO) << path;
        EXPECT_NE(a.message.find("not a regular file"), std::string::npos) << a.message;
        EXPECT_NE(a.message.find(path), std::string::npos) << a.message;
    }
    const Added missing = add([] {
        StratumTextureDesc d = describe("sRGB");
        d.path = "/nonexistent/stratum/texture.png";
        return d;
    }());
    EXPECT_EQ(missing.status, STRATUM_ERROR_IO);
    EXPECT_NE(missing.message.find("does not exist"), std::string::npos) << missing.message;
    std::filesystem::remove(fifo);
}

// An OCIO config path that is a FIFO is an unreadable config (the built-in names still work),
// found without opening it.
TEST(TextureHostile, OcioConfigThatIsAFifoIsUnreadableNotAHang) {
    const std::string fifo = temp_path("config.ocio");
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    const std::vector<float> pixels = {0.5f, 0.5f, 0.5f};
    StratumTextureDesc d = describe("sRGB");
    d.pixels = pixels.data();
    d.width = d.height = 1;
    d.channels = 3;
    d.ocio_config = fifo.c_str();
    const Added builtin = add(d);
    EXPECT_EQ(builtin.status, STRATUM_OK) << builtin.message;
    d.color_space = "ACEScg";
    const Added unknown = add(d);
    EXPECT_EQ(unknown.status, STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(unknown.message.find("not a regular file"), std::string::npos) << unknown.message;
    std::filesystem::remove(fifo);
}

// 8- and 16-bit files are converted through tables (or OCIO's processor for that depth); every
// stored value must give what converting its float v / max gives. Both OCIO paths approximate
// pow (OPTIMIZATION_FAST_LOG_EXP_POW, part of the default optimisation) and a table holds the
// rounded curve: measured worst relative difference 3.5e-7 (8-bit) and 7.6e-7 (16-bit, Blender
// 3.4's config); 2^-18 = 3.8e-6 leaves a factor 5 and still catches a wrong table (an 8-bit step
// is 1/255 = 4e-3).
TEST(TextureHostile, IntegerFilesConvertLikeTheirFloatValues) {
    const char* configs[] = {nullptr, "/usr/share/blender/datafiles/colormanagement/config.ocio"};
    for (const OIIO::TypeDesc format : {OIIO::TypeDesc::UINT8, OIIO::TypeDesc::UINT16}) {
        const int levels = format == OIIO::TypeDesc::UINT8 ? 256 : 65536;
        const int width = 256, height = levels / 256;
        std::vector<float> values(static_cast<size_t>(width) * height * 3);
        for (size_t i = 0; i < values.size(); ++i)
            values[i] = static_cast<float>((i / 3 * 7 + i % 3) % levels) / static_cast<float>(levels - 1);
        const std::string path = temp_path(format == OIIO::TypeDesc::UINT8 ? "levels8.png" : "levels16.png");
        auto out = OIIO::ImageOutput::create(path);
        const OIIO::ImageSpec spec(width, height, 3, format);
        ASSERT_TRUE(out && out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, values.data()) &&
                    out->close());
        for (const char* config : configs) {
            if (config && !std::filesystem::exists(config)) continue;
            // Without a config the built-in sRGB (kept encoded: v / max exactly); with Blender
            // 3.4's, Filmic Log, whose OCIO transform is converted at load.
            const char* space = config ? "Filmic Log" : "sRGB";
            StratumTextureDesc from_file = describe(space);
            from_file.path = path.c_str();
            from_file.ocio_config = config;
            StratumTextureDesc from_floats = describe(space);
            from_floats.pixels = values.data();  // rows bottom to top: compare row y with height-1-y
            from_floats.width = width;
            from_floats.height = height;
            from_floats.channels = 3;
            from_floats.ocio_config = config;
            const auto file = load_texture(from_file);
            const auto floats = load_texture(from_floats);
            float worst = 0.0f;
            for (int y = 0; y < height; ++y) {
                for (int x = 0; x < width; ++x) {
                    const Rgba a = file->texel(x, y), b = floats->texel(x, height - 1 - y);
                    for (const auto& [u, v] : {std::pair{a.r, b.r}, {a.g, b.g}, {a.b, b.b}, {a.a, b.a}})
                        worst = std::max(worst, std::abs(u - v) / std::max(std::abs(v), 1e-3f));
                }
            }
            EXPECT_LT(worst, 1.0f / (1 << 18)) << format << " " << (config ? config : "built-in");
        }
    }
}
