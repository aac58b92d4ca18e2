// Setting a render setting by name (render/setting_registry.h): the value is checked against
// the setting's row (kind, range, choices) once, here, and stored through its accessors; the
// message of a rejected value names the setting, the value and what it accepts.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "render/setting_registry.h"

namespace stratum {

namespace {

std::string format_number(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
}

std::string choice_names(const SettingSpec& spec) {
    std::string names;
    for (const RegistryEntry& e : spec.choices()) names += (names.empty() ? "" : ", ") + std::string(e.name);
    return names;
}

// The position of `name` among the setting's choices, or choices().size().
size_t find_choice(const SettingSpec& spec, std::string_view name) {
    const std::span<const RegistryEntry> choices = spec.choices();
    for (size_t i = 0; i < choices.size(); ++i)
        if (name == choices[i].name) return i;
    return choices.size();
}

const char* kind_name(SettingKind kind) {
    switch (kind) {
        case SettingKind::Int:
            return "integer";
        case SettingKind::Float:
            return "float";
        case SettingKind::Choice:
        case SettingKind::List:
            return "string";
    }
    return "";
}

// The setting `name` of `kind`, or an error message naming what is wrong.
const SettingSpec* lookup(std::string_view name, SettingKind kind, std::string* error) {
    const SettingSpec* spec = find_setting(name);
    const bool string_kind = kind == SettingKind::Choice;
    if (!spec || (string_kind ? (spec->kind != SettingKind::Choice && spec->kind != SettingKind::List)
                              : spec->kind != kind)) {
        *error = "unknown " + std::string(kind_name(kind)) + " setting '" + std::string(name) + "'" +
                 (spec ? " (it is a " + std::string(kind_name(spec->kind)) + " setting)" : "");
        return nullptr;
    }
    return spec;
}

}  // namespace

std::string default_value(const SettingSpec& spec) {
    const RenderSettings defaults;
    switch (spec.kind) {
        case SettingKind::Int:
        case SettingKind::Float:
            return format_number(spec.get(defaults));
        case SettingKind::Choice:
            return spec.choices()[static_cast<size_t>(spec.get(defaults))].name;
        case SettingKind::List: {
            std::string names;
            for (const size_t c : spec.get_list(defaults))
                names += (names.empty() ? "" : ",") + std::string(spec.choices()[c].name);
            return names;
        }
    }
    return {};
}

std::string set_int_setting(RenderSettings& s, std::string_view name, int64_t value) {
    std::string error;
    const SettingSpec* spec = lookup(name, SettingKind::Int, &error);
    if (!spec) return error;
    const double v = static_cast<double>(value);
    if (v < spec->minimum || v > spec->maximum) {
        return "setting '" + std::string(name) + "' = " + std::to_string(value) + " is out of range [" +
               format_number(spec->minimum) + ", " + format_number(spec->maximum) + "]";
    }
    spec->set(s, v);
    return {};
}

std::string set_float_setting(RenderSettings& s, std::string_view name, double value) {
    std::string error;
    const SettingSpec* spec = lookup(name, SettingKind::Float, &error);
    if (!spec) return error;
    // The renderer stores a float: a double that rounds to 0 where 0 is excluded, or to infinity
    // where the range is finite, is judged by what it becomes.
    const float stored = static_cast<float>(value);
    const bool above_minimum =
        spec->open_minimum ? value > spec->minimum && stored > spec->minimum : value >= spec->minimum;
    if (std::isnan(value) || !above_minimum || !(value <= spec->maximum) ||
        (!std::isinf(spec->maximum) && !std::isfinite(stored))) {
        const std::string unit = *spec->unit ? std::string(" ") + spec->unit : "";
        return "setting '" + std::string(name) + "' = " + format_number(value) + " must be in " +
               (spec->open_minimum ? "(" : "[") + format_number(spec->minimum) + ", " +
               format_number(spec->maximum) + "]" + unit;
    }
    spec->set(s, value);
    return {};
}

std::string set_string_setting(RenderSettings& s, std::string_view name, std::string_view value) {
    std::string error;
    const SettingSpec* spec = lookup(name, SettingKind::Choice, &error);
    if (!spec) return error;
    if (spec->kind == SettingKind::Choice) {
        const size_t choice = find_choice(*spec, value);
        if (choice == spec->choices().size())
            return "unknown " + std::string(name) + " '" + std::string(value) +
                   "' (known: " + choice_names(*spec) + ")";
        spec->set(s, static_cast<double>(choice));
        return {};
    }
    std::vector<size_t> choices;
    for (size_t begin = 0; begin <= value.size();) {
        const size_t comma = std::min(value.find(',', begin), value.size());
        const std::string_view item = value.substr(begin, comma - begin);
        if (!item.empty()) {
            const size_t choice = find_choice(*spec, item);
            if (choice == spec->choices().size())
                return "unknown " + std::string(name) + " item '" + std::string(item) +
                       "' (known: " + choice_names(*spec) + ")";
            if (std::find(choices.begin(), choices.end(), choice) == choices.end()) choices.push_back(choice);
        }
        begin = comma + 1;
    }
    spec->set_list(s, choices);
    return {};
}

}  // namespace stratum
