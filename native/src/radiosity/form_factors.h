// Form factors by ray casting (textbook §3, eq. 3.4, and the Nusselt analogy; Cohen & Wallace
// 1993, "Radiosity and Realistic Image Synthesis", §4.9–4.10).
//
// | quantity  | definition |
// |-----------|------------|
// | G_ij      | (1/A_i) ∫_{A_i} ∫_{A_j} c_i c_j v / (π r²) dA_j dA_i (3.4) |
// | estimate  | Ĝ_ij = (rays from i that hit j first) / N |
// | ray k     | origin uniform on patch i (folded square, textbook 4.38), direction cosine-distributed about
// | |           | its side's normal (Malley, 4.60–4.61), both from the 4-D point (sobol pair 0, pair 2) of |
// |           | sample k at "pixel" (i mod 2^16, i / 2^16), seed kFormFactorSeed: a fixed, padded |
// |           | Owen-scrambled Sobol set per patch, the same for any thread count |
// | sky E_i   | (π/N) Σ over the rays that leave the scene of the background radiance they see |
//
// Why Ĝ_ij is unbiased: a ray with origin density 1/A_i and direction density c_i/π hits the
// element dA_j with probability (1/A_i) ∫ (c_i/π) dω = (1/A_i) ∫ c_i c_j v/(π r²) dA_j: the
// integrand of (3.4). Each ray hits one patch or none, so Ĝ_ij is a multinomial share with
// Var Ĝ_ij = G_ij (1 − G_ij)/N, and Σ_j Ĝ_ij = (rays that hit something)/N: exactly 1 from a
// side of a closed mesh, whatever N (closure holds row by row, not only in expectation).
// Reciprocity A_i G_ij = A_j G_ji holds in expectation only (independent rays from i and j).
//
// The sky term is the same estimator for the background: ∫ L_bg c_i dω = π E[L_bg] over
// cosine directions that escape. Rays are diffuse rays (StratumVisibility DIFFUSE) at shutter
// open, where the patches are.
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "radiosity/patch_set.h"
#include "radiosity/sparse_matrix.h"
#include "render_scene/render_scene.h"

namespace stratum {

inline constexpr uint32_t kFormFactorSeed = 0x52414431u;  // "RAD1"

struct FormFactors {
    SparseMatrix gather;              // row i: (j, Ĝ_ij) for every patch j some ray of i hit
    std::vector<Rgb> sky_irradiance;  // per patch
    uint64_t rays = 0;
};

// Throws RenderScene::BuildCancelled when *cancel (may be null) becomes true.
FormFactors estimate_form_factors(const RenderScene& scene, const PatchSet& patches, uint32_t rays_per_patch,
                                  const std::atomic<bool>* cancel);

// A ray origin on patch `p` at `point`, moved off the surface along the side's normal by the
// relative distance integrators/ray_offset.h uses for hit points (1e-4 of the larger of 1 and
// the point's largest coordinate).
Vec3 patch_ray_origin(Vec3 point, Vec3 normal);
float patch_ray_offset(Vec3 point);

}  // namespace stratum
