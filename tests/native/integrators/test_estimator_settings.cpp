// The estimator settings of issue 6 at the C ABI (names, ranges, messages), the MIS heuristics,
// the light selection distributions, and the renderer's notices. The analytic scenes that show
// each estimator unbiased are in test_integrating_sphere*.cpp and test_emitter_normalisation.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "integrators/estimator_options.h"
#include "lights/light_set.h"
#include "lights/point_light.h"
#include "render/setting_registry.h"
#include "render_helpers.h"

using namespace stratum;
using namespace stratum_test;

namespace {

struct RendererFixture : ::testing::Test {
    void SetUp() override {
        scene = make_sphere_interior(diffuse_grey(0.5f), 8, 0.0f, 0.0f, 0.0f);
        ASSERT_NE(scene, nullptr) << stratum_last_error();
        ASSERT_EQ(stratum_renderer_create(scene, &renderer), STRATUM_OK) << stratum_last_error();
    }
    void TearDown() override {
        stratum_renderer_destroy(renderer);
        stratum_scene_destroy(scene);
    }
    // Adds a point light of radius `radius` at the origin (before the renderer copies the scene).
    void recreate_with_point_light(float radius) {
        StratumLightDesc light{};
        light.type = STRATUM_LIGHT_POINT;
        light.color[0] = light.color[1] = light.color[2] = 1.0f;
        light.strength = 10.0f;
        light.radius = radius;
        std::copy(kIdentity, kIdentity + 16, light.transform);
        ASSERT_EQ(stratum_scene_add_light(scene, &light), STRATUM_OK) << stratum_last_error();
        stratum_renderer_destroy(renderer);
        ASSERT_EQ(stratum_renderer_create(scene, &renderer), STRATUM_OK) << stratum_last_error();
    }
    std::string start_and_notices() {
        stratum_renderer_set_int(renderer, "width", 4);
        stratum_renderer_set_int(renderer, "height", 4);
        stratum_renderer_set_int(renderer, "samples", 1);
        EXPECT_TRUE(render_to_end(renderer)) << stratum_last_error();
        const char* notices = nullptr;
        EXPECT_EQ(stratum_renderer_notices(renderer, &notices), STRATUM_OK);
        return notices ? notices : "";
    }
    StratumScene* scene = nullptr;
    StratumRenderer* renderer = nullptr;
};

}  // namespace

TEST_F(RendererFixture, EveryOptionValueIsAcceptedAndUnknownOnesAreNamed) {
    // Every enumerated setting of the registry, each of its values, and a bogus one.
    for (const SettingSpec& spec : setting_registry()) {
        if (spec.kind != SettingKind::Choice) continue;
        const char* name = spec.info.name;
        ASSERT_FALSE(spec.choices().empty()) << name;
        for (const RegistryEntry& value : spec.choices()) {
            EXPECT_EQ(stratum_renderer_set_string(renderer, name, value.name), STRATUM_OK)
                << name << "=" << value.name << ": " << stratum_last_error();
        }
        EXPECT_EQ(stratum_renderer_set_string(renderer, name, "bogus"), STRATUM_ERROR_INVALID_ARGUMENT);
        const std::string message = stratum_last_error();
        EXPECT_NE(message.find("bogus"), std::string::npos) << message;
        EXPECT_NE(message.find(spec.choices()[0].name), std::string::npos) << message;  // lists the choices
    }
    EXPECT_EQ(light_sampling_choices().size(), 3u);
    EXPECT_EQ(triangle_sampling_choices().size(), 2u);
    for (const char* integrator : {"path", "direct", "ao"}) {
        EXPECT_EQ(stratum_renderer_set_string(renderer, "integrator", integrator), STRATUM_OK) << integrator;
    }
}

TEST_F(RendererFixture, NumericEstimatorSettingsAreRangeChecked) {
    EXPECT_EQ(stratum_renderer_set_int(renderer, "rr_min_depth", 0), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_set_int(renderer, "rr_min_depth", 1024), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_set_int(renderer, "rr_min_depth", -1), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("rr_min_depth"), std::string::npos);
    EXPECT_EQ(stratum_renderer_set_float(renderer, "control_variate", 0.0), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_set_float(renderer, "control_variate", 2.5), STRATUM_OK);
    for (const double bad : {-0.5, std::nan(""), double(INFINITY), 1e300}) {
        EXPECT_EQ(stratum_renderer_set_float(renderer, "control_variate", bad),
                  STRATUM_ERROR_INVALID_ARGUMENT)
            << bad;
        EXPECT_NE(std::string(stratum_last_error()).find("control_variate"), std::string::npos);
    }
}

TEST_F(RendererFixture, BsdfSamplingAloneSaysWhyAPointLightIsMissing) {
    recreate_with_point_light(0.0f);
    ASSERT_EQ(stratum_renderer_set_string(renderer, "light_sampling", "bsdf"), STRATUM_OK);
    const std::string notice = start_and_notices();
    EXPECT_NE(notice.find("'bsdf'"), std::string::npos) << notice;
    EXPECT_NE(notice.find("1 light"), std::string::npos) << notice;
    // NEE and MIS see it: no notice; neither does a point light with a radius (a disk rays hit).
    for (const char* mode : {"nee", "mis"}) {
        ASSERT_EQ(stratum_renderer_set_string(renderer, "light_sampling", mode), STRATUM_OK);
        EXPECT_EQ(start_and_notices(), "") << mode;
    }
}

TEST_F(RendererFixture, PointLightWithRadiusIsFoundByBsdfSampling) {
    recreate_with_point_light(0.2f);
    ASSERT_EQ(stratum_renderer_set_string(renderer, "light_sampling", "bsdf"), STRATUM_OK);
    EXPECT_EQ(start_and_notices(), "");
}

TEST(MisHeuristics, WeightsOfTheTwoStrategiesSumToOne) {
    const float pdfs[] = {0.0f, 1e-30f, 0.3f, 1.0f, 7.5f, 1e20f, 3e38f};
    for (const MisHeuristic h : {MisHeuristic::Balance, MisHeuristic::Power, MisHeuristic::Maximum}) {
        for (const float a : pdfs) {
            for (const float b : pdfs) {
                if (a == 0.0f && b == 0.0f) continue;
                const float sum = mis_weight(h, a, b) + mis_weight(h, b, a);
                EXPECT_NEAR(sum, 1.0f, 1e-6f) << static_cast<int>(h) << " " << a << " " << b;
            }
        }
    }
    // Closed forms (Veach 1997 §9.2): balance 1/(1+r), power 1/(1+r²), max: the larger wins.
    EXPECT_FLOAT_EQ(mis_weight(MisHeuristic::Balance, 1.0f, 3.0f), 0.25f);
    EXPECT_FLOAT_EQ(mis_weight(MisHeuristic::Power, 1.0f, 3.0f), 0.1f);
    EXPECT_EQ(mis_weight(MisHeuristic::Maximum, 1.0f, 3.0f), 0.0f);
    EXPECT_EQ(mis_weight(MisHeuristic::Maximum, 3.0f, 1.0f), 1.0f);
    EXPECT_EQ(mis_weight(MisHeuristic::Maximum, 2.0f, 2.0f), 0.5f);
    EXPECT_EQ(mis_weight(MisHeuristic::Power, 0.0f, 2.0f), 0.0f);
}

TEST(LightSelection, PowerUniformAndMixedDistributions) {
    // Two lamps of 10 W and 30 W and a 2-triangle emitter of one object (1 W + 3 W).
    LightSet set;
    set.add(PointLight(Vec3{0, 0, 0}, Rgb(10.0f), 0.0f), 0);
    set.add(PointLight(Vec3{1, 0, 0}, Rgb(30.0f), 0.0f), 1);
    const Rgb l(0.5f / kPi);  // two-sided (Cycles mesh lights): Φ = 2π L A
    set.add(EmissiveTriangle(Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 2, 0}, l), 2);  // A = 1
    set.add(EmissiveTriangle(Vec3{0, 0, 0}, Vec3{3, 0, 0}, Vec3{0, 2, 0}, l), 2);  // A = 3
    set.finalize(10.0f);
    const double powers[] = {10, 30, 1, 3};
    for (uint32_t i = 0; i < 4; ++i) {
        EXPECT_NEAR(set.power(i), powers[i], 1e-4 * powers[i]) << i;
        EXPECT_NEAR(set.probability(i, LightSelection::Power), powers[i] / 44.0, 1e-6) << i;
        EXPECT_NEAR(set.probability(i, LightSelection::Uniform), 0.25, 1e-7) << i;
    }
    // Mixed: ½ Φ_j/ΣΦ + ½ (1/3 objects) Φ_j/Φ_object.
    EXPECT_NEAR(set.probability(0, LightSelection::Mixed), 0.5 * 10 / 44 + 0.5 / 3, 1e-6);
    EXPECT_NEAR(set.probability(3, LightSelection::Mixed), 0.5 * 3 / 44 + 0.5 / 3 * 0.75, 1e-6);
    // choose() inverts each cdf: the interval of light i has the width of its probability.
    for (const LightSelection s : {LightSelection::Mixed, LightSelection::Power, LightSelection::Uniform}) {
        float start = 0.0f;
        for (uint32_t i = 0; i < 4; ++i) {
            EXPECT_EQ(set.choose(start + 0.5f * set.probability(i, s), s), i);
            start += set.probability(i, s);
        }
        EXPECT_EQ(set.choose(0.9999999f, s), 3u);
    }
}
