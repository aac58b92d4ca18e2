// Light samples per second (next-event estimation's Light::sample) and the spherical triangle
// alone (sampling/spherical_triangle.h: its setup from a shading point plus one sample, or plus
// one inversion, which is the MIS pdf's work). The emissive triangle is half of the Cornell box's
// 0.5 × 0.5 ceiling lamp at z = 1.98, seen by shading points either near it (up to 0.3 below,
// as on the upper walls) or far (the floor, 1.7 – 2 below), sampled by area and by solid angle
// (triangle_sampling). The lamps (point, spot, rectangular area lamp) hang at the same place.
#include <benchmark/benchmark.h>

#include "bench_inputs.h"
#include "lights/emissive_triangle.h"
#include "lights/light_registry.h"
#include "sampling/spherical_triangle.h"
#include "stratum/stratum.h"

namespace stratum::bench {
namespace {

const Vec3 kV0(-0.25f, -0.25f, 1.98f), kV1(0.25f, -0.25f, 1.98f), kV2(0.25f, 0.25f, 1.98f);
const Vec3 kUp(0.0f, 0.0f, 1.0f);

// Shading points with x, y in [−1, 1] and z in [z0, z1], at fixed pseudo-random places.
std::vector<Vec3> points(float z0, float z1, uint64_t seed) {
    std::vector<Vec3> out(kInputs);
    const std::vector<Vec2> xy = uniform_pairs(seed), z = uniform_pairs(seed + 1);
    for (size_t i = 0; i < kInputs; ++i)
        out[i] = {2.0f * xy[i].x - 1.0f, 2.0f * xy[i].y - 1.0f, z0 + (z1 - z0) * z[i].x};
    return out;
}
std::vector<Vec3> near_points() { return points(1.68f, 1.93f, 11); }
std::vector<Vec3> far_points() { return points(0.0f, 0.3f, 13); }

// Samples of `light` from the shading points, normal up; items: samples taken.
void light_samples(benchmark::State& state, const Light& light, const std::vector<Vec3>& p,
                   TriangleSampling mode) {
    const std::vector<Vec2> u = uniform_pairs(17);
    size_t i = 0;
    float sum = 0.0f;
    for (auto _ : state) {
        LightSample ls;
        if (light.sample(p[i], kUp, u[i], mode, &ls)) sum += ls.pdf + ls.wi.z;
        i = (i + 1) & (kInputs - 1);
    }
    benchmark::DoNotOptimize(sum);
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}

void emissive_triangle(benchmark::State& state, bool near, TriangleSampling mode) {
    const EmissiveTriangle tri(kV0, kV1, kV2, Rgb(15.0f));
    light_samples(state, tri, near ? near_points() : far_points(), mode);
}
BENCHMARK_CAPTURE(emissive_triangle, near_area, true, TriangleSampling::Area);
BENCHMARK_CAPTURE(emissive_triangle, near_solid_angle, true, TriangleSampling::SolidAngle);
BENCHMARK_CAPTURE(emissive_triangle, far_area, false, TriangleSampling::Area);
BENCHMARK_CAPTURE(emissive_triangle, far_solid_angle, false, TriangleSampling::SolidAngle);

// The MIS pdf of a BSDF ray that hit the triangle at the point a sample chose (what the path
// integrator asks at every emissive hit).
void emissive_triangle_pdf(benchmark::State& state, bool near, TriangleSampling mode) {
    const EmissiveTriangle tri(kV0, kV1, kV2, Rgb(15.0f));
    const std::vector<Vec3> p = near ? near_points() : far_points();
    const std::vector<Vec2> u = uniform_pairs(19);
    std::vector<Vec3> hits(kInputs);
    for (size_t i = 0; i < kInputs; ++i) {
        const Vec3 b(1.0f - std::sqrt(u[i].x), std::sqrt(u[i].x) * (1.0f - u[i].y),
                     std::sqrt(u[i].x) * u[i].y);
        hits[i] = kV0 * b.x + kV1 * b.y + kV2 * b.z;
    }
    size_t i = 0;
    float sum = 0.0f;
    for (auto _ : state) {
        sum += tri.pdf(p[i], kUp, hits[i], mode);
        i = (i + 1) & (kInputs - 1);
    }
    benchmark::DoNotOptimize(sum);
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}
BENCHMARK_CAPTURE(emissive_triangle_pdf, near_area, true, TriangleSampling::Area);
BENCHMARK_CAPTURE(emissive_triangle_pdf, near_solid_angle, true, TriangleSampling::SolidAngle);
BENCHMARK_CAPTURE(emissive_triangle_pdf, far_area, false, TriangleSampling::Area);
BENCHMARK_CAPTURE(emissive_triangle_pdf, far_solid_angle, false, TriangleSampling::SolidAngle);

LightParams lamp(StratumLightType type) {
    LightParams params;
    params.type = type;
    params.strength = 100.0f;
    params.radius = 0.1f;
    params.size_x = params.size_y = 0.5f;
    params.spot_size = 1.2f;
    params.spot_blend = 0.2f;
    params.light_to_world.m = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1.9f};
    return params;
}

void lamp_samples(benchmark::State& state, StratumLightType type) {
    const std::unique_ptr<Light> light = make_light(lamp(type));
    light_samples(state, *light, far_points(), TriangleSampling::SolidAngle);
}
BENCHMARK_CAPTURE(lamp_samples, point, STRATUM_LIGHT_POINT);
BENCHMARK_CAPTURE(lamp_samples, spot, STRATUM_LIGHT_SPOT);
BENCHMARK_CAPTURE(lamp_samples, area_rectangle, STRATUM_LIGHT_AREA_RECTANGLE);

// The spherical triangle alone: setup from the shading point, then one sample or one inversion.
void spherical_triangle_sample(benchmark::State& state, bool near) {
    const std::vector<Vec3> p = near ? near_points() : far_points();
    const std::vector<Vec2> u = uniform_pairs(23);
    size_t i = 0;
    float sum = 0.0f;
    for (auto _ : state) {
        const SphericalTriangle spherical(p[i], kV0, kV1, kV2);
        sum += spherical.sample(u[i]).z;
        i = (i + 1) & (kInputs - 1);
    }
    benchmark::DoNotOptimize(sum);
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}
BENCHMARK_CAPTURE(spherical_triangle_sample, near, true);
BENCHMARK_CAPTURE(spherical_triangle_sample, far, false);

void spherical_triangle_pdf(benchmark::State& state, bool near) {
    const std::vector<Vec3> p = near ? near_points() : far_points();
    const std::vector<Vec2> u = uniform_pairs(29);
    std::vector<Vec3> w(kInputs);
    for (size_t i = 0; i < kInputs; ++i) w[i] = SphericalTriangle(p[i], kV0, kV1, kV2).sample(u[i]);
    size_t i = 0;
    float sum = 0.0f;
    for (auto _ : state) {
        const SphericalTriangle spherical(p[i], kV0, kV1, kV2);
        sum += spherical.invert(w[i]).x + static_cast<float>(spherical.solid_angle());
        i = (i + 1) & (kInputs - 1);
    }
    benchmark::DoNotOptimize(sum);
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}
BENCHMARK_CAPTURE(spherical_triangle_pdf, near, true);
BENCHMARK_CAPTURE(spherical_triangle_pdf, far, false);

}  // namespace
}  // namespace stratum::bench
