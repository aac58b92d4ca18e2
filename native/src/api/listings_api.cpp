// C entry points that list what the library knows, for every host to build its menus, help,
// tables and exports from: light types, closure models and shader node types by name, render
// settings with their choices, passes. Every input is validated and every exception stops here
// (api/abi_guard.h).
#include <string>
#include <utility>
#include <vector>

#include "api/abi_guard.h"
#include "bsdf/bsdf.h"
#include "film/passes.h"
#include "lights/light_registry.h"
#include "render/setting_registry.h"
#include "shading/node_registry.h"
#include "stratum/stratum.h"

namespace {

using stratum::require;
using stratum::abi::guarded;

}  // namespace

extern "C" {

int32_t stratum_model_count(int32_t kind) {
    switch (kind) {
        case STRATUM_MODEL_LIGHT:
            return stratum::light_models().count();
        case STRATUM_MODEL_CLOSURE:
            return stratum::closure_models().count();
        case STRATUM_MODEL_SHADER_NODE:
            return stratum::node_registry().count();
        default:
            return -1;
    }
}

StratumStatus stratum_model_entry(int32_t kind, int32_t index, const char** name, int32_t* value) {
    return guarded("stratum_model_entry", [&] {
        const int32_t count = stratum_model_count(kind);
        require(count >= 0, "unknown model kind " + std::to_string(kind) +
                                " (STRATUM_MODEL_LIGHT, STRATUM_MODEL_CLOSURE or STRATUM_MODEL_SHADER_NODE)");
        require(index >= 0 && index < count,
                "model index " + std::to_string(index) + " out of range [0, " + std::to_string(count) + ")");
        const auto [entry_value, entry_name] = [&] {
            if (kind == STRATUM_MODEL_LIGHT) {
                const auto* e = stratum::light_models().entry(index);
                return std::pair{e->value, e->name};
            }
            if (kind == STRATUM_MODEL_SHADER_NODE) {
                const stratum::NodeEntry* e = stratum::node_registry().listed(index);
                return std::pair{e->value, e->name};
            }
            const auto* e = stratum::closure_models().entry(index);
            return std::pair{e->value, e->name};
        }();
        if (name) *name = entry_name;
        if (value) *value = entry_value;
        return STRATUM_OK;
    });
}

int32_t stratum_setting_count(void) { return static_cast<int32_t>(stratum::setting_registry().size()); }

StratumStatus stratum_setting_info(int32_t index, StratumSettingInfo* out) {
    return guarded("stratum_setting_info", [&] {
        require(out != nullptr, "out is NULL");
        require(index >= 0 && index < stratum_setting_count(),
                "setting index " + std::to_string(index) + " out of range [0, " +
                    std::to_string(stratum_setting_count()) + ")");
        // Default values as text, made once: the strings handed out stay valid.
        static const std::vector<std::string> defaults = [] {
            std::vector<std::string> texts;
            for (const stratum::SettingSpec& spec : stratum::setting_registry())
                texts.push_back(stratum::default_value(spec));
            return texts;
        }();
        const auto i = static_cast<size_t>(index);
        const stratum::SettingSpec& spec = stratum::setting_registry()[i];
        *out = StratumSettingInfo{spec.info.name,
                                  spec.info.label,
                                  spec.info.description,
                                  static_cast<int32_t>(spec.kind),
                                  spec.minimum,
                                  spec.maximum,
                                  spec.open_minimum ? 1 : 0,
                                  spec.unit,
                                  defaults[i].c_str(),
                                  spec.choices ? static_cast<int32_t>(spec.choices().size()) : 0};
        return STRATUM_OK;
    });
}

StratumStatus stratum_setting_choice(int32_t setting, int32_t choice, const char** name, const char** label,
                                     const char** description) {
    return guarded("stratum_setting_choice", [&] {
        require(setting >= 0 && setting < stratum_setting_count(),
                "setting index " + std::to_string(setting) + " out of range [0, " +
                    std::to_string(stratum_setting_count()) + ")");
        const stratum::SettingSpec& spec = stratum::setting_registry()[static_cast<size_t>(setting)];
        const int32_t count = spec.choices ? static_cast<int32_t>(spec.choices().size()) : 0;
        require(choice >= 0 && choice < count, "choice " + std::to_string(choice) + " of setting '" +
                                                   spec.info.name + "' out of range [0, " +
                                                   std::to_string(count) + ")");
        const stratum::RegistryEntry& e = spec.choices()[static_cast<size_t>(choice)];
        if (name) *name = e.name;
        if (label) *label = e.label;
        if (description) *description = e.description;
        return STRATUM_OK;
    });
}

int32_t stratum_pass_count(void) { return static_cast<int32_t>(stratum::kPasses.size()); }

StratumStatus stratum_pass_info(int32_t index, const char** name, int32_t* channels,
                                const char** description) {
    return guarded("stratum_pass_info", [&] {
        require(index >= 0 && index < stratum_pass_count(), "pass index " + std::to_string(index) +
                                                                " out of range [0, " +
                                                                std::to_string(stratum_pass_count()) + ")");
        const stratum::PassInfo& info = stratum::kPasses[static_cast<size_t>(index)];
        if (name) *name = info.name;
        if (channels) *channels = static_cast<int32_t>(info.channels);
        if (description) *description = info.description;
        return STRATUM_OK;
    });
}

}  // extern "C"
