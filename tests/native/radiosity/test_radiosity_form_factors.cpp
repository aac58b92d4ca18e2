// Radiosity patches and form factors (radiosity/patch_set.h, radiosity/form_factors.h;
// textbook §3: reciprocity A_i G_ij = A_j G_ji, closure Σ_j G_ij = 1 in a closed scene,
// G_ij = A_j/A_s inside a sphere).
//
// Tolerances. Ĝ_ij counts the rays of patch i (N of them) that hit j first. Were the rays
// independent, the count of hits in any set J of patches would be binomial: Var Ĝ_iJ =
// G_iJ (1 − G_iJ)/N, and rows of different patches are independent. The rays are a scrambled
// Sobol set per patch, whose error is at most that of independent rays for these smooth
// integrands (stratification, textbook 4.8: σ²_strat ≤ σ²), so the binomial σ is an upper bound
// and k·σ tolerances derived from it are conservative. Sums over patches add variances.
// * closure: every ray from the inner side of a closed mesh hits the mesh, so each row sums to 1
//   exactly (only float rounding of the shares, < 1e-5), not just in expectation;
// * a face's form factor to another face of the cube: F̂_IJ = Σ_{i∈I} A_i Ĝ_iJ / A_I, σ² =
//   Σ_{i∈I} A_i² Ĝ_iJ (1 − Ĝ_iJ) / (N A_I²); |F̂_IJ − F_IJ| ≤ 4.5σ against the exact values
//   (Howell's catalogue), 30 ordered face pairs: false alarms ≤ 30 × 6.8e-6 = 2e-4;
// * patch reciprocity: z_ij = (A_i Ĝ_ij − A_j Ĝ_ji)/σ_ij, σ_ij² = (A_i² G̃_ij (1 − G̃_ij) +
//   A_j² G̃_ji (1 − G̃_ji))/N with G̃ the reciprocal mean of the two estimates; every |z| ≤ 5.5
//   (3.8e-8 per pair, 2e-4 over the 5,000-odd pairs) and mean z² ≤ 1 + 5 √(2/pairs) (a χ² of
//   `pairs` degrees of freedom has mean 1 per pair and standard deviation √(2/pairs));
// * sphere: octant I's hits in octant J, C_IJ = Σ_{i∈I} N Ĝ_iJ, expected E_IJ = N Σ_{i∈I} A_J/A_s;
//   Pearson's χ² over the 8 × 8 cells has 8 × 7 = 56 degrees of freedom (each source octant's
//   counts sum to its rays exactly); accepted below the 0.9999 quantile 103.4. The mesh's flat
//   facets see octants with form factors that differ from A_J/A_s by their tilt, < 0.5 % per
//   facet and cancelling over an octant to ~1e-5 (render_helpers.h, kPortedSphereBias): far
//   under the 0.8 % σ of each cell's ~15,000 hits.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstdio>

#include "radiosity/form_factors.h"
#include "radiosity/patch_set.h"
#include "radiosity_scenes.h"

using namespace stratum_test;
using stratum::FormFactors;
using stratum::Patch;
using stratum::PatchSet;
using stratum::RenderScene;
using stratum::SparseEntry;
using stratum::Vec2;
using stratum::Vec3;

namespace {

double row_sum(const FormFactors& f, uint32_t i) {
    double sum = 0.0;
    for (const SparseEntry& e : f.gather.row(i)) sum += e.value;
    return sum;
}

// Whether patch i of a closed mesh around the origin faces inward (its normal toward the centre).
bool faces_inward(const Patch& p) { return stratum::dot(p.normal, p.centroid()) < 0.0f; }

float longest(const Patch& p) {
    return std::max({stratum::length(p.edge1), stratum::length(p.edge2), stratum::length(p.edge2 - p.edge1)});
}

}  // namespace

// Every sub-triangle's centroid is found in that sub-triangle, for each division count.
TEST(RadiosityPatches, SubTriangleIndexInvertsItsCorners) {
    for (uint32_t n = 1; n <= 9; ++n) {
        for (uint32_t sub = 0; sub < n * n; ++sub) {
            Vec2 c[3];
            PatchSet::sub_triangle_corners(n, sub, c);
            const float scale = 1.0f / (3.0f * static_cast<float>(n));
            const float b1 = (c[0].x + c[1].x + c[2].x) * scale, b2 = (c[0].y + c[1].y + c[2].y) * scale;
            EXPECT_EQ(PatchSet::sub_triangle(n, b1, b2), sub) << "n " << n;
        }
    }
}

// Splitting keeps every edge under the patch size, covers each triangle's area exactly twice
// (two sides), and a ray finds the patch (and side) that holds the point it hits.
TEST(RadiosityPatches, SubdivisionIsBelowThePatchSizeAndRaysFindTheirPatch) {
    const stratum::Scene scene = closed_cube(0.5f);
    const RenderScene rs(scene);
    for (const float size : {3.0f, 1.0f, 0.3f}) {
        const PatchSet patches(rs, size, nullptr);
        const uint32_t n = static_cast<uint32_t>(std::floor(2.0f * std::sqrt(2.0f) / size)) + 1;
        ASSERT_EQ(patches.size(), 6u * 2u * n * n * 2u) << "size " << size;
        double area = 0.0;
        for (uint32_t i = 0; i < patches.size(); ++i) {
            EXPECT_LT(longest(patches.patch(i)), size);
            area += patches.patch(i).area;
        }
        EXPECT_NEAR(area, 2.0 * 24.0, 1e-4 * 48.0);
        EXPECT_EQ(stratum::count_patches(rs, size).patches, patches.size());
        // From the centre toward each patch's centroid (inner side) and from outside back at it
        // (outer side): the hit must be that patch.
        for (uint32_t i = 0; i < patches.size(); i += 2) {
            const Vec3 c = patches.patch(i).centroid();
            for (const bool inside : {true, false}) {
                const Vec3 origin = inside ? Vec3(0, 0, 0) : c * 2.0f;
                const Vec3 dir = stratum::normalize(c - origin);
                stratum::RayHit hit;
                ASSERT_TRUE(rs.intersect_triangle(origin, dir, 0.0f, 10.0f, &hit));
                const uint32_t j = patches.patch_of(hit, dir);
                ASSERT_NE(j, stratum::kNoPatch);
                EXPECT_EQ(j / 2, i / 2) << "patch " << i;
                EXPECT_LT(stratum::dot(patches.patch(j).normal, dir), 0.0f);
                EXPECT_EQ(faces_inward(patches.patch(j)), inside);
            }
        }
    }
}

// Closure and the cube's face-to-face form factors against Howell's exact values, with the
// reciprocity of faces and of patches (header: tolerances).
TEST(RadiosityFormFactors, CubeClosureFaceFactorsAndReciprocity) {
    const double parallel = parallel_rectangles_form_factor(2, 2, 2),
                 adjacent = perpendicular_squares_form_factor();
    ASSERT_NEAR(parallel + 4 * adjacent, 1.0, 1e-5);  // the catalogue's own closure
    const stratum::Scene scene = closed_cube(0.5f);
    const RenderScene rs(scene);
    const PatchSet patches(rs, 1.0f, nullptr);  // n = 3: 18 patches per face and side
    constexpr uint32_t kRays = 16384;
    const FormFactors f = stratum::estimate_form_factors(rs, patches, kRays, nullptr);
    std::printf("cube: K = %u patches, %zu form factors, %.2f MB\n", patches.size(), f.gather.entries(),
                static_cast<double>(f.gather.bytes()) / 1e6);
    double face_area[6] = {}, face_sum[6][6] = {}, face_var[6][6] = {};
    for (uint32_t i = 0; i < patches.size(); ++i) {
        const Patch& p = patches.patch(i);
        if (!faces_inward(p)) {
            EXPECT_EQ(f.gather.row(i).size(), 0u) << "outer patch " << i << " sees something";
            continue;
        }
        EXPECT_NEAR(row_sum(f, i), 1.0, 1e-5) << "patch " << i;
        double to_face[6] = {};
        for (const SparseEntry& e : f.gather.row(i)) {
            ASSERT_TRUE(faces_inward(patches.patch(e.column)));
            to_face[cube_face(patches.patch(e.column).centroid())] += e.value;
        }
        const int I = cube_face(p.centroid());
        face_area[I] += p.area;
        for (int J = 0; J < 6; ++J) {
            face_sum[I][J] += p.area * to_face[J];
            face_var[I][J] += double(p.area) * p.area * to_face[J] * (1.0 - to_face[J]) / kRays;
        }
    }
    double worst_z = 0.0, mean_parallel = 0.0, mean_adjacent = 0.0;
    for (int I = 0; I < 6; ++I) {
        ASSERT_NEAR(face_area[I], 4.0, 1e-4);
        for (int J = 0; J < 6; ++J) {
            const double estimate = face_sum[I][J] / face_area[I];
            if (I == J) {
                EXPECT_EQ(estimate, 0.0);
                continue;
            }
            const double exact = (I / 2 == J / 2) ? parallel : adjacent;
            const double sigma = std::sqrt(face_var[I][J]) / face_area[I];
            EXPECT_NEAR(estimate, exact, 4.5 * sigma) << "faces " << I << " -> " << J << " sigma " << sigma;
            worst_z = std::max(worst_z, std::abs(estimate - exact) / sigma);
            (I / 2 == J / 2 ? mean_parallel : mean_adjacent) += estimate / (I / 2 == J / 2 ? 6.0 : 24.0);
            // Reciprocity of faces: A_I F_IJ = A_J F_JI within both estimates' spread.
            const double spread = std::sqrt(face_var[I][J] + face_var[J][I]);
            EXPECT_NEAR(face_sum[I][J], face_sum[J][I], 4.5 * spread) << "faces " << I << ", " << J;
        }
    }
    std::printf("cube faces: parallel %.5f (exact %.5f), adjacent %.5f (exact %.5f), worst |z| %.2f\n",
                mean_parallel, parallel, mean_adjacent, adjacent, worst_z);
    // Reciprocity of patches.
    double z2 = 0.0, worst = 0.0;
    double pairs = 0.0;
    auto value = [&](uint32_t i, uint32_t j) {
        for (const SparseEntry& e : f.gather.row(i))
            if (e.column == j) return static_cast<double>(e.value);
        return 0.0;
    };
    for (uint32_t i = 0; i < patches.size(); ++i) {
        for (const SparseEntry& e : f.gather.row(i)) {
            const uint32_t j = e.column;
            if (j <= i) continue;
            const double ai = patches.patch(i).area, aj = patches.patch(j).area;
            const double flux_ij = ai * e.value, flux_ji = aj * value(j, i);
            const double mean = 0.5 * (flux_ij + flux_ji);
            const double gij = mean / ai, gji = mean / aj;
            const double sigma = std::sqrt((ai * ai * gij * (1 - gij) + aj * aj * gji * (1 - gji)) / kRays);
            const double z = (flux_ij - flux_ji) / sigma;
            z2 += z * z;
            worst = std::max(worst, std::abs(z));
            pairs += 1.0;
        }
    }
    ASSERT_GT(pairs, 4000.0);
    std::printf("patch reciprocity: %.0f pairs, mean z^2 %.3f, worst |z| %.2f\n", pairs, z2 / pairs, worst);
    EXPECT_LE(worst, 5.5);
    EXPECT_LE(z2 / pairs, 1.0 + 5.0 * std::sqrt(2.0 / pairs));
}

// Closure row by row and G_iJ = A_J/A_s for octants J of a sphere (header: the χ² test).
TEST(RadiosityFormFactors, SphereRowsCloseAndSeeEachOctantByItsArea) {
    const PortedSphereMesh sphere = make_ported_sphere(16, 0);
    const stratum::Scene scene = sphere_scene(sphere, 0.5f);
    const RenderScene rs(scene);
    const PatchSet patches(rs, 4.0f, nullptr);  // one patch per triangle and side
    constexpr uint32_t kRays = 1024;
    const FormFactors f = stratum::estimate_form_factors(rs, patches, kRays, nullptr);
    const auto octant = [](Vec3 p) { return (p.x > 0 ? 1 : 0) + (p.y > 0 ? 2 : 0) + (p.z > 0 ? 4 : 0); };
    double octant_area[8] = {}, sources[8] = {}, hits[8][8] = {};
    double total_area = 0.0;
    uint32_t sources_counted = 0;
    for (uint32_t i = 0; i < patches.size(); ++i) {
        const Patch& p = patches.patch(i);
        // The UV sphere's south pole has sliver facets (area ~1e-9: sin π rounds to −8.7e-8, so
        // the pole's vertices are not one point) whose normals tilt far off the radius: the
        // mesh is not quite convex there and their outer sides see their neighbours, and a
        // facet tilted off the radius does not see octants by their area. Elsewhere the outer
        // side sees nothing; the slivers still close (every ray hits) and count in the areas.
        const bool sliver = p.area < 1e-6f;
        if (!faces_inward(p)) {
            if (!sliver) {
                EXPECT_EQ(f.gather.row(i).size(), 0u) << "outer patch " << i;
            }
            continue;
        }
        EXPECT_NEAR(row_sum(f, i), 1.0, 1e-5) << "patch " << i;
        octant_area[octant(p.centroid())] += p.area;
        total_area += p.area;
        if (sliver) continue;
        sources[octant(p.centroid())] += 1.0;
        for (const SparseEntry& e : f.gather.row(i))
            hits[octant(p.centroid())][octant(patches.patch(e.column).centroid())] += e.value * kRays;
        ++sources_counted;
    }
    EXPECT_NEAR(total_area, sphere.total_area(), 1e-4 * total_area);
    EXPECT_GT(sources_counted, 900u);
    double chi2 = 0.0;
    for (int I = 0; I < 8; ++I) {
        for (int J = 0; J < 8; ++J) {
            const double expected = kRays * sources[I] * octant_area[J] / total_area;
            chi2 += (hits[I][J] - expected) * (hits[I][J] - expected) / expected;
        }
    }
    std::printf("sphere: K = %u, octant chi^2 = %.1f (56 dof, 0.9999 quantile 103.4)\n", patches.size(),
                chi2);
    EXPECT_LT(chi2, 103.4);
}

// The same form factors for any thread count: each row is traced from its own point set.
TEST(RadiosityFormFactors, DeterministicForAnyThreadCount) {
    const stratum::Scene scene = closed_cube(0.5f);
    const RenderScene rs(scene);
    const PatchSet patches(rs, 0.7f, nullptr);
    FormFactors one, two;
    tbb::task_arena(1).execute([&] { one = stratum::estimate_form_factors(rs, patches, 256, nullptr); });
    tbb::task_arena(2).execute([&] { two = stratum::estimate_form_factors(rs, patches, 256, nullptr); });
    ASSERT_EQ(one.gather.entries(), two.gather.entries());
    for (uint32_t i = 0; i < patches.size(); ++i) {
        const auto a = one.gather.row(i), b = two.gather.row(i);
        ASSERT_EQ(a.size(), b.size());
        for (size_t k = 0; k < a.size(); ++k) {
            EXPECT_EQ(a[k].column, b[k].column);
            EXPECT_EQ(a[k].value, b[k].value);
        }
    }
}
