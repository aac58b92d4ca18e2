#include "integrators/camera_path_passes.h"

#include <algorithm>
#include <cmath>

#include "integrators/light_path_limits.h"
#include "integrators/ray_offset.h"
#include "sampling/hemisphere.h"
#include "scene/visibility.h"

namespace stratum {

namespace {

// Cycles' default view-layer pass_alpha_threshold: a surface at least this opaque takes the
// data passes; a more transparent one lets them through to what lies behind.
constexpr float kPassAlphaThreshold = 0.5f;

}  // namespace

CameraPathPasses::CameraPathPasses(PassValues& passes, const MistSettings& mist)
    : passes_(passes),
      mist_(mist),
      data_pending_(passes.wants(Pass::Depth) || passes.wants(Pass::Position) || passes.wants(Pass::Normal) ||
                    passes.wants(Pass::Uv) || passes.wants(Pass::ObjectIndex) ||
                    passes.wants(Pass::MaterialIndex)),
      features_pending_(passes.wants(Pass::DenoisingAlbedo) || passes.wants(Pass::DenoisingNormal)),
      direct_(passes.wants(Pass::Emit) || passes.wants(Pass::Env)),
      mist_wanted_(passes.wants(Pass::Mist) && passes.camera()),
      colors_wanted_(passes.wants(Pass::DiffuseColor) || passes.wants(Pass::GlossyColor) ||
                     passes.wants(Pass::TransmissionColor)) {}

void CameraPathPasses::surface(const SurfaceHit& hit, Vec3 ns, Vec3 wo_world, const ClosureSet& closures,
                               Rgb beta, bool camera_visible, float emission_clamp) {
    const bool local_wanted =
        (colors_wanted_ && camera_visible) || (features_pending_ && closures.has_non_delta());
    const Vec3 wo = local_wanted ? Frame::from_normal(ns).to_local(wo_world) : Vec3{};
    if (colors_wanted_ && camera_visible) {
        const ClosureColors c = closures.colors(wo);
        diffuse_color_ += beta * c.diffuse;
        glossy_color_ += beta * c.glossy;
        transmission_color_ += beta * c.transmission;
    }
    if (direct_ && camera_visible) emit_ += clamp_contribution(beta * closures.emission(), emission_clamp);
    if (mist_wanted_ && camera_visible) add_mist(hit.position, beta * (Rgb(1.0f) - closures.transparency()));
    if (data_pending_ && camera_visible) {
        write_first_surface(hit);
        if (1.0f - closures.transparency().average() >= kPassAlphaThreshold) {
            passes_.write(Pass::Normal, ns);
            passes_.write(Pass::Uv, Vec3(hit.uv.x, hit.uv.y, 0.0f));
            data_pending_ = false;
        }
    }
    if (!features_pending_) return;
    albedo_ += beta * closures.emission();
    if (closures.has_non_delta()) {
        write_features(ns, albedo_ + beta * closures.denoising_albedo(wo));
    } else if (!closures.scatters()) {
        write_features(Vec3{}, albedo_);
    }
}

void CameraPathPasses::plain_surface(const SurfaceHit& hit, Vec3 ns) {
    if (mist_wanted_) add_mist(hit.position, Rgb(1.0f));
    if (data_pending_) {
        write_first_surface(hit);
        passes_.write(Pass::Normal, ns);
        passes_.write(Pass::Uv, Vec3(hit.uv.x, hit.uv.y, 0.0f));
        data_pending_ = false;
    }
    if (features_pending_) write_features(ns, Rgb(1.0f));
    // The AO integrator's only surface (it calls no finish): white diffuse.
    passes_.write(Pass::DiffuseColor, Vec3(1.0f, 1.0f, 1.0f));
}

void CameraPathPasses::miss(Rgb background, bool camera_visible) {
    if (direct_ && camera_visible) env_ += background;
    if (data_pending_ && camera_visible) {
        passes_.write(Pass::Depth, kBackgroundDepth);
        passes_.write(Pass::Position, Vec3{});
        passes_.write(Pass::Normal, Vec3{});
        passes_.write(Pass::ObjectIndex, 0.0f);
        passes_.write(Pass::MaterialIndex, 0.0f);
    }
    data_pending_ = false;
    if (features_pending_) write_features(Vec3{}, albedo_ + background);
}

void CameraPathPasses::finish() {
    // A path that ended before a non-delta surface (absorbed, out of bounces): what it gathered.
    if (features_pending_) write_features(Vec3{}, albedo_);
    if (mist_wanted_) passes_.write(Pass::Mist, 1.0f - mist_sum_);
    if (passes_.wants(Pass::Ao)) passes_.write(Pass::Ao, Vec3(ao_.r, ao_.g, ao_.b));
    if (colors_wanted_) {
        passes_.write(Pass::DiffuseColor, Vec3(diffuse_color_.r, diffuse_color_.g, diffuse_color_.b));
        passes_.write(Pass::GlossyColor, Vec3(glossy_color_.r, glossy_color_.g, glossy_color_.b));
        passes_.write(Pass::TransmissionColor,
                      Vec3(transmission_color_.r, transmission_color_.g, transmission_color_.b));
    }
    if (!direct_) return;
    passes_.write(Pass::Emit, Vec3(emit_.r, emit_.g, emit_.b));
    passes_.write(Pass::Env, Vec3(env_.r, env_.g, env_.b));
}

void CameraPathPasses::ao(const RenderScene& scene, Vec3 position, Vec3 ns, Vec3 ng, Vec2 u, Rgb weight,
                          float time, float distance, uint64_t& rays) {
    const Vec3 d = Frame::from_normal(ns).to_world(sample_hemisphere(HemisphereDistribution::Cosine, u));
    // A direction below the true surface is blocked by it.
    if (!(dot(d, ng) > 0.0f)) return;
    ++rays;
    if (!scene.occluded(offset_ray_origin(position, ng), d, 0.0f, distance, {time, kVisibleShadow}))
        ao_ += weight;
}

void CameraPathPasses::add_mist(Vec3 position, Rgb weight) {
    const float inv_depth = mist_.depth > 0.0f ? 1.0f / mist_.depth : 0.0f;
    float mist = std::clamp((passes_.camera()->distance(position) - mist_.start) * inv_depth, 0.0f, 1.0f);
    if (mist_.falloff != 1.0f) mist = std::pow(mist, mist_.falloff);
    mist_sum_ += (1.0f - mist) * weight.average();
}

void CameraPathPasses::write_first_surface(const SurfaceHit& hit) {
    write_depth(hit.position);
    passes_.write(Pass::Position, hit.position);
    // Floats hold every index up to STRATUM_MAX_PASS_INDEX exactly.
    passes_.write(Pass::ObjectIndex, static_cast<float>(hit.object_pass_index));
    passes_.write(Pass::MaterialIndex, static_cast<float>(hit.material_pass_index));
}

void CameraPathPasses::write_depth(Vec3 position) {
    if (passes_.camera()) passes_.write(Pass::Depth, passes_.camera()->z_depth(position));
}

void CameraPathPasses::write_features(Vec3 ns, Rgb albedo) {
    passes_.write(Pass::DenoisingAlbedo, Vec3(albedo.r, albedo.g, albedo.b));
    passes_.write(Pass::DenoisingNormal,
                  dot(ns, ns) > 0.0f && passes_.camera() ? passes_.camera()->to_view_space(ns) : Vec3{});
    features_pending_ = false;
}

}  // namespace stratum
