#include "radiosity/patch_set.h"

#include <algorithm>
#include <cmath>

#include "bsdf/bsdf.h"
#include "radiosity/radiosity_settings.h"

namespace stratum {

namespace {

constexpr uint32_t kCancelCheckTriangles = 65536;

float longest_edge(const RenderScene::PlacedTriangle& t) {
    return std::max({length(t.p1 - t.p0), length(t.p2 - t.p1), length(t.p0 - t.p2)});
}

// n = ⌊longest / size⌋ + 1 in double (a tiny size gives more than any integer type holds).
double divisions(float longest, float size) { return std::floor(static_cast<double>(longest) / size) + 1.0; }

bool degenerate(const RenderScene::PlacedTriangle& t) {
    const float area = 0.5f * length(cross(t.p1 - t.p0, t.p2 - t.p0));
    return !(area > 0.0f) || !std::isfinite(area);
}

void throw_if_cancelled(const std::atomic<bool>* cancel) {
    if (cancel && cancel->load(std::memory_order_relaxed)) throw RenderScene::BuildCancelled();
}

}  // namespace

bool radiosity_approximates(const SceneMaterial& material) {
    return std::any_of(material.closures.begin(), material.closures.end(), [](const WeightedClosure& c) {
        const ClosureModel& model = closure_model(c.params.model);
        return !model.lambertian && (model.transparent || model.sample_weight(c.params) > 0.0f);
    });
}

PatchCount count_patches(const RenderScene& scene, float requested) {
    float size = requested;
    if (!(size > 0.0f)) {
        Bounds bounds;
        for (uint32_t p = 0; p < scene.placement_count(); ++p) {
            for (uint32_t t = 0; t < scene.placement_triangle_count(p); ++t) {
                const RenderScene::PlacedTriangle tri = scene.placed_triangle(p, t);
                bounds.add(tri.p0);
                bounds.add(tri.p1);
                bounds.add(tri.p2);
            }
        }
        const float diagonal = bounds.empty() ? 0.0f : length(bounds.hi - bounds.lo);
        size = diagonal > 0.0f && std::isfinite(diagonal) ? diagonal / kAutomaticPatchDivisions : 1.0f;
    }
    double patches = 0.0;
    for (uint32_t p = 0; p < scene.placement_count(); ++p) {
        for (uint32_t t = 0; t < scene.placement_triangle_count(p); ++t) {
            const RenderScene::PlacedTriangle tri = scene.placed_triangle(p, t);
            if (degenerate(tri)) continue;
            const double n = divisions(longest_edge(tri), size);
            patches += 2.0 * n * n;
        }
    }
    constexpr double kSaturated = 1.8e19;  // below 2^64
    return {size, static_cast<uint64_t>(std::min(patches, kSaturated))};
}

uint32_t PatchSet::sub_triangle(uint32_t n, float b1, float b2) {
    const float x = b1 * static_cast<float>(n), y = b2 * static_cast<float>(n);
    const uint32_t i = std::min(static_cast<uint32_t>(std::max(x, 0.0f)), n - 1);
    const uint32_t j = std::min(static_cast<uint32_t>(std::max(y, 0.0f)), n - 1 - i);
    const bool inverted = (x - static_cast<float>(i)) + (y - static_cast<float>(j)) > 1.0f && i + j + 2 <= n;
    // Rows before i hold Σ_{r<i} (n − r) upright and Σ_{r<i} (n − 1 − r) inverted cells.
    const uint32_t before = i * (i - 1) / 2;
    if (!inverted) return i * n - before + j;
    return n * (n + 1) / 2 + i * (n - 1) - before + j;
}

void PatchSet::sub_triangle_corners(uint32_t n, uint32_t sub, Vec2 corners[3]) {
    const uint32_t upright = n * (n + 1) / 2;
    const bool inverted = sub >= upright;
    uint32_t rest = inverted ? sub - upright : sub;
    uint32_t i = 0;
    for (;; ++i) {
        const uint32_t row = inverted ? n - 1 - i : n - i;
        if (rest < row) break;
        rest -= row;
    }
    cell_corners(i, rest, inverted, corners);
}

void PatchSet::cell_corners(uint32_t i, uint32_t j, bool inverted, Vec2 corners[3]) {
    const float fi = static_cast<float>(i), fj = static_cast<float>(j);
    if (!inverted) {
        corners[0] = {fi, fj};
        corners[1] = {fi + 1.0f, fj};
        corners[2] = {fi, fj + 1.0f};
    } else {
        corners[0] = {fi + 1.0f, fj + 1.0f};
        corners[1] = {fi, fj + 1.0f};
        corners[2] = {fi + 1.0f, fj};
    }
}

PatchSet::PatchSet(const RenderScene& scene, float patch_size, const std::atomic<bool>* cancel)
    : patch_size_(patch_size) {
    uint32_t triangles = 0;
    for (uint32_t p = 0; p < scene.placement_count(); ++p) {
        placement_first_triangle_.push_back(triangles);
        triangles += scene.placement_triangle_count(p);
    }
    triangle_first_patch_.assign(triangles, kNoPatch);
    triangle_divisions_.assign(triangles, 0);
    // First the divisions and where each triangle's patches start (the caller has checked that
    // they fit: count_patches), then the patches.
    uint32_t global = 0, patches = 0;
    for (uint32_t p = 0; p < scene.placement_count(); ++p) {
        for (uint32_t t = 0; t < scene.placement_triangle_count(p); ++t, ++global) {
            const RenderScene::PlacedTriangle tri = scene.placed_triangle(p, t);
            if (degenerate(tri)) continue;
            const uint32_t n = static_cast<uint32_t>(divisions(longest_edge(tri), patch_size));
            triangle_first_patch_[global] = patches;
            triangle_divisions_[global] = n;
            patches += 2 * n * n;
        }
    }
    patches_.reserve(patches);
    albedo_.reserve(patches);
    emission_.reserve(patches);
    global = 0;
    for (uint32_t p = 0; p < scene.placement_count(); ++p) {
        for (uint32_t t = 0; t < scene.placement_triangle_count(p); ++t, ++global) {
            if (global % kCancelCheckTriangles == 0) throw_if_cancelled(cancel);
            const uint32_t n = triangle_divisions_[global];
            if (n == 0) continue;
            const RenderScene::PlacedTriangle tri = scene.placed_triangle(p, t);
            const ClosureSet& closures = scene.closure_set(tri.material_id);
            const Rgb albedo = closures.colors(Vec3(0.0f, 0.0f, 1.0f)).diffuse;
            const Rgb emission = closures.emission() * kPi;
            const Vec3 e1 = tri.p1 - tri.p0, e2 = tri.p2 - tri.p0;
            const Vec3 normal = normalize(cross(e1, e2));
            const float inv_n = 1.0f / static_cast<float>(n);
            const float area = 0.5f * length(cross(e1, e2)) * inv_n * inv_n;
            const auto at = [&](Vec2 b) { return tri.p0 + e1 * (b.x * inv_n) + e2 * (b.y * inv_n); };
            // Cells in sub-triangle order: the upright ones row by row, then the inverted ones.
            for (const bool inverted : {false, true}) {
                for (uint32_t i = 0; i < n; ++i) {
                    // A triangle far larger than the patch size is many rows of cells.
                    if (i % 256 == 255) throw_if_cancelled(cancel);
                    for (uint32_t j = 0; j + i + (inverted ? 1 : 0) < n; ++j) {
                        Vec2 c[3];
                        cell_corners(i, j, inverted, c);
                        const Vec3 corner = at(c[0]);
                        const Patch front{corner, at(c[1]) - corner, at(c[2]) - corner, normal, area};
                        Patch back = front;
                        back.normal = -normal;
                        patches_.push_back(front);
                        patches_.push_back(back);
                    }
                }
            }
            albedo_.resize(patches_.size(), albedo);
            emission_.resize(patches_.size(), emission);
        }
    }
}

uint32_t PatchSet::patch_of(const RayHit& hit, Vec3 direction) const {
    const uint32_t global = placement_first_triangle_[hit.instance] + hit.triangle;
    const uint32_t first = triangle_first_patch_[global];
    if (first == kNoPatch) return kNoPatch;
    const uint32_t n = triangle_divisions_[global];
    const uint32_t patch = first + 2 * sub_triangle(n, hit.b1, hit.b2);
    // The ray arrives against the normal of the side it hits.
    return dot(direction, patches_[patch].normal) < 0.0f ? patch : patch + 1;
}

size_t PatchSet::bytes() const {
    return patches_.capacity() * sizeof(Patch) + (albedo_.capacity() + emission_.capacity()) * sizeof(Rgb) +
           (placement_first_triangle_.capacity() + triangle_first_patch_.capacity() +
            triangle_divisions_.capacity()) *
               sizeof(uint32_t);
}

}  // namespace stratum
