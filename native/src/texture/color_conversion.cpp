#include "texture/color_conversion.h"

#include <OpenColorIO/OpenColorIO.h>

#include <algorithm>
#include <cmath>
#include <map>
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

// What converting from one colour space does: nothing, the built-in sRGB curve, or an OCIO
// processor.
struct Conversion {
    Builtin builtin = Builtin::Identity;
    OCIO::ConstCPUProcessorRcPtr processor;  // set: use it instead of `builtin`
};

struct LoadedConfig {
    OCIO::ConstConfigRcPtr config;  // null when the file could not be read
    std::string error;              // why, when config is null
};

struct Cache {
    std::mutex mutex;
    std::map<std::string, LoadedConfig> configs;
    std::map<std::pair<std::string, std::string>, Conversion> conversions;
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
    return c;
}

Conversion make_conversion(const std::string& config_path, const std::string& space, Cache& c) {
    if (config_path.empty()) return builtin_or_throw(space, "no OpenColorIO config given");
    auto found = c.configs.find(config_path);
    if (found == c.configs.end()) {
        LoadedConfig loaded;
        try {
            loaded.config = OCIO::Config::CreateFromFile(config_path.c_str());
        } catch (const OCIO::Exception& e) {
            loaded.error = e.what();
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
        conversion.processor =
            config.getProcessor(source->getName(), OCIO::ROLE_SCENE_LINEAR)->getDefaultCPUProcessor();
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

void convert_to_scene_linear(const char* config_path, const std::string& color_space, float* rgba,
                             size_t count) {
    Conversion conversion;
    {
        Cache& c = cache();
        const std::string path = config_path ? config_path : "";
        std::lock_guard<std::mutex> lock(c.mutex);
        const auto key = std::make_pair(path, color_space);
        auto found = c.conversions.find(key);
        if (found == c.conversions.end())
            found = c.conversions.emplace(key, make_conversion(path, color_space, c)).first;
        conversion = found->second;
    }
    if (conversion.processor) {
        // Packed RGBA, 4 floats per pixel: OCIO leaves the alpha channel as it is.
        OCIO::PackedImageDesc image(rgba, static_cast<long>(count), 1, 4);
        conversion.processor->apply(image);
        return;
    }
    if (conversion.builtin == Builtin::Srgb) {
        for (size_t i = 0; i < count; ++i)
            for (size_t k = 0; k < 3; ++k) rgba[4 * i + k] = srgb_to_linear(rgba[4 * i + k]);
    }
}

}  // namespace stratum
