// The one list of render settings: each setting's name (as the host sets it), label,
// description, kind, range or choices, and how it is read from and written to RenderSettings
// (the table: render/setting_registry.cpp). The ABI serves it (stratum_setting_*), and the
// add-on's properties, `stratum compare`'s choices and help, and the README's settings table are
// generated from it; a value is parsed and checked once, when it is set
// (render/setting_values.cpp).
//
// | kind   | value                                   | checked                                  |
// |--------|-----------------------------------------|------------------------------------------|
// | Int    | integer in [minimum, maximum]           | range                                    |
// | Float  | number in [minimum, maximum] (or        | range; NaN never; +inf only if maximum   |
// |        | (minimum, maximum] when open_minimum)   | is +inf                                  |
// | Choice | one of choices() by name                | name                                     |
// | List   | comma-separated names of choices()      | each name; "" = none                     |
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/registry.h"
#include "render/render_settings.h"

namespace stratum {

enum class SettingKind : int32_t { Int = 0, Float = 1, Choice = 2, List = 3 };

struct SettingSpec {
    RegistryEntry info;  // name, label, description
    SettingKind kind;
    double minimum = 0, maximum = 0;                        // Int and Float
    bool open_minimum = false;                              // Float: the minimum itself is excluded
    const char* unit = "";                                  // shown after numbers in messages ("pixels")
    std::span<const RegistryEntry> (*choices)() = nullptr;  // Choice and List
    // Int/Float: the value; Choice: the position of the value in choices(). (List: unused.)
    double (*get)(const RenderSettings&) = nullptr;
    void (*set)(RenderSettings&, double) = nullptr;
    // List: the positions of the listed choices.
    std::vector<size_t> (*get_list)(const RenderSettings&) = nullptr;
    void (*set_list)(RenderSettings&, const std::vector<size_t>&) = nullptr;
};

std::span<const SettingSpec> setting_registry();
// nullptr when no setting has this name.
const SettingSpec* find_setting(std::string_view name);
// The setting's value in a default-constructed RenderSettings, as text ("16", "1.5", "mis",
// "Normal,Depth").
std::string default_value(const SettingSpec& spec);

// Each returns an empty string on success, else a message naming the setting and the value.
std::string set_int_setting(RenderSettings& s, std::string_view name, int64_t value);
std::string set_float_setting(RenderSettings& s, std::string_view name, double value);
std::string set_string_setting(RenderSettings& s, std::string_view name, std::string_view value);

}  // namespace stratum
