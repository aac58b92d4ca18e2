#include "bsdf/bsdf.h"

#include "bsdf/glass.h"
#include "bsdf/glossy.h"
#include "bsdf/lambert.h"
#include "bsdf/principled_v1.h"
#include "bsdf/principled_v2.h"

namespace stratum {

bool bsdf_is_delta(const Material& m) {
    switch (m.model) {
        case MaterialModel::Glossy:
        case MaterialModel::Glass:
            return ggx_is_sharp(m.roughness);
        case MaterialModel::Transparent:
            return true;
        default:
            return false;
    }
}

bool bsdf_has_transmission(const Material& m) {
    switch (m.model) {
        case MaterialModel::Glass:
        case MaterialModel::Transparent:
            return true;
        case MaterialModel::PrincipledV1:
        case MaterialModel::PrincipledV2:
            return m.transmission > 0.0f;
        default:
            return false;
    }
}

BsdfEval bsdf_eval(const Material& m, Vec3 wo, Vec3 wi, HemisphereDistribution hemisphere) {
    switch (m.model) {
        case MaterialModel::Diffuse:
            return lambert_eval(m, wo, wi, hemisphere);
        case MaterialModel::PrincipledV1:
            return principled_v1_eval(m, wo, wi, hemisphere);
        case MaterialModel::PrincipledV2:
            return principled_v2_eval(m, wo, wi, hemisphere);
        case MaterialModel::Glossy:
            return glossy_eval(m, wo, wi);
        case MaterialModel::Glass:
            return glass_eval(m, wo, wi);
        case MaterialModel::Emission:     // emitters do not scatter
        case MaterialModel::Transparent:  // a Dirac: no value for any given pair of directions
        case MaterialModel::Holdout:      // no scattering (the integrator turns it into alpha)
            break;
    }
    return {Rgb(), 0.0f};
}

bool bsdf_sample(const Material& m, Vec3 wo, float u_lobe, Vec2 u, BsdfSample* out,
                 HemisphereDistribution hemisphere) {
    switch (m.model) {
        case MaterialModel::Diffuse:
            return lambert_sample(m, wo, u, out, hemisphere);
        case MaterialModel::PrincipledV1:
            return principled_v1_sample(m, wo, u_lobe, u, out, hemisphere);
        case MaterialModel::PrincipledV2:
            return principled_v2_sample(m, wo, u_lobe, u, out, hemisphere);
        case MaterialModel::Glossy:
            return glossy_sample(m, wo, u, out);
        case MaterialModel::Glass:
            return glass_sample(m, wo, u_lobe, u, out);
        case MaterialModel::Transparent:
            // Straight through, unrefracted (Cycles bsdf_transparent): weight = tint.
            *out = {-wo, m.base_color, 1.0f, true, ScatterKind::Transparent};
            return true;
        case MaterialModel::Emission:
        case MaterialModel::Holdout:
            break;
    }
    return false;
}

}  // namespace stratum
