// `light`: light tracing (textbook ch. 6; Veach 1997 §5.3 for shading normals): particles leave
// the lights, scatter by the closures and connect to the camera at every surface vertex; the
// camera sees what particles cannot bring into a pinhole (paths of length 1) by a camera-ray part.
//
// | parameter               | meaning                                                         |
// |-------------------------|-----------------------------------------------------------------|
// | max_bounces             | as the path tracer: at most max_bounces + 1 scattering vertices |
// |                         | per path; a camera connection is its vertex's scattering        |
// | diffuse_bounces, glossy_ | the camera path's limits per kind (light_path_limits.h), read   |
// | bounces, transmission_  | along it: the connection's and the particle's scatterings after |
// | bounces                 | its first hit count                                             |
// | clamp_direct            | what the camera sees directly; clamp_indirect is not applied    |
// |                         | (a notice says so): a splat is no camera sample                 |
// | transparent_max_bounces | Transparent pass-throughs per particle (not bounces), and per   |
// |                         | connection ray                                                  |
// | film_transparent        | camera-ray part: background seen directly gives alpha 0         |
// | light_selection         | the distribution particles choose their light by (LightSet);    |
// |                         | `tree` emits by power (a particle has no shading point)         |
// | rr_mode, rr_min_depth   | roulette from scattering vertex rr_min_depth on: throughput     |
// |                         | (survival min(1, max T), T = particle flux / emitted flux) or    |
// |                         | albedo (min(1, max f cos/p) of the sampled scattering: ρ for    |
// |                         | cosine-sampled Lambert, eq. 5.5)                                |
// | hemisphere              | the distribution diffuse lobes scatter particles by             |
//
// Estimator (6.2 with camera NEE 6.8–6.9): a particle chosen as in LightSet::sample_emission
// carries β₀ = L_e c/(p_j p_A p_ω) / (W H) (W×H particles per sample index). At surface vertex x
// (arrival direction ω_l toward the light, connection direction ω_c toward lens point z), the
// pixels p around film point s(x) receive
//     β · f(ω_l, ω_c) |ω_l·n_s| |ω_c·n_g| / |ω_l·n_g| · V(x, z) · h(s − p) / (r² A_pix cos³θ)
// (scene/camera.h CameraConnection; h = PixelFilter::pdf). |ω_l·n_s|/|ω_l·n_g| together with
// |ω_c·n_g| in place of |ω_c·n_s| is the adjoint BSDF's shading-normal correction (Veach 1997
// eq. 5.19): particles carry importance-weighted flux, for which shading normals are not
// symmetric. Scattering multiplies β by f cos/p · |ω_l·n_s| |ω_o·n_g| / (|ω_l·n_g| |ω_o·n_s|).
// f(ω_l, ω_c) is read as the closures' eval(wo = ω_l, wi = ω_c): the reflection closures are
// reciprocal, so it equals f(ω_c, ω_l), what a camera path evaluates.
//
// Camera-ray part (radiance()): what the path tracer's first vertex sees, exactly: lamps
// visible to the camera, the emission of the first surface, background or film alpha,
// holdouts, straight on through Transparent closures (times their summed weight, the
// expectation of sampling them).
//
// Visibility: the connection ray stands for a camera ray: it is tested with the CAMERA bit
// (through Transparent closures, as transparent shadows), and vertices on instances hidden from
// the camera or on holdout objects do not connect (a camera ray meeting a holdout object ends
// black). Particles fly with the bits of the kind they were scattered as (DIFFUSE / GLOSSY /
// TRANSMISSION); the first flight, from the light, sees every non-camera kind. A light's
// DIFFUSE / GLOSSY / TRANSMISSION bits select the closures it lights at the first vertex (its
// connection, and the kind of its scattering), as NEE's lit kinds do. Not honoured: a light's
// SHADOW bit off (occluders are in the particle's way whatever it says) and the CAMERA bit of
// the particle part (lamps are not surfaces particles meet).
//
// Limitations, stated by notices(): orthographic and equirectangular cameras have no
// connection (only the camera-ray part renders). Refraction: the closures return radiance
// BSDFs, and the importance a particle carries through a refraction differs by η², which the
// closures do not expose, so scenes with transmissive closures differ behind refracting
// surfaces. Point and spot lamps with a radius: see PointLight::sample_emission. Moving
// emissive meshes are no lights (RenderScene), so they emit no particles.
#pragma once

#include <vector>

#include "integrators/integrator.h"
#include "lights/emission_sample.h"

namespace stratum {

class LightTracer final : public Integrator {
public:
    explicit LightTracer(const IntegratorSettings& settings) : settings_(settings) {}
    // The camera-ray part.
    RadianceSample estimate(const RenderScene& scene, const Sampler& sampler, const PixelSample& pixel,
                            const CameraRay& ray, PassValues& passes, uint64_t& rays) const override;
    std::vector<std::string> notices(const Scene& scene) const override;
    // Chooses how often particles leave the sky (sky_probability) for this scene.
    void prepare(const RenderScene& scene, const std::atomic<bool>&) override {
        sky_probability_ = sky_probability(scene);
    }
    // W x H particles per sample index: one per pixel of the full frame.
    uint64_t light_paths_per_sample(uint32_t frame_width, uint32_t frame_height) const override {
        return static_cast<uint64_t>(frame_width) * frame_height;
    }
    // Traces particle (x, y, i) = `particle` and appends its splats through the camera.
    void trace_light_path(const RenderScene& scene, const Sampler& sampler, const Camera& camera,
                          const Film& film, const PixelSample& particle, std::vector<Splat>& splats,
                          uint64_t& rays) const override;
    // A constant background (no environment image) emits particles too, as a uniform sky, chosen
    // by power against the lights (π R² L̄ for the sky, LightSet::power for each light).
    static float sky_probability(const RenderScene& scene);

private:
    IntegratorSettings settings_;
    float sky_probability_ = 0.0f;  // set by prepare()
};

}  // namespace stratum
