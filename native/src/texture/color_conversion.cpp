#include "texture/color_conversion.h"

#include <OpenColorIO/OpenColorIO.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <utility>
#include <vector>

namespace stratum {

namespace OCIO = OCIO_NAMESPACE;

namespace {

enum class Builtin { Identity, Srgb };

// The names accepted without a config (and with a config OCIO cannot read).
constexpr const char* kBuiltinNames = "'sRGB', 'Linear', 'Linear Rec.709', 'Non-Color', 'Raw'";

bool builtin_conversion(const std::string& name, Builtin* out) {
    if (name == "sRGB") {
        *out = Builtin::Srgb;
        return true;
    }
    if (name == "Linear" || name == "Linear Rec.709" || name == "Non-Color" || name == "Raw") {
        *out = Builtin::Identity;
        return true;
    }
    return false;
}

}  // namespace

// What converting from one colour space does: nothing, the built-in sRGB curve, or an OCIO
// processor (then also its versions optimised for 8- and 16-bit input).
struct SceneLinearConversion::Impl {
    Builtin builtin = Builtin::Identity;
    bool srgb_curve = false;                 // the conversion is the sRGB curve per channel
    OCIO::ConstCPUProcessorRcPtr processor;  // set: use these instead of `builtin`
    OCIO::ConstCPUProcessorRcPtr processor_u8, processor_u16;
};

namespace {

using Conversion = SceneLinearConversion::Impl;

struct LoadedConfig {
    OCIO::ConstConfigRcPtr config;  // null when the file could not be read
    std::string error;              // why, when config is null
};

struct Cache {
    std::mutex mutex;
    std::map<std::string, LoadedConfig> configs;
    std::map<std::pair<std::string, std::string>, std::shared_ptr<const Conversion>> conversions;
};

Cache& cache() {
    static Cache c;
    return c;
}

// Up to 8 of the config's colour space names, the ones Blender users pick most often first.
std::string some_names(const OCIO::Config& config) {
    std::vector<std::string> names;
    for (const char* common : {"sRGB", "Non-Color", "Linear Rec.709", "Linear", "Raw"}) {
        const OCIO::ConstColorSpaceRcPtr cs = config.getColorSpace(common);
        if (cs && std::find(names.begin(), names.end(), cs->getName()) == names.end())
            names.push_back(cs->getName());
    }
    const int n = config.getNumColorSpaces();
    for (int i = 0; i < n && names.size() < 8; ++i) {
        const std::string name = config.getColorSpaceNameByIndex(i);
        if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    }
    std::string text;
    for (const std::string& name : names) text += (text.empty() ? "'" : ", '") + name + "'";
    return text + (static_cast<size_t>(n) > names.size() ? ", ..." : "");
}

Conversion builtin_or_throw(const std::string& space, const std::string& why_no_config) {
    Conversion c;
    if (!builtin_conversion(space, &c.builtin)) {
        throw std::invalid_argument("unknown colour space '" + space + "' (" + why_no_config +
                                    "; the built-in colour spaces are " + kBuiltinNames + ")");
    }
    c.srgb_curve = c.builtin == Builtin::Srgb;
    return c;
}

// Whether `processor` is the sRGB curve on each channel alone, by Cycles' test (see the header).
bool is_srgb_curve(const OCIO::CPUProcessor& processor) {
    for (int i = 0; i < 256; ++i) {
        const float v = static_cast<float>(i) / 255.0f;
        float r[3] = {v, 0, 0}, g[3] = {0, v, 0}, b[3] = {0, 0, v}, w[3] = {v, v, v};
        for (float* c : {r, g, b, w}) processor.applyRGB(c);
        const float crosstalk = std::max(
            {std::abs(r[1]), std::abs(r[2]), std::abs(g[0]), std::abs(g[2]), std::abs(b[0]), std::abs(b[1])});
        const float expected = srgb_to_linear(v);
        const auto near = [](float x, float y, float tolerance) { return std::abs(x - y) <= tolerance; };
        if (crosstalk > 1e-5f || !near(r[0], w[0], 1e-6f) || !near(g[1], w[1], 1e-6f) ||
            !near(b[2], w[2], 1e-6f) || !near(w[0], w[1], 1e-6f) || !near(w[1], w[2], 1e-6f) ||
            !near((w[0] + w[1] + w[2]) / 3.0f, expected, 1e-4f))
            return false;
    }
    return true;
}

Conversion make_conversion(const std::string& config_path, const std::string& space, Cache& c) {
    if (config_path.empty()) return builtin_or_throw(space, "no OpenColorIO config given");
    auto found = c.configs.find(config_path);
    if (found == c.configs.end()) {
        LoadedConfig loaded;
        std::error_code ec;
        if (!std::filesystem::is_regular_file(config_path, ec)) {
            loaded.error = "it is not a regular file";
        } else {
            try {
                loaded.config = OCIO::Config::CreateFromFile(config_path.c_str());
            } catch (const OCIO::Exception& e) {
                loaded.error = e.what();
            }
        }
        found = c.configs.emplace(config_path, std::move(loaded)).first;
    }
    const LoadedConfig& loaded = found->second;
    if (!loaded.config) {
        return builtin_or_throw(space, "OpenColorIO " + std::string(OCIO::GetVersion()) +
                                           " cannot read config '" + config_path + "': " + loaded.error);
    }
    const OCIO::Config& config = *loaded.config;
    const OCIO::ConstColorSpaceRcPtr source = config.getColorSpace(space.c_str());
    if (!source) {
        throw std::invalid_argument("unknown colour space '" + space + "' in OpenColorIO config '" +
                                    config_path + "' (valid names include " + some_names(config) + ")");
    }
    Conversion conversion;  // identity unless a transform is needed
    const OCIO::ConstColorSpaceRcPtr linear = config.getColorSpace(OCIO::ROLE_SCENE_LINEAR);
    if (source->isData() || (linear && std::string(linear->getName()) == source->getName()))
        return conversion;
    try {
        const OCIO::ConstProcessorRcPtr processor =
            config.getProcessor(source->getName(), OCIO::ROLE_SCENE_LINEAR);
        conversion.processor = processor->getDefaultCPUProcessor();
        conversion.srgb_curve = is_srgb_curve(*conversion.processor);
        conversion.processor_u8 = processor->getOptimizedCPUProcessor(
            OCIO::BIT_DEPTH_UINT8, OCIO::BIT_DEPTH_F32, OCIO::OPTIMIZATION_DEFAULT);
        conversion.processor_u16 = processor->getOptimizedCPUProcessor(
            OCIO::BIT_DEPTH_UINT16, OCIO::BIT_DEPTH_F32, OCIO::OPTIMIZATION_DEFAULT);
    } catch (const OCIO::Exception& e) {
        throw std::invalid_argument("colour space '" + space + "' cannot be converted to scene_linear by '" +
                                    config_path + "': " + e.what());
    }
    return conversion;
}

}  // namespace

float srgb_to_linear(float encoded) {
    // IEC 61966-2-1: linear segment below 0.04045, else ((c + 0.055) / 1.055)^2.4.
    return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

SceneLinearConversion conversion_to_scene_linear(const char* config_path, const std::string& color_space) {
    Cache& c = cache();
    const std::string path = config_path ? config_path : "";
    std::lock_guard<std::mutex> lock(c.mutex);
    const auto key = std::make_pair(path, color_space);
    auto found = c.conversions.find(key);
    if (found == c.conversions.end()) {
        found = c.conversions
                    .emplace(key, std::make_shared<const Conversion>(make_conversion(path, color_space, c)))
                    .first;
    }
    return SceneLinearConversion(found->second);
}

bool SceneLinearConversion::is_srgb_curve() const { return impl_->srgb_curve; }

void SceneLinearConversion::apply(float* rgba, size_t count) const {
    if (impl_->processor) {
        // Packed RGBA, 4 floats per pixel: OCIO leaves the alpha channel as it is.
        OCIO::PackedImageDesc image(rgba, static_cast<long>(count), 1, 4);
        impl_->processor->apply(image);
        return;
    }
    if (impl_->builtin == Builtin::Srgb) {
        for (size_t i = 0; i < count; ++i)
            for (size_t k = 0; k < 3; ++k) rgba[4 * i + k] = srgb_to_linear(rgba[4 * i + k]);
    }
}

namespace {

// Stored integers to floats: through the processor optimised for that depth, else v / max and
// the built-in curve from a table (`lut`, built on first use, one entry per stored value).
template <typename T, OCIO::BitDepth kDepth>
void apply_integers(const SceneLinearConversion::Impl& impl, const OCIO::ConstCPUProcessorRcPtr& processor,
                    const T* rgba, float* out, size_t count, const std::vector<float>& lut) {
    if (processor) {
        OCIO::PackedImageDesc src(const_cast<T*>(rgba), static_cast<long>(count), 1, 4, kDepth, sizeof(T),
                                  4 * sizeof(T), static_cast<ptrdiff_t>(4 * sizeof(T) * count));
        OCIO::PackedImageDesc dst(out, static_cast<long>(count), 1, 4, OCIO::BIT_DEPTH_F32, sizeof(float),
                                  4 * sizeof(float), static_cast<ptrdiff_t>(4 * sizeof(float) * count));
        processor->apply(src, dst);
        return;
    }
    constexpr float kScale = 1.0f / static_cast<float>(std::numeric_limits<T>::max());
    const bool srgb = impl.builtin == Builtin::Srgb;
    for (size_t i = 0; i < 4 * count; ++i) {
        const bool colour = (i & 3) != 3;
        out[i] = (srgb && colour) ? lut[rgba[i]] : static_cast<float>(rgba[i]) * kScale;
    }
}

template <typename T>
const std::vector<float>& srgb_table() {
    static const std::vector<float> table = [] {
        std::vector<float> t(static_cast<size_t>(std::numeric_limits<T>::max()) + 1);
        const float scale = 1.0f / static_cast<float>(std::numeric_limits<T>::max());
        for (size_t v = 0; v < t.size(); ++v) t[v] = srgb_to_linear(static_cast<float>(v) * scale);
        return t;
    }();
    return table;
}

}  // namespace

void SceneLinearConversion::apply(const uint8_t* rgba, float* out, size_t count) const {
    apply_integers<uint8_t, OCIO::BIT_DEPTH_UINT8>(*impl_, impl_->processor_u8, rgba, out, count,
                                                   srgb_table<uint8_t>());
}

void SceneLinearConversion::apply(const uint16_t* rgba, float* out, size_t count) const {
    apply_integers<uint16_t, OCIO::BIT_DEPTH_UINT16>(*impl_, impl_->processor_u16, rgba, out, count,
                                                     srgb_table<uint16_t>());
}

}  // namespace stratum
