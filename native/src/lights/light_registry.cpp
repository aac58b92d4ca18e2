#include "lights/light_registry.h"

#include <array>
#include <stdexcept>
#include <string>
#include <utility>

#include "lights/area_light.h"
#include "lights/point_light.h"
#include "lights/spot_light.h"
#include "lights/sun_light.h"

namespace stratum {

namespace {

// The light types of the C ABI, one line each.
constexpr std::pair<LightType, const LightModel*> kLightModels[] = {
    {LightType::Point, &kPointLightModel},
    {LightType::Sun, &kSunLightModel},
    {LightType::AreaRectangle, &kRectangleAreaLightModel},
    {LightType::AreaEllipse, &kEllipseAreaLightModel},
    {LightType::Spot, &kSpotLightModel},
    {LightType::SpotV1, &kSpotV1LightModel},
};

using LightModelTable = std::array<const LightModel*, kMaxLightTypes>;

// Indexed by type; filled at compile time (constinit: no static-initialisation order to mind).
constinit LightModelTable g_light_models = [] {
    LightModelTable table{};
    for (const auto& [type, model] : kLightModels) table[static_cast<uint32_t>(type)] = model;
    return table;
}();

}  // namespace

const LightModel* find_light_model(LightType type) {
    const auto index = static_cast<uint32_t>(type);
    return index < kMaxLightTypes ? g_light_models[index] : nullptr;
}

std::unique_ptr<Light> make_light(const LightParams& params) {
    const LightModel* model = find_light_model(params.type);
    if (!model) {
        throw std::runtime_error("light type " + std::to_string(static_cast<int32_t>(params.type)) +
                                 " has no model");
    }
    return model->make(params);
}

bool register_light_model(LightType type, const LightModel& model) {
    const auto index = static_cast<uint32_t>(type);
    if (index >= kMaxLightTypes || g_light_models[index]) return false;
    g_light_models[index] = &model;
    return true;
}

}  // namespace stratum
