// The data passes (film/passes.h, integrators/camera_path_passes.h) against closed forms: a
// plane at a known distance and tilt with a known albedo, seen by a pinhole camera at the
// origin looking down −Z (90° horizontal field of view), the right half of the frame open to a
// constant background; and the film's derived passes (sample count, standard error).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "film/film.h"
#include "render_helpers.h"

using namespace stratum;
using namespace stratum_test;

namespace {

constexpr int kSize = 16;
constexpr float kDistance = 3.0f;             // the plane passes through (0, 0, −kDistance)
constexpr float kTilt = 0.5235987755982988f;  // 30°: its normal (sin a, 0, cos a) turns toward +x
constexpr float kAlbedo[3] = {0.2f, 0.5f, 0.8f};
constexpr float kBackground[3] = {0.3f, 0.6f, 0.9f};
constexpr float kEmission[3] = {0.05f, 0.1f, 0.15f};
const char* const kAllPasses =
    "Normal,Depth,Position,Denoising Albedo,Denoising Normal,Debug Sample Count,Stratum "
    "Error,UV,Emit,Env,Mist";
// The Mist pass rises linearly from the camera to kMistDepth: m(d) = d / kMistDepth.
constexpr float kMistDepth = 10.0f;
// The plane's texture coordinates: u = (x + 20) / 20, v = (y + 20) / 40 in its own coordinates.
float plane_u(float x) { return (x + 20.0f) / 20.0f; }
float plane_v(float y) { return (y + 20.0f) / 40.0f; }

// The plane's quad: from p0 = (0, 0, −D) along t1 = (cos a, 0, −sin a) over [−20, 0] and along
// +y over [−20, 20]. Its edge runs through p0, which the image centre (u = 0) sees, so pixels
// x < 8 see the plane and x >= 8 the background. It emits kEmission.
StratumScene* make_plane_scene(int32_t model) {
    StratumScene* scene = nullptr;
    if (stratum_scene_create(&scene) != STRATUM_OK) return nullptr;
    const float c = std::cos(kTilt), s = std::sin(kTilt);
    const float x0 = -20.0f, x1 = 0.0f, y0 = -20.0f, y1 = 20.0f;
    const float positions[] = {x0 * c, y0, -kDistance - x0 * s, x1 * c, y0, -kDistance - x1 * s,
                               x1 * c, y1, -kDistance - x1 * s, x0 * c, y1, -kDistance - x0 * s};
    // Counter-clockwise seen from the camera (front face toward it).
    const uint32_t triangles[] = {0, 1, 2, 0, 2, 3};
    const uint32_t mats[] = {0, 0};
    float uvs[12];
    for (int corner = 0; corner < 6; ++corner) {
        const uint32_t v = triangles[corner];
        const bool right = v == 1 || v == 2, top = v == 2 || v == 3;
        uvs[2 * corner] = plane_u(right ? x1 : x0);
        uvs[2 * corner + 1] = plane_v(top ? y1 : y0);
    }
    const StratumMeshDesc mesh{positions, 4, triangles, 2, nullptr, uvs, mats};
    const StratumMaterialDesc material{model,
                                       {kAlbedo[0], kAlbedo[1], kAlbedo[2]},
                                       0.5f,
                                       0,
                                       0.5f,
                                       1.5f,
                                       {kEmission[0], kEmission[1], kEmission[2]},
                                       STRATUM_MICROFACET_GGX};
    const StratumCameraDesc camera = camera_at(0, 0, 0);
    uint32_t mat = 0, mesh_id = 0;
    if (stratum_scene_add_material(scene, &material, &mat) != STRATUM_OK ||
        stratum_scene_add_mesh(scene, &mesh, &mesh_id) != STRATUM_OK ||
        stratum_scene_add_instance(scene, mesh_id, kIdentity) != STRATUM_OK ||
        stratum_scene_set_camera(scene, &camera) != STRATUM_OK ||
        stratum_scene_set_background(scene, kBackground) != STRATUM_OK) {
        stratum_scene_destroy(scene);
        return nullptr;
    }
    return scene;
}

struct Passes {
    std::vector<float> rgba, normal, depth, position, albedo, denoising_normal, count, error, uv, emit, env,
        mist;
};

// Renders 16 x 16 at 8 samples with a box filter of width 1 (every sample inside its pixel).
Passes render_passes(StratumScene* scene, const char* passes, const char* integrator = "path",
                     const char* sampler = "random", double clamp_direct = 0.0) {
    Passes out;
    StratumRenderer* r = nullptr;
    EXPECT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
    EXPECT_EQ(apply_settings(r, {{"width", kSize},
                                 {"height", kSize},
                                 {"samples", 8},
                                 {"filter_type", "box"},
                                 {"filter_width", 1.0},
                                 {"integrator", integrator},
                                 {"sampler", sampler},
                                 {"mist_start", 0.0},
                                 {"mist_depth", kMistDepth},
                                 {"mist_falloff", 1.0},
                                 {"clamp_direct", clamp_direct},
                                 {"passes", passes}}),
              "");
    EXPECT_TRUE(render_to_end(r)) << stratum_last_error();
    out.rgba.resize(kSize * kSize * 4);
    EXPECT_EQ(stratum_renderer_read_pixels(r, out.rgba.data(), out.rgba.size()), STRATUM_OK);
    const auto read = [&](const char* name, size_t channels, std::vector<float>* v) {
        if (std::string(passes).find(name) == std::string::npos) return;
        v->resize(kSize * kSize * channels);
        EXPECT_EQ(stratum_renderer_read_pass(r, name, v->data(), v->size()), STRATUM_OK)
            << stratum_last_error();
    };
    read("Normal", 3, &out.normal);
    read("Depth", 1, &out.depth);
    read("Position", 3, &out.position);
    read("Denoising Albedo", 3, &out.albedo);
    read("Denoising Normal", 3, &out.denoising_normal);
    read("Debug Sample Count", 1, &out.count);
    read("Stratum Error", 3, &out.error);
    read("UV", 3, &out.uv);
    read("Emit", 3, &out.emit);
    read("Env", 3, &out.env);
    read("Mist", 1, &out.mist);
    stratum_renderer_destroy(r);
    return out;
}

// Depth of the plane along the view axis at film coordinate u (the view plane at unit depth):
// the ray s (u, v, −1) meets n · x = −D cos a where s = D cos a / (cos a − u sin a).
float plane_depth(float u) { return kDistance * std::cos(kTilt) / (std::cos(kTilt) - u * std::sin(kTilt)); }

}  // namespace

TEST(RenderPasses, DepthPositionNormalAndAlbedoOfATiltedPlaneFollowTheirClosedForms) {
    StratumScene* scene = make_plane_scene(STRATUM_MATERIAL_DIFFUSE);
    ASSERT_NE(scene, nullptr) << stratum_last_error();
    const Passes p = render_passes(scene, kAllPasses);
    const Vec3 n(std::sin(kTilt), 0.0f, std::cos(kTilt));
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            const size_t i = static_cast<size_t>(y * kSize + x);
            const float* normal = &p.normal[3 * i];
            const float* position = &p.position[3 * i];
            const float* albedo = &p.albedo[3 * i];
            const float* dn = &p.denoising_normal[3 * i];
            const float depth = p.depth[i];
            EXPECT_EQ(p.count[i], 8.0f);
            if (x < kSize / 2) {
                // Pixel x spans u in [−1 + x/8, −1 + (x+1)/8]; sample 0 lies somewhere in it.
                const float u0 = -1.0f + static_cast<float>(x) / 8.0f, u1 = u0 + 0.125f;
                EXPECT_GE(depth, plane_depth(u0) * (1 - 1e-5f)) << x << ", " << y;
                EXPECT_LE(depth, plane_depth(u1) * (1 + 1e-5f)) << x << ", " << y;
                // Position is the same sample's hit: its depth is −z, it lies on the plane and
                // projects into the pixel.
                EXPECT_NEAR(-position[2], depth, 1e-5f * depth);
                EXPECT_NEAR(position[0] * n.x + position[2] * n.z, -kDistance * n.z, 1e-5f);
                EXPECT_GE(position[0] / depth, u0 - 1e-5f);
                EXPECT_LE(position[0] / depth, u1 + 1e-5f);
                // Every sample sees the same flat face: the means are the exact values.
                EXPECT_NEAR(normal[0], n.x, 1e-6f);
                EXPECT_NEAR(normal[1], 0.0f, 1e-6f);
                EXPECT_NEAR(normal[2], n.z, 1e-6f);
                // Cycles' camera space: x right, y up, z forward (−z of Blender's camera).
                EXPECT_NEAR(dn[0], n.x, 1e-6f);
                EXPECT_NEAR(dn[1], 0.0f, 1e-6f);
                EXPECT_NEAR(dn[2], -n.z, 1e-6f);
                // The albedo, plus the emission seen on the way (as Cycles adds it).
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(albedo[c], kAlbedo[c] + kEmission[c], 1e-6f);
                // Emission seen directly; no background.
                for (int c = 0; c < 3; ++c) {
                    EXPECT_NEAR(p.emit[3 * i + c], kEmission[c], 1e-6f);
                    EXPECT_EQ(p.env[3 * i + c], 0.0f);
                }
                // UV: the mean of the samples' (u, v) lies within the pixel footprint's range. On
                // the plane x = s(u)(u cos a + sin a) − D sin a along t1 (s the depth) and y =
                // s(u) v_film: monotonic in u, and in each of u, v on the pixel's rectangle.
                const auto plane_x = [](float u) {
                    return plane_depth(u) * (u * std::cos(kTilt) + std::sin(kTilt)) -
                           kDistance * std::sin(kTilt);
                };
                const float v0 = -1.0f + static_cast<float>(y) / 8.0f, v1 = v0 + 0.125f;
                float y_lo = 1e30f, y_hi = -1e30f;
                for (const float u : {u0, u1}) {
                    for (const float v : {v0, v1}) {
                        y_lo = std::min(y_lo, plane_depth(u) * v);
                        y_hi = std::max(y_hi, plane_depth(u) * v);
                    }
                }
                const float* uv = &p.uv[3 * i];
                EXPECT_GE(uv[0], plane_u(plane_x(u0)) - 1e-5f) << x << ", " << y;
                EXPECT_LE(uv[0], plane_u(plane_x(u1)) + 1e-5f) << x << ", " << y;
                EXPECT_GE(uv[1], plane_v(y_lo) - 1e-5f) << x << ", " << y;
                EXPECT_LE(uv[1], plane_v(y_hi) + 1e-5f) << x << ", " << y;
                EXPECT_EQ(uv[2], 0.0f);
                // Mist: the mean of d / kMistDepth over the samples, d = s(u) |(u, v, −1)| the
                // distance of the point seen: within its range over the pixel (a 9 x 9 grid of
                // it, widened by the largest step between grid points).
                float d_lo = 1e30f, d_hi = 0.0f;
                for (int a = 0; a <= 8; ++a) {
                    for (int b = 0; b <= 8; ++b) {
                        const float u = u0 + 0.125f * static_cast<float>(a) / 8.0f;
                        const float v = v0 + 0.125f * static_cast<float>(b) / 8.0f;
                        const float d = plane_depth(u) * std::sqrt(u * u + v * v + 1.0f);
                        d_lo = std::min(d_lo, d);
                        d_hi = std::max(d_hi, d);
                    }
                }
                const float step = (d_hi - d_lo) / 8.0f;
                EXPECT_GE(p.mist[i], (d_lo - step) / kMistDepth - 1e-5f) << x << ", " << y;
                EXPECT_LE(p.mist[i], (d_hi + step) / kMistDepth + 1e-5f) << x << ", " << y;
            } else {
                EXPECT_EQ(depth, kBackgroundDepth) << x << ", " << y;
                EXPECT_EQ(p.mist[i], 1.0f);
                for (int c = 0; c < 3; ++c) {
                    EXPECT_EQ(position[c], 0.0f);
                    EXPECT_EQ(normal[c], 0.0f);
                    EXPECT_EQ(dn[c], 0.0f);
                    // The background seen directly is its albedo (Cycles adds it there too), and
                    // it is constant: its samples do not spread.
                    EXPECT_NEAR(albedo[c], kBackground[c], 1e-6f);
                    EXPECT_EQ(p.error[3 * i + c], 0.0f);
                    EXPECT_EQ(p.uv[3 * i + c], 0.0f);
                    EXPECT_EQ(p.emit[3 * i + c], 0.0f);
                    EXPECT_NEAR(p.env[3 * i + c], kBackground[c], 1e-6f);
                    // Combined there is the background, all of it in Env.
                    EXPECT_NEAR(p.rgba[4 * i + c], p.env[3 * i + c], 1e-6f);
                }
            }
        }
    }
    stratum_scene_destroy(scene);
}

TEST(RenderPasses, PassesLeaveTheImageBitIdenticalAndAgreeAcrossIntegrators) {
    StratumScene* scene = make_plane_scene(STRATUM_MATERIAL_DIFFUSE);
    ASSERT_NE(scene, nullptr) << stratum_last_error();
    const Passes with = render_passes(scene, kAllPasses);
    EXPECT_EQ(with.rgba, render_passes(scene, "").rgba);
    // The same camera rays meet the same first surfaces whichever integrator shades them.
    for (const char* integrator : {"light", "ao", "direct"}) {
        const Passes other = render_passes(scene, "Normal,Depth,Position,Denoising Normal,UV", integrator);
        EXPECT_EQ(other.depth, with.depth) << integrator;
        EXPECT_EQ(other.position, with.position) << integrator;
        EXPECT_EQ(other.normal, with.normal) << integrator;
        EXPECT_EQ(other.denoising_normal, with.denoising_normal) << integrator;
        EXPECT_EQ(other.uv, with.uv) << integrator;
    }
    stratum_scene_destroy(scene);
}

// Cycles writes every light pass after its clamp (film_clamp_light before the pass writes), so
// Emit and Env hold the clamped emission and background, as Combined does: with clamp_direct c
// each is scaled to a channel sum of 3c. The plane's emission sums to 0.3 and the background to
// 1.8; c = 0.05 halves the one and takes 1/12 of the other. Radiosity does not clamp: its Emit
// is the emission itself, once.
TEST(RenderPasses, EmitAndEnvHoldTheClampedValuesCombinedTakes) {
    StratumScene* scene = make_plane_scene(STRATUM_MATERIAL_DIFFUSE);
    ASSERT_NE(scene, nullptr) << stratum_last_error();
    constexpr double kClamp = 0.05;
    const float emission_scale =
        3.0f * static_cast<float>(kClamp) / (kEmission[0] + kEmission[1] + kEmission[2]);
    const float background_scale =
        3.0f * static_cast<float>(kClamp) / (kBackground[0] + kBackground[1] + kBackground[2]);
    for (const char* integrator : {"path", "light", "radiosity"}) {
        const bool clamps = std::string(integrator) != "radiosity";
        const Passes p = render_passes(scene, "Emit,Env", integrator, "random", clamps ? kClamp : 0.0);
        for (int y = 0; y < kSize; ++y) {
            for (int x = 0; x < kSize; ++x) {
                const size_t i = static_cast<size_t>(y * kSize + x);
                for (int c = 0; c < 3; ++c) {
                    const bool plane = x < kSize / 2;
                    const float emit = plane ? kEmission[c] * (clamps ? emission_scale : 1.0f) : 0.0f;
                    const float env = plane ? 0.0f : kBackground[c] * (clamps ? background_scale : 1.0f);
                    EXPECT_NEAR(p.emit[3 * i + c], emit, 1e-6f) << integrator << " " << x << ", " << y;
                    EXPECT_NEAR(p.env[3 * i + c], env, 1e-6f) << integrator << " " << x << ", " << y;
                    if (!plane && clamps) {
                        EXPECT_NEAR(p.rgba[4 * i + c], env, 1e-6f) << integrator;
                    }
                }
            }
        }
    }
    stratum_scene_destroy(scene);
}

TEST(RenderPasses, AMirrorPassesTheDenoisingFeaturesOnToWhatItReflects) {
    // A perfect mirror (Glossy, roughness 0) of colour kAlbedo: its camera rays reflect off the
    // plane into the constant background, so Denoising Albedo = kAlbedo × background, and no
    // surface gives Denoising Normal one.
    StratumScene* scene = make_plane_scene(STRATUM_MATERIAL_GLOSSY);
    ASSERT_NE(scene, nullptr) << stratum_last_error();
    StratumMaterialDesc mirror{
        STRATUM_MATERIAL_GLOSSY, {kAlbedo[0], kAlbedo[1], kAlbedo[2]}, 0.0f, 0, 0.5f, 1.5f, {0, 0, 0},
        STRATUM_MICROFACET_GGX};
    ASSERT_EQ(stratum_scene_set_material(scene, 0, &mirror), STRATUM_OK) << stratum_last_error();
    const Passes p = render_passes(scene, "Denoising Albedo,Denoising Normal,Normal");
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize / 2; ++x) {
            const size_t i = static_cast<size_t>(y * kSize + x);
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(p.albedo[3 * i + c], kAlbedo[c] * kBackground[c], 1e-5f) << x << ", " << y;
                EXPECT_EQ(p.denoising_normal[3 * i + c], 0.0f);
            }
            // The Normal pass is the first surface's, mirror or not.
            EXPECT_NEAR(p.normal[3 * i + 2], std::cos(kTilt), 1e-6f);
        }
    }
    stratum_scene_destroy(scene);
}

TEST(RenderPasses, FirstSamplePassesKeepSampleZeroAndTheErrorPassIsTheMeansStandardError) {
    const Pass passes[] = {Pass::Depth, Pass::SampleCount, Pass::Error};
    Film film(PixelRegion{0, 0, 1, 1}, 1, 1, PixelFilter(FilterType::Box, 1.0f), passes, false);
    // Depth is written by the integrator, the count and the error are the film's own.
    ASSERT_EQ(film.layout().extra_channels(), 1u);
    ASSERT_EQ(film.sums_stride(), 4u + 1u + 3u);
    std::vector<FilmSum> sums(film.sums_stride(), 0);
    const float red[] = {1, 2, 3, 4};
    for (uint32_t i = 0; i < 4; ++i) {
        const float depth = 10.0f + static_cast<float>(i);
        EXPECT_FALSE(film.add_sample(sums.data(), i, Rgb(red[i], 1.0f, 0.0f), 1.0f, &depth));
    }
    film.store_sums(0, sums.data(), 4);
    film.publish(0, 1, 0, 1);
    float depth = 0, count = 0, error[3] = {};
    ASSERT_TRUE(film.read(Pass::Depth, &depth));
    ASSERT_TRUE(film.read(Pass::SampleCount, &count));
    ASSERT_TRUE(film.read(Pass::Error, error));
    EXPECT_EQ(depth, 10.0f);
    EXPECT_EQ(count, 4.0f);
    // Red 1, 2, 3, 4: mean 2.5, sample variance 5/3, standard error of the mean sqrt(5/12).
    EXPECT_NEAR(error[0], std::sqrt(5.0 / 12.0), 1e-6);
    EXPECT_EQ(error[1], 0.0f);
    EXPECT_EQ(error[2], 0.0f);
    // The memory budget counts the sums (RGBA + depth + 3 squares, 16-byte fixed point), the
    // published floats (RGBA + depth + count + 3 errors), the count, and the error estimate's
    // prefix sums (RGB at 3 levels, 16 bytes each), their counts and the estimate (gain, count).
    EXPECT_EQ(Film::bytes_per_pixel(passes, false), 8.0 * 16 + 9.0 * 4 + 4 + 9.0 * 16 + 3 * 4 + 8);
}

// Cycles' AO pass inside a closed unit sphere: from a wall point, the direction at angle θ to the
// inward normal leaves along a chord of length 2 cos θ, so it is blocked within distance d iff
// 2 cos θ ≤ d; under the cosine distribution P(cos θ > c) = 1 − c², so AO = 1 − d²/4 (0.75 for
// d = 1). Tolerance: 4 standard errors of the image mean (pixel values' spread over 256 pixels of
// 64 Bernoulli samples each: ~0.0034) plus 0.005 for the 64-ring tessellation (facets within
// cos(π/128) of the unit radius, normals within π/64 of the radial direction: chords change by
// < 1e-3).
TEST(RenderPasses, TheAoPassInsideAClosedSphereIsOneMinusAQuarterOfTheDistanceSquared) {
    IntegratingSphere s = make_closed_sphere(0.5f, 0.0f, 64);
    ASSERT_NE(s.scene, nullptr) << stratum_last_error();
    StratumRenderer* r = nullptr;
    ASSERT_EQ(stratum_renderer_create(s.scene, &r), STRATUM_OK);
    const Settings ao_settings = {
        {"width", kSize}, {"height", kSize}, {"samples", 64}, {"ao_distance", 1.0}, {"passes", "AO"}};
    EXPECT_EQ(apply_settings(r, ao_settings), "");
    EXPECT_TRUE(render_to_end(r)) << stratum_last_error();
    std::vector<float> ao(kSize * kSize * 3);
    EXPECT_EQ(stratum_renderer_read_pass(r, "AO", ao.data(), ao.size()), STRATUM_OK);
    stratum_renderer_destroy(r);
    stratum_scene_destroy(s.scene);
    double sum = 0, sum_sq = 0;
    const double n = kSize * kSize;
    for (int p = 0; p < kSize * kSize; ++p) {
        EXPECT_EQ(ao[3 * p], ao[3 * p + 1]);  // grey: the opacity weight is 1 in every channel
        sum += ao[3 * p];
        sum_sq += static_cast<double>(ao[3 * p]) * ao[3 * p];
    }
    const double mean = sum / n;
    const double se = std::sqrt((sum_sq / n - mean * mean) / (n - 1.0));
    EXPECT_GT(se, 0.0);
    EXPECT_NEAR(mean, 0.75, 4.0 * se + 0.005) << "se " << se;
}
