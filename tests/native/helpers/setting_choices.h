// The names of a setting's choices as the C ABI lists them (stratum_setting_info,
// stratum_setting_choice): the samplers, integrators, hemisphere distributions... a test loops
// over, so that one added to the library is tested without touching the test.
#pragma once

#include <string>
#include <vector>

#include "stratum/stratum.h"

inline std::vector<const char*> setting_choices(const char* setting) {
    std::vector<const char*> names;
    for (int32_t i = 0; i < stratum_setting_count(); ++i) {
        StratumSettingInfo info{};
        if (stratum_setting_info(i, &info) != STRATUM_OK || std::string(info.name) != setting) continue;
        for (int32_t c = 0; c < info.choice_count; ++c) {
            const char* name = nullptr;
            if (stratum_setting_choice(i, c, &name, nullptr, nullptr) == STRATUM_OK) names.push_back(name);
        }
    }
    return names;
}
