// The one list of render settings (render/setting_registry.h) and its ABI (stratum_setting_*):
// every setting is described, accepts its whole range and its default, refuses what is outside
// naming the setting, and the defaults it reports are the renderer's.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "render/setting_registry.h"
#include "stratum/stratum.h"

using namespace stratum;

namespace {

std::string set_by_text(RenderSettings& s, const SettingSpec& spec, const std::string& text) {
    switch (spec.kind) {
        case SettingKind::Int:
            return set_int_setting(s, spec.info.name, std::stoll(text));
        case SettingKind::Float:
            return set_float_setting(s, spec.info.name, std::stod(text));
        case SettingKind::Choice:
        case SettingKind::List:
            return set_string_setting(s, spec.info.name, text);
    }
    return "no kind";
}

}  // namespace

TEST(SettingRegistry, EverySettingIsDescribedOnceAndTakesItsDefaultBack) {
    std::set<std::string> names;
    for (const SettingSpec& spec : setting_registry()) {
        const std::string name = spec.info.name;
        EXPECT_TRUE(names.insert(name).second) << name << " is listed twice";
        EXPECT_NE(std::string(spec.info.label), "") << name;
        EXPECT_NE(std::string(spec.info.description), "") << name;
        EXPECT_EQ(find_setting(name), &spec);
        // Setting the reported default changes nothing: it is the renderer's own.
        RenderSettings s;
        EXPECT_EQ(set_by_text(s, spec, default_value(spec)), "") << name << " = " << default_value(spec);
        if (spec.get) {
            EXPECT_EQ(spec.get(s), spec.get(RenderSettings{})) << name;
        }
    }
    EXPECT_EQ(find_setting("bogus"), nullptr);
}

TEST(SettingRegistry, DefaultsAreTheDocumentedOnes) {
    const auto def = [](const char* name) { return default_value(*find_setting(name)); };
    EXPECT_EQ(def("samples"), "16");
    EXPECT_EQ(def("max_bounces"), "12");
    EXPECT_EQ(def("filter_width"), "1.5");
    EXPECT_EQ(def("sampler"), "random");
    EXPECT_EQ(def("integrator"), "path");
    EXPECT_EQ(def("hemisphere"), "cosine");
    EXPECT_EQ(def("filter_type"), "blackman_harris");
    EXPECT_EQ(def("light_sampling"), "mis");
    EXPECT_EQ(def("mis_heuristic"), "power");
    EXPECT_EQ(def("light_selection"), "auto");
    EXPECT_EQ(def("triangle_sampling"), "solid_angle");
    EXPECT_EQ(def("rr_mode"), "throughput");
    EXPECT_EQ(def("passes"), "");
    // The integrator's defaults are IntegratorSettings' (one place).
    const IntegratorSettings integrator;
    EXPECT_EQ(def("rr_min_depth"), std::to_string(integrator.rr_min_depth));
    EXPECT_EQ(def("max_bounces"), std::to_string(integrator.max_bounces));
}

TEST(SettingRegistry, NumbersAreCheckedAgainstTheirRangeNamingTheSetting) {
    for (const SettingSpec& spec : setting_registry()) {
        RenderSettings s;
        const std::string name = spec.info.name;
        if (spec.kind == SettingKind::Int) {
            const auto lo = static_cast<int64_t>(spec.minimum), hi = static_cast<int64_t>(spec.maximum);
            EXPECT_EQ(set_int_setting(s, name, lo), "") << name;
            EXPECT_EQ(spec.get(s), spec.minimum) << name;
            EXPECT_EQ(set_int_setting(s, name, hi), "") << name;
            EXPECT_EQ(spec.get(s), spec.maximum) << name;
            for (const int64_t bad : {lo - 1, hi + 1}) {
                const std::string error = set_int_setting(s, name, bad);
                EXPECT_NE(error.find("'" + name + "' = " + std::to_string(bad)), std::string::npos) << error;
            }
            EXPECT_NE(set_float_setting(s, name, 1.0).find("is a integer setting"), std::string::npos);
        } else if (spec.kind == SettingKind::Float) {
            EXPECT_NE(set_float_setting(s, name, std::nan("")), "") << name;
            EXPECT_NE(set_float_setting(s, name, spec.minimum - 1.0), "") << name;
            EXPECT_EQ(set_float_setting(s, name, spec.open_minimum ? spec.minimum + 0.5 : spec.minimum), "")
                << name;
            if (std::isinf(spec.maximum)) {
                EXPECT_EQ(set_float_setting(s, name, spec.maximum), "") << name;
            } else {
                EXPECT_EQ(set_float_setting(s, name, spec.maximum), "") << name;
                EXPECT_NE(set_float_setting(s, name, std::numeric_limits<double>::infinity()), "") << name;
            }
        }
    }
    RenderSettings s;
    // A double that becomes 0 as the renderer's float is refused where 0 is.
    EXPECT_NE(set_float_setting(s, "ao_distance", 1e-50), "");
    EXPECT_NE(set_float_setting(s, "control_variate", 1e300), "");
    EXPECT_NE(set_int_setting(s, "bogus", 1).find("unknown integer setting 'bogus'"), std::string::npos);
    EXPECT_NE(set_int_setting(s, "sampler", 1).find("it is a string setting"), std::string::npos);
}

TEST(SettingRegistry, TheAbiServesTheSameList) {
    ASSERT_EQ(stratum_setting_count(), static_cast<int32_t>(setting_registry().size()));
    for (int32_t i = 0; i < stratum_setting_count(); ++i) {
        StratumSettingInfo info{};
        ASSERT_EQ(stratum_setting_info(i, &info), STRATUM_OK);
        const SettingSpec& spec = setting_registry()[static_cast<size_t>(i)];
        EXPECT_EQ(std::string(info.name), spec.info.name);
        EXPECT_EQ(info.kind, static_cast<int32_t>(spec.kind));
        EXPECT_EQ(std::string(info.default_value), default_value(spec));
        for (int32_t c = 0; c < info.choice_count; ++c) {
            const char* name = nullptr;
            ASSERT_EQ(stratum_setting_choice(i, c, &name, nullptr, nullptr), STRATUM_OK);
            EXPECT_EQ(std::string(name), spec.choices()[static_cast<size_t>(c)].name);
        }
        EXPECT_EQ(stratum_setting_choice(i, info.choice_count, nullptr, nullptr, nullptr),
                  STRATUM_ERROR_INVALID_ARGUMENT);
    }
    StratumSettingInfo info{};
    EXPECT_EQ(stratum_setting_info(stratum_setting_count(), &info), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(stratum_setting_info(0, nullptr), STRATUM_ERROR_INVALID_ARGUMENT);
}

TEST(SettingRegistry, AValueIsParsedOnceIntoWhatTheRendererReads) {
    RenderSettings s;
    ASSERT_EQ(set_string_setting(s, "light_sampling", "nee"), "");
    ASSERT_EQ(set_string_setting(s, "rr_mode", "off"), "");
    ASSERT_EQ(set_string_setting(s, "hemisphere", "uniform"), "");
    ASSERT_EQ(set_string_setting(s, "filter_type", "box"), "");
    ASSERT_EQ(set_string_setting(s, "sampler", "sobol"), "");
    ASSERT_EQ(set_string_setting(s, "passes", "Normal,,Normal"), "");
    EXPECT_EQ(s.estimator.light_sampling, LightSampling::Nee);
    EXPECT_EQ(s.estimator.rr_mode, RouletteMode::Off);
    EXPECT_EQ(s.estimator.hemisphere, HemisphereDistribution::Uniform);
    EXPECT_EQ(s.filter_type, FilterType::Box);
    EXPECT_EQ(std::string(s.sampler->info.name), "sobol");
    EXPECT_EQ(s.passes, std::vector<Pass>{Pass::Normal});
}

TEST(SettingRegistry, ChoicesOnlyGrowAtTheEnd) {
    // Blender stores an enum property as the position of its item, so a .blend saved today must
    // read the same choice tomorrow: these lists may gain entries at their end, never reorder
    // or lose one (scenes/ao_study.blend once read as 'light' because 'ao' moved).
    const std::pair<const char*, std::vector<std::string>> pinned[] = {
        {"sampler",
         {"random", "lcg", "stratified", "lhs", "halton", "halton_rd", "halton_owen", "sobol", "zsobol",
          "bluenoise", "fibonacci", "fibonacci_static"}},
        {"integrator", {"path", "light", "direct", "ao"}},
        {"hemisphere", {"uniform_angles", "uniform", "cosine"}},
        {"filter_type", {"box", "blackman_harris"}},
        {"light_sampling", {"mis", "nee", "bsdf"}},
        {"mis_heuristic", {"power", "balance", "max"}},
        {"light_selection", {"mixed", "power", "uniform", "tree", "auto"}},
        {"triangle_sampling", {"solid_angle", "area"}},
        {"rr_mode", {"throughput", "albedo", "off"}},
        {"bvh", {"static", "dynamic"}},
    };
    for (const auto& [name, names] : pinned) {
        const SettingSpec* spec = find_setting(name);
        ASSERT_NE(spec, nullptr) << name;
        ASSERT_GE(spec->choices().size(), names.size()) << name;
        for (size_t i = 0; i < names.size(); ++i)
            EXPECT_EQ(spec->choices()[i].name, names[i]) << name << " #" << i;
    }
}
