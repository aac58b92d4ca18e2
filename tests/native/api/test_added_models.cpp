// A light type and a closure model added by a test alone, through the registries' hooks
// (register_light_model, register_closure_model; docs/adding_models.md): nothing of the library
// names them, yet the C ABI accepts them and every estimator renders them.
//
// | model            | value | parameters                                                      |
// |------------------|-------|-----------------------------------------------------------------|
// | test sphere lamp | 31    | centre = the transform's translation, radius r > 0 (its own    |
// |                  |       | check), radiance L = color × strength from every point, outward |
// | test lambert     | 31    | f = ρ/π with the constant ρ = kTestAlbedo (base_color ignored), |
// |                  |       | sampled uniformly over the hemisphere (pdf 1/(2π))              |
//
// Closed form (the scene of lamp_over_plane): a diffuse plane z = 0 under the lamp, centre at
// height h. A plane point x at distance D = √(h² + |x|²) from the centre sees the sphere as a cone
// of half angle α, sin α = r/D, about the direction to the centre, at θ_c from the normal,
// cos θ_c = h/D; the cone lies above the horizon (θ_c + α < π/2). Its projected solid angle is
// π sin²α cos θ_c (the form factor of a sphere to a differential area, (r/D)² cos θ_c), so
//     E = ∫_cone L cos θ dω = π L r² h / D³,   L_o = (ρ/π) E = ρ L r² h / D³.
// Nothing else lights the plane (the background is black, the plane cannot see itself), so each
// pixel's expectation is L_o averaged over the pixel's filter footprint. The camera at height 1
// sees |x|, |y| <= 0.5 in 32 x 32 pixels; taking L_o at the pixel centres instead is off by the
// filter's second moment (under a pixel², (1/32)²) times |∇²L_o|/2 <= (3/h²) L_o/2 (from the
// expansion of h/D³), below 1e-3 L_o. Every estimator's image mean must lie within 4 standard
// errors, plus that 1e-3, of the mean of L_o over the pixel centres. The standard error comes
// from the spread of the image means of kSeeds independent renders (a light-tracing particle
// splats into several pixels, so pixel values are not independent; test_light_tracer.cpp):
// the ratio is t-distributed with kSeeds − 1 degrees of freedom, |t| > 4 has probability 5e-3,
// and the seeds are fixed.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "bsdf/bsdf.h"
#include "lights/light.h"
#include "lights/light_registry.h"
#include "render_helpers.h"
#include "sampling/warps.h"
#include "stratum/stratum.h"

using namespace stratum_test;

namespace {

using stratum::BsdfEval;
using stratum::BsdfSample;
using stratum::EmissionSample;
using stratum::Frame;
using stratum::HemisphereDistribution;
using stratum::LightSample;
using stratum::Material;
using stratum::Rgb;
using stratum::Vec2;
using stratum::Vec3;

constexpr int32_t kTestLightType = 31, kTestClosureModel = 31;
constexpr float kTestAlbedo = 0.6f;

class TestSphereLamp final : public stratum::Light {
public:
    TestSphereLamp(Vec3 center, float radius, Rgb radiance)
        : center_(center), radius_(radius), radiance_(radiance) {}

    bool is_delta() const override { return false; }
    bool is_hittable_lamp() const override { return true; }
    // A Lambertian emitter of area 4π r²: Φ = π L A.
    double power(float) const override {
        return stratum::mean(radiance_) * 4.0 * stratum::kPi * stratum::kPi * radius_ * radius_;
    }

    // Directions uniform in the cone the sphere subtends: pdf 1/(2π(1 − cos α)).
    bool sample(Vec3 p, Vec3, Vec2 u, stratum::TriangleSampling, LightSample* out) const override {
        const Vec3 to_center = center_ - p;
        const float d = stratum::length(to_center);
        if (!(d > radius_)) return false;
        const float cos_max = std::sqrt(1.0f - radius_ * radius_ / (d * d));
        const Vec3 wi = Frame::from_normal(to_center / d).to_world(stratum::sample_uniform_cone(u, cos_max));
        const float b = stratum::dot(to_center, wi);
        const float distance = b - std::sqrt(std::max(b * b - (d * d - radius_ * radius_), 0.0f));
        *out = {wi, distance, radiance_, cone_pdf(cos_max), true};
        return true;
    }

    // Point uniform on the sphere (p_A = 1/A), direction cosine-distributed about the outward
    // normal (p_ω = cos/π): weight L cos/(p_A p_ω) = π L A.
    bool sample_emission(Vec2 u_position, Vec2 u_direction, Vec3, float, EmissionSample* out) const override {
        const Vec3 n = stratum::sample_uniform_sphere(u_position);
        out->position = center_ + n * radius_;
        out->direction = Frame::from_normal(n).to_world(stratum::sample_cosine_hemisphere(u_direction));
        out->normal = n;
        out->weight = radiance_ * (4.0f * stratum::kPi * stratum::kPi * radius_ * radius_);
        out->soft_radius = 0.0f;
        return true;
    }

    bool intersect(Vec3 origin, Vec3 dir, float t_max, float* t, Rgb* radiance, float* pdf) const override {
        const Vec3 to_center = center_ - origin;
        const float d2 = stratum::dot(to_center, to_center), r2 = radius_ * radius_;
        if (!(d2 > r2)) return false;
        const float b = stratum::dot(to_center, dir);
        const float discriminant = b * b - (d2 - r2);
        if (!(b > 0.0f) || !(discriminant >= 0.0f)) return false;
        const float hit = b - std::sqrt(discriminant);
        if (!(hit < t_max)) return false;
        *t = hit;
        *radiance = radiance_;
        *pdf = cone_pdf(std::sqrt(1.0f - r2 / d2));
        return true;
    }

private:
    static float cone_pdf(float cos_max) { return 1.0f / (2.0f * stratum::kPi * (1.0f - cos_max)); }

    Vec3 center_;
    float radius_;
    Rgb radiance_;
};

void check_test_sphere_lamp_params(const stratum::LightParams&, stratum::LightParams* params) {
    if (!(params->radius > 0.0f)) throw std::invalid_argument("test sphere lamp radius must be > 0");
}

std::unique_ptr<stratum::Light> make_test_sphere_lamp(const stratum::LightParams& params) {
    return std::make_unique<TestSphereLamp>(params.light_to_world.translation(), params.radius,
                                            params.color * params.strength);
}

const stratum::LightModel kTestSphereLampModel{&make_test_sphere_lamp, &check_test_sphere_lamp_params};

BsdfEval test_lambert_eval(const Material&, Vec3 wo, Vec3 wi, HemisphereDistribution) {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return {Rgb(), 0.0f};
    return {Rgb(kTestAlbedo * stratum::kInvPi * wi.z), stratum::uniform_hemisphere_pdf()};
}

bool test_lambert_sample(const Material& m, Vec3 wo, float, Vec2 u, BsdfSample* out,
                         HemisphereDistribution h) {
    if (wo.z <= 0.0f) return false;
    const Vec3 wi = stratum::sample_uniform_hemisphere(u);
    const BsdfEval e = test_lambert_eval(m, wo, wi, h);
    if (!(e.pdf > 0.0f) || wi.z <= 0.0f) return false;
    *out = {wi, e.value / e.pdf, e.pdf, false, stratum::ScatterKind::Diffuse};
    return true;
}

const stratum::ClosureModel kTestLambertClosure{
    .eval = &test_lambert_eval,
    .sample = &test_lambert_sample,
    .is_delta = &stratum::answer_false,
    .has_transmission = &stratum::answer_false,
    .sample_weight = [](const Material&) { return kTestAlbedo; },
    .albedo_estimate = [](const Material&) { return Rgb(kTestAlbedo); },
    .kinds_above = stratum::scatter_kind_bit(stratum::ScatterKind::Diffuse),
    .kinds_below = stratum::scatter_kind_bit(stratum::ScatterKind::Diffuse),
};

// Once per process (gtest may run these tests in one process or one each).
bool register_test_models() {
    static const bool registered =
        stratum::register_light_model(kTestLightType, "test_sphere_lamp", kTestSphereLampModel) &&
        stratum::register_closure_model(kTestClosureModel, "test_lambert", kTestLambertClosure);
    return registered;
}

constexpr float kHeight = 2.0f, kRadius = 0.5f, kRadiance = 3.0f;
constexpr uint32_t kPixels = 32, kSeeds = 8;

StratumMaterialDesc test_material(int32_t model) {
    StratumMaterialDesc m{};
    m.model = model;
    m.base_color[0] = m.base_color[1] = m.base_color[2] = 0.5f;  // the test lambert ignores it
    m.ior = 1.5f;
    return m;
}

StratumLightDesc test_lamp(float radius) {
    StratumLightDesc l{};
    l.type = kTestLightType;
    l.color[0] = l.color[1] = l.color[2] = 1.0f;
    l.strength = kRadiance;
    l.radius = radius;
    std::copy(kIdentity, kIdentity + 16, l.transform);
    l.transform[11] = kHeight;
    return l;
}

// The test lamp over a 40 x 40 plane of the test closure, seen from height 1 by a camera looking
// down with a 1 x 1 view of the plane; nullptr on failure.
StratumScene* lamp_over_plane() {
    StratumScene* scene = nullptr;
    if (stratum_scene_create(&scene) != STRATUM_OK) return nullptr;
    const StratumMaterialDesc material = test_material(kTestClosureModel);
    const float positions[] = {-20, -20, 0, 20, -20, 0, 20, 20, 0, -20, 20, 0};
    const uint32_t triangles[] = {0, 1, 2, 0, 2, 3};
    const uint32_t material_ids[] = {0, 0};
    uint32_t mat = 0, mesh_id = 0;
    StratumCameraDesc camera = camera_at(0.0f, 0.0f, 1.0f);
    camera.lens_mm = 36.0f;  // 36 mm sensor: half width 18/36 = 0.5 at distance 1
    const StratumLightDesc light = test_lamp(kRadius);
    const StratumMeshDesc mesh{positions, 4, triangles, 2, nullptr, nullptr, material_ids};
    if (stratum_scene_add_material(scene, &material, &mat) != STRATUM_OK ||
        stratum_scene_add_mesh(scene, &mesh, &mesh_id) != STRATUM_OK ||
        stratum_scene_add_instance(scene, mesh_id, kIdentity) != STRATUM_OK ||
        stratum_scene_add_light(scene, &light) != STRATUM_OK ||
        stratum_scene_set_camera(scene, &camera) != STRATUM_OK) {
        stratum_scene_destroy(scene);
        return nullptr;
    }
    return scene;
}

}  // namespace

TEST(AddedModels, TheAbiKnowsRegisteredModelsAndTheirOwnChecks) {
    ASSERT_TRUE(register_test_models());
    StratumScene* scene = nullptr;
    ASSERT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    StratumLightDesc light = test_lamp(0.0f);
    EXPECT_EQ(stratum_scene_add_light(scene, &light), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("test sphere lamp radius"), std::string::npos)
        << stratum_last_error();
    light.radius = kRadius;
    EXPECT_EQ(stratum_scene_add_light(scene, &light), STRATUM_OK) << stratum_last_error();
    light.type = kTestLightType - 1;  // nothing registered there
    EXPECT_EQ(stratum_scene_add_light(scene, &light), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("is not a StratumLightType"), std::string::npos)
        << stratum_last_error();
    StratumMaterialDesc material = test_material(kTestClosureModel - 1);
    EXPECT_EQ(stratum_scene_add_material(scene, &material, nullptr), STRATUM_ERROR_INVALID_ARGUMENT);
    material.model = kTestClosureModel;
    EXPECT_EQ(stratum_scene_add_material(scene, &material, nullptr), STRATUM_OK) << stratum_last_error();
    // A taken value is not registered again.
    EXPECT_FALSE(stratum::register_light_model(kTestLightType, "again", kTestSphereLampModel));
    EXPECT_FALSE(stratum::register_closure_model(STRATUM_MATERIAL_DIFFUSE, "again", kTestLambertClosure));
    stratum_scene_destroy(scene);
}

// Hosts find a model's value by its name (stratum_model_entry): the registered models are listed
// last, in value order, so a host mirrors no number of them.
TEST(AddedModels, TheAbiListsRegisteredModelsByName) {
    ASSERT_TRUE(register_test_models());
    for (const auto& [kind, name] : {std::pair{STRATUM_MODEL_LIGHT, "test_sphere_lamp"},
                                     std::pair{STRATUM_MODEL_CLOSURE, "test_lambert"}}) {
        const int32_t count = stratum_model_count(kind);
        ASSERT_GE(count, 2);
        const char* last_name = nullptr;
        int32_t last_value = -1;
        ASSERT_EQ(stratum_model_entry(kind, count - 1, &last_name, &last_value), STRATUM_OK);
        EXPECT_STREQ(last_name, name);
        EXPECT_EQ(last_value, 31);
        EXPECT_EQ(stratum_model_entry(kind, count, &last_name, &last_value), STRATUM_ERROR_INVALID_ARGUMENT);
    }
}

TEST(AddedModels, DiffusePlaneUnderTheTestLampIsTheClosedForm) {
    ASSERT_TRUE(register_test_models());
    StratumScene* scene = lamp_over_plane();
    ASSERT_NE(scene, nullptr) << stratum_last_error();
    double expected = 0.0;
    for (uint32_t j = 0; j < kPixels; ++j) {
        for (uint32_t i = 0; i < kPixels; ++i) {
            const double x = (i + 0.5) / kPixels - 0.5, y = (j + 0.5) / kPixels - 0.5;
            const double D = std::sqrt(kHeight * kHeight + x * x + y * y);
            expected += kTestAlbedo * kRadiance * kRadius * kRadius * kHeight / (D * D * D);
        }
    }
    expected /= kPixels * kPixels;
    const double footprint = 1e-3 * expected;
    // NEE alone asks sample(), BSDF rays alone intersect() and the closure's sample(), MIS both
    // with eval(); light tracing asks sample_emission() and eval().
    const struct {
        const char* integrator;
        const char* light_sampling;
    } estimators[] = {{"path", "mis"}, {"path", "nee"}, {"path", "bsdf"}, {"light", "mis"}};
    for (const auto& e : estimators) {
        const Measurement m = measure(scene,
                                      {{"width", kPixels},
                                       {"height", kPixels},
                                       {"samples", 64},
                                       {"integrator", e.integrator},
                                       {"light_sampling", e.light_sampling}},
                                      kSeeds);
        ASSERT_TRUE(m.error.empty()) << e.integrator << " " << e.light_sampling << ": " << m.error;
        EXPECT_NEAR(m.mean, expected, 4.0 * m.standard_error + footprint)
            << e.integrator << " " << e.light_sampling << ": mean " << m.mean << " expected " << expected
            << " (se " << m.standard_error << ")";
        EXPECT_LT(m.standard_error, 0.03 * expected) << e.integrator << " " << e.light_sampling;
    }
    stratum_scene_destroy(scene);
}
