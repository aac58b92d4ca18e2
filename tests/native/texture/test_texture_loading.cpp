// Image textures: reading (path, in-memory bytes through OIIO's IOProxy or a temporary file,
// Blender-ordered pixels), orientation, alpha, colour conversion with OpenColorIO against the
// closed-form sRGB curve, and the errors of stratum_scene_add_texture.
//
// Images are written by OpenImageIO into the test's temporary directory. 8-bit values are
// k/255 exactly after reading, so texel comparisons of 8-bit files use equality with k/255.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "api/texture_validation.h"
#include "stratum/stratum.h"
#include "texture/color_conversion.h"
#include "texture/texture.h"

using namespace stratum;

namespace {

const std::string kBlender34Config = "/usr/share/blender/datafiles/colormanagement/config.ocio";
// The bpy wheel's config in the checkout's .venv (make setup installs it): found by walking
// .venv/lib/python*/site-packages/bpy/<version>/, so that neither the checkout's path nor the
// Python and Blender versions are written here. Empty when the wheel is not installed.
std::string bpy_wheel_config() {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path lib = fs::path(STRATUM_SOURCE_DIR) / ".venv" / "lib";
    for (const auto& python : fs::directory_iterator(lib, ec)) {
        const fs::path bpy = python.path() / "site-packages" / "bpy";
        for (const auto& version : fs::directory_iterator(bpy, ec)) {
            const fs::path config = version.path() / "datafiles" / "colormanagement" / "config.ocio";
            if (fs::is_regular_file(config, ec)) return config.string();
        }
    }
    return {};
}

// Writes `pixels` (rows top to bottom, as files store them) with OIIO; returns the path.
std::string write_image(const std::string& name, int width, int height, int channels,
                        const std::vector<float>& pixels, OIIO::TypeDesc format) {
    const std::string path = ::testing::TempDir() + name;
    auto out = OIIO::ImageOutput::create(path);
    EXPECT_TRUE(out) << OIIO::geterror();
    OIIO::ImageSpec spec(width, height, channels, format);
    EXPECT_TRUE(out->open(path, spec)) << out->geterror();
    EXPECT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data())) << out->geterror();
    EXPECT_TRUE(out->close());
    return path;
}

std::vector<char> read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

StratumTextureDesc from_path(const std::string& path, const char* space = "Non-Color",
                             const char* config = nullptr) {
    StratumTextureDesc d{};
    d.path = path.c_str();
    d.color_space = space;
    d.ocio_config = config;
    d.interpolation = STRATUM_TEXTURE_CLOSEST;
    return d;
}

StratumTextureDesc from_pixels(const std::vector<float>& pixels, uint32_t w, uint32_t h, uint32_t c,
                               const char* space = "Non-Color", const char* config = nullptr) {
    StratumTextureDesc d{};
    d.pixels = pixels.data();
    d.width = w;
    d.height = h;
    d.channels = c;
    d.color_space = space;
    d.ocio_config = config;
    d.interpolation = STRATUM_TEXTURE_CLOSEST;
    return d;
}

void expect_texel(const Texture& t, uint32_t x, uint32_t y, Rgba expected) {
    const Rgba v = t.texel(x, y);
    EXPECT_FLOAT_EQ(v.r, expected.r) << "texel " << x << "," << y;
    EXPECT_FLOAT_EQ(v.g, expected.g) << "texel " << x << "," << y;
    EXPECT_FLOAT_EQ(v.b, expected.b) << "texel " << x << "," << y;
    EXPECT_FLOAT_EQ(v.a, expected.a) << "texel " << x << "," << y;
}

// A 2x2 RGB image as stored in a file (first scanline = top of the picture):
// top: red, green; bottom: blue, white.
const std::vector<float> kQuadTopToBottom = {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};

// Status and message of adding `d` to a fresh scene.
std::pair<StratumStatus, std::string> add_texture(const StratumTextureDesc& d) {
    StratumScene* scene = nullptr;
    EXPECT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    uint32_t id = 99;
    const StratumStatus status = stratum_scene_add_texture(scene, &d, &id);
    const std::string message = stratum_last_error();
    if (status == STRATUM_OK) {
        EXPECT_EQ(id, 0u);
    }
    stratum_scene_destroy(scene);
    return {status, message};
}

}  // namespace

// Blender's UV (0,0) is the bottom-left of the picture (Cycles flips OIIO's scanlines so its
// row 0 is the bottom). The file's first scanline must therefore become the top row.
TEST(TextureLoading, PngFromPathPutsTheFirstScanlineAtTheTop) {
    const auto path = write_image("tex_quad.png", 2, 2, 3, kQuadTopToBottom, OIIO::TypeDesc::UINT8);
    const auto t = load_texture(from_path(path));
    ASSERT_EQ(t->width, 2u);
    ASSERT_EQ(t->height, 2u);
    expect_texel(*t, 0, 1, {1, 0, 0, 1});  // top-left red
    expect_texel(*t, 1, 1, {0, 1, 0, 1});
    expect_texel(*t, 0, 0, {0, 0, 1, 1});  // bottom-left blue
    expect_texel(*t, 1, 0, {1, 1, 1, 1});
    const Rgba top_left = texture_lookup(*t, {0.25f, 0.75f});
    EXPECT_EQ(top_left.r, 1.0f);
    EXPECT_EQ(top_left.b, 0.0f);
}

TEST(TextureLoading, ExrFromPathKeepsFloatValuesAndUnassociatesAlpha) {
    // RGBA: colour stored premultiplied (OpenEXR's convention): (2, 1, 0.5) at alpha 0.5 is the
    // straight colour (4, 2, 1).
    const std::vector<float> px = {2.0f, 1.0f, 0.5f, 0.5f};
    const auto path = write_image("tex_hdr.exr", 1, 1, 4, px, OIIO::TypeDesc::FLOAT);
    const auto t = load_texture(from_path(path, "Linear"));
    expect_texel(*t, 0, 0, {4.0f, 2.0f, 1.0f, 0.5f});
}

TEST(TextureLoading, PngStraightAlphaIsKept) {
    // 8-bit PNG stores straight alpha: colour 1 at alpha 128/255 must stay 1, not 128/255.
    const std::vector<float> px = {1.0f, 1.0f, 1.0f, 128.0f / 255.0f};
    const auto path = write_image("tex_alpha.png", 1, 1, 4, px, OIIO::TypeDesc::UINT8);
    const auto t = load_texture(from_path(path));
    expect_texel(*t, 0, 0, {1.0f, 1.0f, 1.0f, 128.0f / 255.0f});
}

TEST(TextureLoading, InMemoryBytesMatchTheFileForProxyAndTemporaryFileReaders) {
    // PNG and OpenEXR readers read from memory (IOProxy); SGI's reader does not, so its bytes
    // go through a temporary file. Each must give what reading the path gives.
    ASSERT_TRUE(OIIO::ImageInput::create("png")->supports("ioproxy"));
    ASSERT_TRUE(OIIO::ImageInput::create("exr")->supports("ioproxy"));
    ASSERT_FALSE(OIIO::ImageInput::create("sgi")->supports("ioproxy"));
    for (const auto& [name, format] :
         {std::pair<std::string, OIIO::TypeDesc>{"tex_mem.png", OIIO::TypeDesc::UINT8},
          {"tex_mem.exr", OIIO::TypeDesc::HALF},
          {"tex_mem.sgi", OIIO::TypeDesc::UINT8}}) {
        const auto path = write_image(name, 2, 2, 3, kQuadTopToBottom, format);
        const std::vector<char> bytes = read_bytes(path);
        StratumTextureDesc d{};
        d.file_data = bytes.data();
        d.file_size = bytes.size();
        d.file_name = name.c_str();
        d.color_space = "Non-Color";
        const auto from_memory = load_texture(d);
        const auto from_file = load_texture(from_path(path));
        EXPECT_EQ(from_memory->rgba, from_file->rgba) << name;
        expect_texel(*from_memory, 0, 1, {1, 0, 0, 1});
    }
    // The temporary file is removed.
    for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::temp_directory_path())) {
        EXPECT_EQ(entry.path().filename().string().rfind("stratum-texture-", 0), std::string::npos)
            << entry.path();
    }
}

// Blender's Image.pixels run bottom row first (measured with Blender 5.0: an image whose
// pixels are [red, green] saved as PNG has green on its first scanline).
TEST(TextureLoading, PixelsRunBottomToTopAsBlendersImagePixels) {
    const std::vector<float> px = {1, 0, 0, 1, 0, 1, 0, 1};  // 1x2 RGBA: bottom red, top green
    const auto t = load_texture(from_pixels(px, 1, 2, 4));
    EXPECT_EQ(texture_lookup(*t, {0.5f, 0.25f}).r, 1.0f);
    EXPECT_EQ(texture_lookup(*t, {0.5f, 0.75f}).g, 1.0f);
}

TEST(TextureLoading, OneToFourChannelsBecomeRgba) {
    const std::vector<float> grey = {0.25f}, grey_alpha = {0.25f, 0.5f}, rgb = {0.1f, 0.2f, 0.3f},
                             rgba = {0.1f, 0.2f, 0.3f, 0.4f};
    expect_texel(*load_texture(from_pixels(grey, 1, 1, 1)), 0, 0, {0.25f, 0.25f, 0.25f, 1.0f});
    expect_texel(*load_texture(from_pixels(grey_alpha, 1, 1, 2)), 0, 0, {0.25f, 0.25f, 0.25f, 0.5f});
    expect_texel(*load_texture(from_pixels(rgb, 1, 1, 3)), 0, 0, {0.1f, 0.2f, 0.3f, 1.0f});
    expect_texel(*load_texture(from_pixels(rgba, 1, 1, 4)), 0, 0, {0.1f, 0.2f, 0.3f, 0.4f});
}

// sRGB textures keep their encoded texels and decode after the lookup's interpolation, as
// Cycles does for images whose colour space is the sRGB curve (compress_as_srgb).
TEST(TextureColour, BuiltinSrgbIsTheClosedFormCurve) {
    EXPECT_NEAR(srgb_to_linear(0.5f), 0.2140411f, 1e-6f);  // ((0.5 + 0.055)/1.055)^2.4
    EXPECT_FLOAT_EQ(srgb_to_linear(0.04f), 0.04f / 12.92f);
    const std::vector<float> px = {0.5f, 0.04f, 1.0f, 0.5f};
    const auto t = load_texture(from_pixels(px, 1, 1, 4, "sRGB"));
    EXPECT_TRUE(t->srgb_encoded);
    expect_texel(*t, 0, 0, {0.5f, 0.04f, 1.0f, 0.5f});
    const Rgba v = texture_lookup(*t, {0.5f, 0.5f});
    EXPECT_FLOAT_EQ(v.r, srgb_to_linear(0.5f));
    EXPECT_FLOAT_EQ(v.g, 0.04f / 12.92f);
    EXPECT_FLOAT_EQ(v.b, 1.0f);
    EXPECT_FLOAT_EQ(v.a, 0.5f);
}

// Bilinear interpolation half way between an encoded 0 and 1 gives decode(0.5) = 0.214, not the
// 0.5 of interpolating linear values: Cycles' svm_image_texture decodes after interpolating.
TEST(TextureColour, SrgbDecodesAfterInterpolation) {
    const std::vector<float> px = {0.0f, 0.0f, 0.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f};
    StratumTextureDesc d = from_pixels(px, 2, 1, 4, "sRGB");
    d.interpolation = STRATUM_TEXTURE_LINEAR;
    d.extension = STRATUM_TEXTURE_EXTEND;
    const auto t = load_texture(d);
    EXPECT_FLOAT_EQ(texture_lookup(*t, {0.5f, 0.5f}).r, srgb_to_linear(0.5f));
    EXPECT_FLOAT_EQ(texture_lookup(*t, {0.5f, 0.5f}).a, 1.0f);
}

// Blender 3.4's config: sRGB -> scene_linear ("Linear") is a 65561-entry 1D LUT (srgb.spi1d),
// which Cycles' test (256 levels within 1e-4) finds to be the sRGB curve: the texture keeps the
// encoded values and decodes with the closed form, exactly as the built-in "sRGB". A matrix
// space ("Linear ACES") is not the curve and is converted by OCIO at load.
TEST(TextureColour, Blender34ConfigSrgbMatchesTheClosedFormAndNonColorIsIdentity) {
    if (!std::filesystem::exists(kBlender34Config)) GTEST_SKIP() << "Blender 3.4 is not installed";
    std::vector<float> ramp;
    for (int i = 0; i <= 100; ++i) {
        const float c = static_cast<float>(i) / 100.0f;
        ramp.insert(ramp.end(), {c, c, c, 0.3f});
    }
    const auto srgb = load_texture(from_pixels(ramp, 101, 1, 4, "sRGB", kBlender34Config.c_str()));
    const auto data = load_texture(from_pixels(ramp, 101, 1, 4, "Non-Color", kBlender34Config.c_str()));
    EXPECT_TRUE(srgb->srgb_encoded);
    EXPECT_FALSE(data->srgb_encoded);
    for (uint32_t i = 0; i <= 100; ++i) {
        const float c = static_cast<float>(i) / 100.0f;
        const Rgba v = texture_lookup(*srgb, {(static_cast<float>(i) + 0.5f) / 101.0f, 0.5f});
        EXPECT_EQ(v.r, srgb_to_linear(c)) << c;
        EXPECT_EQ(v.a, 0.3f) << "alpha is not converted";
        EXPECT_EQ(data->texel(i, 0).g, c) << "Non-Color is data: unchanged";
    }
    const auto aces = load_texture(from_pixels(ramp, 101, 1, 4, "Linear ACES", kBlender34Config.c_str()));
    EXPECT_FALSE(aces->srgb_encoded);
    EXPECT_NE(aces->texel(50, 0).r, 0.5f) << "Linear ACES is converted to Rec.709 at load";
}

// OpenColorIO 2.1.2 (Debian 12) cannot read Blender 5.0's version-2.4 config: the built-in
// names still convert, other names are refused with the reason.
TEST(TextureColour, UnreadableConfigFallsBackToBuiltinNamesOnly) {
    const std::string wheel_config = bpy_wheel_config();
    if (wheel_config.empty()) GTEST_SKIP() << "the bpy wheel is not installed in .venv";
    const std::vector<float> px = {0.5f, 0.5f, 0.5f, 1.0f};
    const auto t = load_texture(from_pixels(px, 1, 1, 4, "sRGB", wheel_config.c_str()));
    EXPECT_FLOAT_EQ(texture_lookup(*t, {0.5f, 0.5f}).r, srgb_to_linear(0.5f));
    const auto [status, message] = add_texture(from_pixels(px, 1, 1, 4, "ACEScg", wheel_config.c_str()));
    EXPECT_EQ(status, STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(message.find("'ACEScg'"), std::string::npos) << message;
    EXPECT_NE(message.find("cannot read config"), std::string::npos) << message;
}

TEST(TextureErrors, MissingFileIsAnIoErrorNamingThePath) {
    const std::string path = ::testing::TempDir() + "no_such_texture.png";
    const auto [status, message] = add_texture(from_path(path));
    EXPECT_EQ(status, STRATUM_ERROR_IO);
    EXPECT_NE(message.find(path), std::string::npos) << message;
}

TEST(TextureErrors, UnknownColourSpaceIsNamedWithValidNames) {
    const std::vector<float> px = {0.5f};
    auto [status, message] = add_texture(from_pixels(px, 1, 1, 1, "Linear FooRGB"));
    EXPECT_EQ(status, STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(message.find("'Linear FooRGB'"), std::string::npos) << message;
    EXPECT_NE(message.find("'Non-Color'"), std::string::npos) << message;
    if (!std::filesystem::exists(kBlender34Config)) return;
    std::tie(status, message) =
        add_texture(from_pixels(px, 1, 1, 1, "Linear FooRGB", kBlender34Config.c_str()));
    EXPECT_EQ(status, STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(message.find("'Linear FooRGB'"), std::string::npos) << message;
    EXPECT_NE(message.find("'sRGB'"), std::string::npos) << message;
}

TEST(TextureErrors, EveryFieldIsValidated) {
    const std::vector<float> px = {0.5f, 0.5f, 0.5f, 0.5f};
    const std::string path = ::testing::TempDir() + "x.png";
    struct Case {
        const char* expect;
        StratumTextureDesc desc;
    };
    std::vector<Case> cases;
    auto base = [&] { return from_pixels(px, 1, 1, 4); };
    StratumTextureDesc d = base();
    d.path = path.c_str();
    cases.push_back({"exactly one of path, file_data and pixels (got 2)", d});
    d = base();
    d.pixels = nullptr;
    cases.push_back({"(got 0)", d});
    d = base();
    d.channels = 5;
    cases.push_back({"channels 5", d});
    d = base();
    d.width = 0;
    cases.push_back({"width 0", d});
    d = base();
    d.interpolation = 2;
    cases.push_back({"interpolation 2", d});
    d = base();
    d.extension = 4;
    cases.push_back({"extension 4", d});
    d = base();
    d.color_space = nullptr;
    cases.push_back({"color_space", d});
    d = from_path(path);
    d.width = 4;
    cases.push_back({"must be 0 with a path", d});
    StratumTextureDesc mem{};
    const char bytes[4] = {1, 2, 3, 4};
    mem.file_data = bytes;
    mem.file_size = 4;
    mem.file_name = "packed";
    mem.color_space = "sRGB";
    cases.push_back({"'packed' has no extension", mem});
    for (const Case& c : cases) {
        const auto [status, message] = add_texture(c.desc);
        EXPECT_EQ(status, STRATUM_ERROR_INVALID_ARGUMENT) << c.expect;
        EXPECT_NE(message.find(c.expect), std::string::npos) << message;
    }
}
