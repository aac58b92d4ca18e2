// The radiosity method's patches (textbook §3): every triangle of the render scene, in world
// space after instancing, split into n² congruent sub-triangles, each with two sides.
//
// | quantity        | definition                                                             |
// |-----------------|------------------------------------------------------------------------|
// | divisions n     | ⌊longest edge / patch size⌋ + 1 per triangle, so a sub-triangle's edges |
// |                 | (the triangle's / n) are all shorter than the patch size                |
// | sub-triangle    | the barycentric grid (b1, b2) ∈ {i/n, j/n}: n(n+1)/2 upright cells      |
// |                 | (i, j), i + j ≤ n − 1, then n(n−1)/2 inverted ones (i + j ≤ n − 2)      |
// | patch           | triangle's first patch + 2 × sub-triangle + side (0: the winding        |
// |                 | normal's side, 1: the other); a ray arriving against a side's normal    |
// |                 | hits that side                                                          |
// | area A_i        | the triangle's area / n²                                                |
// | albedo κ_i      | the material's diffuse albedo: its closures' Diffuse Color at normal     |
// |                 | incidence (ClosureSet::colors); exact for Lambert (base colour), the    |
// |                 | diffuse part of other models, 0 for glossy, glass and transparency      |
// | emission M_e,i  | π L_e (both sides: Stratum's emissive triangles are two-sided)          |
//
// Both sides are patches because Blender's surfaces are two-sided (a wall of zero thickness is
// lit on either side); a side that sees nothing simply has an empty row of form factors. Patches
// take the material's parameters without image textures (the final gather shades the camera's
// points with them). Moving placements are taken at shutter open; a ray at another time still
// finds its patch by barycentrics.
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "core/math.h"
#include "radiosity/radiosity_settings.h"
#include "render_scene/render_scene.h"

namespace stratum {

inline constexpr uint32_t kNoPatch = 0xffffffffu;

struct Patch {
    Vec3 corner, edge1, edge2;  // the sub-triangle: corner + a edge1 + b edge2, a, b ≥ 0, a + b ≤ 1
    Vec3 normal;                // unit, out of this side
    float area;
    Vec3 centroid() const { return corner + (edge1 + edge2) * (1.0f / 3.0f); }
    Vec3 point(Vec3 barycentric) const { return corner + edge1 * barycentric.y + edge2 * barycentric.z; }
};

// The patch size `requested` stands for in `scene` (0: automatic, radiosity/radiosity_settings.h),
// and how many patches it gives (counted in 64 bits: a tiny size can exceed any index).
struct PatchCount {
    float patch_size;
    uint64_t patches;
};
PatchCount count_patches(const RenderScene& scene, float requested);

// Whether radiosity takes only the diffuse albedo of `material`: it has a scattering closure
// other than Lambert's (glossy, glass, transparent, Principled's specular layers).
bool radiosity_approximates(const SceneMaterial& material);

class PatchSet {
public:
    // Throws RenderScene::BuildCancelled when *cancel (may be null) becomes true.
    PatchSet(const RenderScene& scene, float patch_size, const std::atomic<bool>* cancel);

    uint32_t size() const { return static_cast<uint32_t>(patches_.size()); }
    const Patch& patch(uint32_t i) const { return patches_[i]; }
    Rgb albedo(uint32_t i) const { return albedo_[i]; }
    Rgb emission(uint32_t i) const { return emission_[i]; }  // M_e = π L_e
    float patch_size() const { return patch_size_; }
    // The patch a ray of direction `direction` meets at `hit`; kNoPatch on a degenerate triangle.
    uint32_t patch_of(const RayHit& hit, Vec3 direction) const;
    size_t bytes() const;

    // The sub-triangle of a triangle divided n ways that barycentrics (b1, b2) fall in, and the
    // sub-triangle's corners in the triangle's barycentrics (b1, b2) × n.
    static uint32_t sub_triangle(uint32_t n, float b1, float b2);
    static void sub_triangle_corners(uint32_t n, uint32_t sub, Vec2 corners[3]);

private:
    // Corners of cell (i, j) of the grid, upright or inverted, in barycentrics × n.
    static void cell_corners(uint32_t i, uint32_t j, bool inverted, Vec2 corners[3]);

    std::vector<Patch> patches_;
    std::vector<Rgb> albedo_, emission_;
    std::vector<uint32_t> placement_first_triangle_;  // per placement, into the two below
    std::vector<uint32_t> triangle_first_patch_;      // kNoPatch for a degenerate triangle
    std::vector<uint32_t> triangle_divisions_;        // n
    float patch_size_;
};

}  // namespace stratum
