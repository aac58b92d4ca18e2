#include "bsdf/bsdf.h"

#include <array>
#include <utility>

#include "bsdf/emission.h"
#include "bsdf/glass.h"
#include "bsdf/glossy.h"
#include "bsdf/holdout.h"
#include "bsdf/lambert.h"
#include "bsdf/principled_v1.h"
#include "bsdf/principled_v2.h"
#include "bsdf/transparent.h"

namespace stratum {

namespace {

// The closure models of the C ABI, one line each.
constexpr std::pair<MaterialModel, const ClosureModel*> kClosureModels[] = {
    // Lambert, albedo = base_color.
    {MaterialModel::Diffuse, &kLambertClosure},
    // Cycles 3.x Principled: Burley diffuse + GGX, cspec0.
    {MaterialModel::PrincipledV1, &kPrincipledV1Closure},
    // Cycles 4.x Principled: Lambert under a dielectric GGX layer (energy conserving) + F82 metal.
    {MaterialModel::PrincipledV2, &kPrincipledV2Closure},
    // No scattering (the emitted radiance lives in `emission`).
    {MaterialModel::Emission, &kEmissionClosure},
    // GGX reflection, Fresnel 1, tinted by base_color.
    {MaterialModel::Glossy, &kGlossyClosure},
    // GGX dielectric reflection + refraction at `ior`.
    {MaterialModel::Glass, &kGlassClosure},
    // Delta pass-through wi = −wo, tinted by base_color.
    {MaterialModel::Transparent, &kTransparentClosure},
    // No scattering; the integrator turns its weight into alpha.
    {MaterialModel::Holdout, &kHoldoutClosure},
};

using ClosureModelTable = std::array<const ClosureModel*, kMaxClosureModels>;

// Indexed by model; filled at compile time (constinit: no static-initialisation order to mind).
constinit ClosureModelTable g_closure_models = [] {
    ClosureModelTable table{};
    for (const auto& [model, entry] : kClosureModels) table[static_cast<uint32_t>(model)] = entry;
    return table;
}();

// What a value without a model answers: no scattering.
constexpr ClosureModel kUnregistered{
    .eval = &no_scattering_eval,
    .sample = &no_scattering_sample,
    .is_delta = &answer_false,
    .has_transmission = &answer_false,
    .sample_weight = &no_sample_weight,
    .albedo_estimate = &no_albedo,
};

}  // namespace

const ClosureModel* find_closure_model(MaterialModel model) {
    const auto index = static_cast<uint32_t>(model);
    return index < kMaxClosureModels ? g_closure_models[index] : nullptr;
}

const ClosureModel& closure_model(MaterialModel model) {
    const ClosureModel* entry = find_closure_model(model);
    return entry ? *entry : kUnregistered;
}

bool register_closure_model(MaterialModel model, const ClosureModel& entry) {
    const auto index = static_cast<uint32_t>(model);
    if (index >= kMaxClosureModels || g_closure_models[index]) return false;
    g_closure_models[index] = &entry;
    return true;
}

bool bsdf_is_delta(const Material& m) { return closure_model(m.model).is_delta(m); }

bool bsdf_has_transmission(const Material& m) { return closure_model(m.model).has_transmission(m); }

BsdfEval bsdf_eval(const Material& m, Vec3 wo, Vec3 wi, HemisphereDistribution hemisphere) {
    return closure_model(m.model).eval(m, wo, wi, hemisphere);
}

bool bsdf_sample(const Material& m, Vec3 wo, float u_lobe, Vec2 u, BsdfSample* out,
                 HemisphereDistribution hemisphere) {
    return closure_model(m.model).sample(m, wo, u_lobe, u, out, hemisphere);
}

}  // namespace stratum
