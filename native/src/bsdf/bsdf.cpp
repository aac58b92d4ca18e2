#include "bsdf/bsdf.h"

#include "bsdf/lambert.h"
#include "bsdf/principled_v1.h"
#include "bsdf/principled_v2.h"

namespace stratum {

BsdfEval bsdf_eval(const Material& m, Vec3 wo, Vec3 wi, HemisphereDistribution hemisphere) {
    switch (m.model) {
        case MaterialModel::Diffuse:
            return lambert_eval(m, wo, wi, hemisphere);
        case MaterialModel::PrincipledV1:
            return principled_v1_eval(m, wo, wi, hemisphere);
        case MaterialModel::PrincipledV2:
            return principled_v2_eval(m, wo, wi, hemisphere);
        case MaterialModel::Emission:
            break;  // emitters do not scatter
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
        case MaterialModel::Emission:
            break;
    }
    return false;
}

}  // namespace stratum
