#include "lights/light_registry.h"

#include <stdexcept>
#include <string>

#include "lights/area_light.h"
#include "lights/point_light.h"
#include "lights/spot_light.h"
#include "lights/sun_light.h"

namespace stratum {

namespace {

// The light types of the C ABI, one line each: StratumLightType's value, its enumerator's name
// in lower case without STRATUM_LIGHT_, the model. tests/python/test_models.py checks the lines
// against include/stratum/stratum.h.
constinit LightModels g_light_models{
    {0, "point", &kPointLightModel},
    {1, "sun", &kSunLightModel},
    {2, "area_rectangle", &kRectangleAreaLightModel},
    {3, "area_ellipse", &kEllipseAreaLightModel},
    {4, "spot", &kSpotLightModel},
    {5, "spot_v1", &kSpotV1LightModel},
};

}  // namespace

const LightModels& light_models() { return g_light_models; }

const LightModel* find_light_model(int32_t type) { return g_light_models.find(type); }

std::unique_ptr<Light> make_light(const LightParams& params) {
    const LightModel* model = find_light_model(params.type);
    if (!model) throw std::runtime_error("light type " + std::to_string(params.type) + " has no model");
    return model->make(params);
}

bool register_light_model(int32_t type, const char* name, const LightModel& model) {
    return g_light_models.add({type, name, &model});
}

}  // namespace stratum
