#include "bsdf/bsdf.h"

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

// The closure models of the C ABI, one line each: StratumMaterialModel's value, its enumerator's
// name in lower case without STRATUM_MATERIAL_, the model. tests/python/test_models.py checks the
// lines against include/stratum/stratum.h.
constinit ClosureModels g_closure_models{
    // Lambert, albedo = base_color.
    {0, "diffuse", &kLambertClosure},
    // Cycles 3.x Principled: Burley diffuse + GGX, cspec0.
    {1, "principled_v1", &kPrincipledV1Closure},
    // Cycles 4.x Principled: Lambert under a dielectric GGX layer (energy conserving) + F82 metal.
    {2, "principled_v2", &kPrincipledV2Closure},
    // No scattering (the emitted radiance lives in `emission`).
    {3, "emission", &kEmissionClosure},
    // GGX reflection, Fresnel 1, tinted by base_color.
    {4, "glossy", &kGlossyClosure},
    // GGX dielectric reflection + refraction at `ior`.
    {5, "glass", &kGlassClosure},
    // Delta pass-through wi = −wo, tinted by base_color.
    {6, "transparent", &kTransparentClosure},
    // No scattering; the integrator turns its weight into alpha.
    {7, "holdout", &kHoldoutClosure},
};

// What a value without a model answers: no scattering.
constexpr ClosureModel kUnregistered{};

}  // namespace

const ClosureModels& closure_models() { return g_closure_models; }

const ClosureModel* find_closure_model(int32_t model) { return g_closure_models.find(model); }

const ClosureModel& closure_model(int32_t model) {
    const ClosureModel* entry = find_closure_model(model);
    return entry ? *entry : kUnregistered;
}

bool register_closure_model(int32_t model, const char* name, const ClosureModel& entry) {
    return g_closure_models.add({model, name, &entry});
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
