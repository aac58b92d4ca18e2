// Issue 6 acceptance point 3: emitter normalisation (textbook Q2.3–2.4, research/textbook.md
// §2.3). A Lambertian a×b panel of radiance L₀ emits Φ = ∫∫ L₀ cos θ dω dA = πL₀ab from its
// face. Checked two ways, for an emissive mesh quad (Emission material, two-sided as in Cycles:
// 2πL₀ab from both faces) and for an area lamp (StratumLightDesc rectangle: power P, radiance
// P/(π·ab), so P = πL₀ab gives the same radiance):
// * the power the LightSet assigns to the emitter;
// * the irradiance E on a facing diffuse plane, measured by path tracing and by light tracing,
//   against each other and against the closed form for a rectangle on a parallel plane.
//
// Closed form (Howell, "A Catalog of Radiation Heat Transfer Configuration Factors", case B-3;
// Modest, "Radiative Heat Transfer", App. D, config. 11): a differential element at height c
// below one corner of a parallel rectangle of sides a, b has the configuration factor
//     F = 1/(2π) [ X/√(1+X²) atan(Y/√(1+X²)) + Y/√(1+Y²) atan(X/√(1+Y²)) ],  X = a/c, Y = b/c,
// so E = πL₀F. Any point follows by superposing the four corner rectangles with signs.
//
// Scene: panel 0.6 × 0.4 of radiance 2 centred at (0.15, 0.05, 1) facing −Z; a diffuse floor of
// reflectance ρ = 0.8 (40 × 40 at z = 0); black background. The floor's radiance is ρE/π (one
// reflection only: the panel does not reflect and the floor is flat). The camera at height 0.5
// looks straight down with a 90° field of view: the floor is parallel to the image plane, so
// every pixel's footprint is an equal square and, with a box filter of width 1, the image mean
// is the average of ρE/π over the viewed square [−0.5, 0.5]². The closed form is averaged over
// it by a 64 × 64 midpoint rule; its error is ≤ (h²/24)·max|∇²E| with h = 1/64, and E varies
// no faster than a small source's E₀/(1 + r²)², whose Laplacian is ≤ 8E₀ (c = 1): ≤ 1e-4 E,
// far below the tolerance.
//
// Standard errors: path tracing with the `random` sampler has independent pixels (s/√P); the
// light tracer splats each particle into many pixels, so it is measured over 8 seeds
// (seed_stats). Agreement is accepted within 4σ of the difference, σ = √(σ₁² + σ₂²).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "api/scene_handle.h"
#include "render_helpers.h"
#include "render_scene/render_scene.h"

using namespace stratum_test;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr float kA = 0.6f, kB = 0.4f, kL0 = 2.0f, kRho = 0.8f;
constexpr double kHalfView = 0.5;  // the floor square the camera sees: 90° from height 0.5

// Where the panel's centre is.
struct Panel {
    float centre_x, centre_y, height;
};
constexpr Panel kOverhead = {0.15f, 0.05f, 1.0f};
// 2 cm over the floor, just outside the view: its near edge x = 0.52 at z = 0.02 projects to
// 0.52 · 0.5/0.48 = 0.54 > 0.5 on the floor, so the camera sees floor only, down to 2.8 cm from
// the edge (the gap over the Cornell box's ceiling: test_triangle_sampling_near_an_emitter).
constexpr Panel kBeside = {0.82f, 0.0f, 0.02f};

enum class Emitter { MeshQuad, AreaLamp };

StratumScene* make_panel_scene(Emitter emitter, const Panel& panel = kOverhead) {
    StratumScene* scene = nullptr;
    if (stratum_scene_create(&scene) != STRATUM_OK) return nullptr;
    const StratumMaterialDesc floor_material{
        STRATUM_MATERIAL_DIFFUSE, {kRho, kRho, kRho},    1.0f, 0.0f, 0.0f, 1.5f,
        {0.0f, 0.0f, 0.0f},       STRATUM_MICROFACET_GGX};
    const StratumMaterialDesc panel_material{
        STRATUM_MATERIAL_EMISSION, {0.0f, 0.0f, 0.0f},    1.0f, 0.0f, 0.0f, 1.5f,
        {kL0, kL0, kL0},           STRATUM_MICROFACET_GGX};
    const float x0 = panel.centre_x - 0.5f * kA, x1 = panel.centre_x + 0.5f * kA;
    const float y0 = panel.centre_y - 0.5f * kB, y1 = panel.centre_y + 0.5f * kB;
    const float z = panel.height;
    std::vector<float> positions = {-20, -20, 0, 20, -20, 0, 20, 20, 0, -20, 20, 0};
    std::vector<uint32_t> triangles = {0, 1, 2, 0, 2, 3};
    std::vector<uint32_t> materials = {0, 0};
    if (emitter == Emitter::MeshQuad) {
        positions.insert(positions.end(), {x0, y0, z, x1, y0, z, x1, y1, z, x0, y1, z});
        triangles.insert(triangles.end(), {4, 6, 5, 4, 7, 6});  // wound to face −Z
        materials.insert(materials.end(), {1, 1});
    }
    const StratumMeshDesc mesh{positions.data(), static_cast<uint32_t>(positions.size() / 3),
                               triangles.data(), static_cast<uint32_t>(triangles.size() / 3),
                               nullptr,          nullptr,
                               materials.data()};
    const StratumCameraDesc camera = camera_at(0.0f, 0.0f, 0.5f);
    const float black[3] = {0.0f, 0.0f, 0.0f};
    uint32_t id = 0;
    bool ok = stratum_scene_add_material(scene, &floor_material, &id) == STRATUM_OK &&
              stratum_scene_add_material(scene, &panel_material, &id) == STRATUM_OK &&
              stratum_scene_add_mesh(scene, &mesh, &id) == STRATUM_OK &&
              stratum_scene_add_instance(scene, id, kIdentity) == STRATUM_OK &&
              stratum_scene_set_camera(scene, &camera) == STRATUM_OK &&
              stratum_scene_set_background(scene, black) == STRATUM_OK;
    if (ok && emitter == Emitter::AreaLamp) {
        StratumLightDesc lamp{};
        lamp.type = STRATUM_LIGHT_AREA_RECTANGLE;
        lamp.color[0] = lamp.color[1] = lamp.color[2] = 1.0f;
        lamp.strength = static_cast<float>(kPi * kL0 * kA * kB);  // P = πL₀ab: radiance L₀
        lamp.size_x = kA;
        lamp.size_y = kB;
        std::copy(kIdentity, kIdentity + 16, lamp.transform);  // local −Z = world −Z: faces the floor
        lamp.transform[3] = panel.centre_x;
        lamp.transform[7] = panel.centre_y;
        lamp.transform[11] = panel.height;
        ok = stratum_scene_add_light(scene, &lamp) == STRATUM_OK;
    }
    if (!ok) {
        stratum_scene_destroy(scene);
        return nullptr;
    }
    return scene;
}

// Irradiance at the floor point (px, py) from the panel (Howell B-3 by superposition).
double panel_irradiance(double px, double py, const Panel& panel = kOverhead) {
    const double c = panel.height;
    // Signed corner term: the rectangle [0, u] × [0, v] (u, v may be negative) above the point.
    const auto corner = [c](double u, double v) {
        const double su = u < 0 ? -1.0 : 1.0, sv = v < 0 ? -1.0 : 1.0;
        const double X = std::abs(u) / c, Y = std::abs(v) / c;
        const double rx = std::sqrt(1.0 + X * X), ry = std::sqrt(1.0 + Y * Y);
        const double F = (X / rx * std::atan(Y / rx) + Y / ry * std::atan(X / ry)) / (2.0 * kPi);
        return su * sv * F;
    };
    const double x0 = panel.centre_x - 0.5 * kA - px, x1 = panel.centre_x + 0.5 * kA - px;
    const double y0 = panel.centre_y - 0.5 * kB - py, y1 = panel.centre_y + 0.5 * kB - py;
    const double F = corner(x1, y1) - corner(x0, y1) - corner(x1, y0) + corner(x0, y0);
    return kPi * kL0 * F;
}

// The average of the closed form over the viewed square (midpoint rule, kN × kN).
template <int kN = 64>
double viewed_irradiance(const Panel& panel = kOverhead) {
    double sum = 0;
    for (int i = 0; i < kN; ++i)
        for (int j = 0; j < kN; ++j)
            sum += panel_irradiance(-kHalfView + 2 * kHalfView * (i + 0.5) / kN,
                                    -kHalfView + 2 * kHalfView * (j + 0.5) / kN, panel);
    return sum / (kN * kN);
}

// The floor's irradiance averaged over the view, E = π·(image mean)/ρ, and its standard error.
// `estimator`: further settings (light_sampling, triangle_sampling). `seeds` > 1 measures the
// standard error from the spread of the image means (render_helpers.h); with 1 it comes from
// the pixels' spread, which also counts the image's own variation (an upper bound, tight when the
// image is uniform; the light tracer's pixels are correlated, so it always takes 8 seeds).
Measurement measure_irradiance(StratumScene* scene, const char* integrator, const Settings& estimator = {},
                               uint32_t seeds = 1) {
    const bool light_tracer = std::string_view(integrator) == "light";
    Settings settings = {
        {"width", 32},          {"height", 32},        {"samples", 64},           {"seed", 5u},
        {"filter_type", "box"}, {"filter_width", 1.0}, {"integrator", integrator}};
    settings.insert(settings.end(), estimator.begin(), estimator.end());
    Measurement m = measure(scene, settings, light_tracer ? 8 : seeds);
    m.mean *= kPi / kRho;
    m.standard_error *= kPi / kRho;
    return m;
}

double light_set_power(StratumScene* scene) {
    return scene->live->read([](const stratum::Scene& s) {
        const stratum::RenderScene render_scene(s);
        const stratum::LightSet& lights = render_scene.lights();
        double total = 0;
        for (uint32_t i = 0; i < lights.size(); ++i) total += lights.power(static_cast<uint32_t>(i));
        return total;
    });
}

}  // namespace

// The closed form itself: far below an infinite panel, E → πL₀ (F → 1); a unit corner square
// at height 1 has F = (1/2π)·2·(1/√2)·atan(1/√2) = 0.13853 (Howell B-3 table value 0.1385).
TEST(EmitterNormalisation, ClosedFormReproducesItsLimits) {
    EXPECT_NEAR(2.0 * (1.0 / std::sqrt(2.0)) * std::atan(1.0 / std::sqrt(2.0)) / (2.0 * kPi), 0.1385, 1e-4);
    const double centre = panel_irradiance(kOverhead.centre_x, kOverhead.centre_y);
    // Small-panel limit at the centre: E ≈ L₀·ab/c² (solid angle × cos², cos ≈ 1), slightly less.
    EXPECT_LT(centre, kL0 * kA * kB);
    EXPECT_GT(centre, 0.8 * kL0 * kA * kB);
}

TEST(EmitterNormalisation, LightSetPowerIsPiRadianceArea) {
    const double flux = kPi * kL0 * kA * kB;
    StratumScene* quad = make_panel_scene(Emitter::MeshQuad);
    ASSERT_NE(quad, nullptr) << stratum_last_error();
    // An emissive triangle emits from both faces (Cycles' mesh emission is two-sided).
    EXPECT_NEAR(light_set_power(quad), 2.0 * flux, 1e-5 * flux);
    stratum_scene_destroy(quad);
    StratumScene* lamp = make_panel_scene(Emitter::AreaLamp);
    ASSERT_NE(lamp, nullptr) << stratum_last_error();
    EXPECT_NEAR(light_set_power(lamp), flux, 1e-5 * flux);
    stratum_scene_destroy(lamp);
}

TEST(EmitterNormalisation, PathTracingMeasuresTheClosedFormIrradiance) {
    const double expected = viewed_irradiance();
    for (const Emitter emitter : {Emitter::MeshQuad, Emitter::AreaLamp}) {
        const char* name = emitter == Emitter::MeshQuad ? "mesh quad" : "area lamp";
        StratumScene* scene = make_panel_scene(emitter);
        ASSERT_NE(scene, nullptr) << stratum_last_error();
        // "tree" splits (8 cut nodes, the default); "tree unsplit" is one light per vertex.
        for (const char* selection : {"mixed", "tree", "tree unsplit"}) {
            const bool unsplit = std::string(selection) == "tree unsplit";
            const Measurement m =
                unsplit ? measure_irradiance(scene, "path",
                                             {{"light_selection", "tree"}, {"light_tree_splits", 1}})
                        : measure_irradiance(scene, "path", {{"light_selection", selection}});
            ASSERT_TRUE(m.error.empty()) << m.error;
            EXPECT_NEAR(m.mean, expected, 4.0 * m.standard_error)
                << name << ", " << selection << ": E " << m.mean << " expected " << expected << " se "
                << m.standard_error;
            EXPECT_GT(m.standard_error, 0.0) << name;
        }
        stratum_scene_destroy(scene);
    }
}

TEST(EmitterNormalisation, LightTracingMeasuresWhatPathTracingMeasures) {
    const double expected = viewed_irradiance();
    for (const Emitter emitter : {Emitter::MeshQuad, Emitter::AreaLamp}) {
        const char* name = emitter == Emitter::MeshQuad ? "mesh quad" : "area lamp";
        StratumScene* scene = make_panel_scene(emitter);
        ASSERT_NE(scene, nullptr) << stratum_last_error();
        const Measurement path = measure_irradiance(scene, "path");
        const Measurement light = measure_irradiance(scene, "light");
        ASSERT_TRUE(path.error.empty()) << path.error;
        ASSERT_TRUE(light.error.empty()) << light.error;
        const double se = std::hypot(path.standard_error, light.standard_error);
        EXPECT_NEAR(light.mean, path.mean, 4.0 * se)
            << name << ": light " << light.mean << " path " << path.mean << " se " << se;
        EXPECT_NEAR(light.mean, expected, 4.0 * light.standard_error)
            << name << ": light " << light.mean << " expected " << expected;
        EXPECT_LT(light.standard_error, 0.02 * expected) << name;
        stratum_scene_destroy(scene);
    }
}

// The panel 2 cm over the floor (kBeside): every strategy of finding the emitter measures the
// same irradiance, with either way of sampling its triangles (lights/emissive_triangle.h; the
// bound on solid-angle sampling's weight is test_triangle_light_sampling.cpp's). Floor points 2.8 cm from the
// panel's edge get area samples of weight up to ρ/π · L₀ · A/r² ≈ 0.8/π · 2 · 0.12/0.0008 ≈ 76 (against an
// image mean of ≈ 0.15), the Cornell box's ceiling gap in small. The closed form varies on the panel's height
// scale there, so it is averaged on a 1024² grid: the midpoint rule's error (h²/24)·|∇²E| with h = 1/1024 and
// |∇²E| ≤ 8E/c², c = 0.02, is ≤ 8e-4 E in the strip next to the panel and far less elsewhere, below the
// tolerances.
TEST(EmitterNormalisation, EveryWayOfFindingAPanelTwoCentimetresAwayMeasuresTheClosedForm) {
    const double expected = viewed_irradiance<1024>(kBeside);
    StratumScene* scene = make_panel_scene(Emitter::MeshQuad, kBeside);
    ASSERT_NE(scene, nullptr) << stratum_last_error();
    struct Case {
        const char* label;
        Settings settings;
    };
    const Case cases[] = {
        {"bsdf", {{"light_sampling", "bsdf"}}},
        {"nee, area", {{"light_sampling", "nee"}, {"triangle_sampling", "area"}}},
        {"nee, solid angle", {{"light_sampling", "nee"}, {"triangle_sampling", "solid_angle"}}},
        {"mis, area", {{"light_sampling", "mis"}, {"triangle_sampling", "area"}}},
        {"mis, solid angle", {{"light_sampling", "mis"}, {"triangle_sampling", "solid_angle"}}},
        {"nee, tree", {{"light_sampling", "nee"}, {"light_selection", "tree"}}},
        {"mis, tree", {{"light_sampling", "mis"}, {"light_selection", "tree"}}},
        {"mis, tree unsplit",
         {{"light_sampling", "mis"}, {"light_selection", "tree"}, {"light_tree_splits", 1}}},
        // Path guiding: the tree learns the panel from the first 32 samples (guided_direction.h).
        {"bsdf, guided", {{"light_sampling", "bsdf"}, {"use_guiding", 1}}},
        {"mis, guided 0.2", {{"light_sampling", "mis"}, {"use_guiding", 1}, {"guiding_bsdf_fraction", 0.2}}},
    };
    for (const Case& c : cases) {
        // 16 seeds: the image is far from uniform (lit in a strip next to the panel), so the
        // pixels' spread would overstate the standard error.
        const Measurement m = measure_irradiance(scene, "path", c.settings, 16);
        ASSERT_TRUE(m.error.empty()) << c.label << ": " << m.error;
        EXPECT_NEAR(m.mean, expected, 4.0 * m.standard_error)
            << c.label << ": E " << m.mean << " expected " << expected << " se " << m.standard_error;
        EXPECT_GT(m.standard_error, 0.0) << c.label;
        std::printf("%-17s E %.5f (closed form %.5f), standard error %.2e\n", c.label, m.mean, expected,
                    m.standard_error);
    }
    stratum_scene_destroy(scene);
}
