#include "radiosity/form_factors.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "sampling/sobol_sampler.h"
#include "sampling/warps.h"

namespace stratum {

namespace {

// Patches per task: a row takes N rays, so a block is enough work to schedule and few enough
// that the last blocks balance across threads.
constexpr uint32_t kBlockPatches = 64;

struct Block {
    std::vector<SparseEntry> entries;
};

}  // namespace

float patch_ray_offset(Vec3 point) {
    return 1e-4f * std::max({1.0f, std::abs(point.x), std::abs(point.y), std::abs(point.z)});
}

Vec3 patch_ray_origin(Vec3 point, Vec3 normal) { return point + normal * patch_ray_offset(point); }

FormFactors estimate_form_factors(const RenderScene& scene, const PatchSet& patches, uint32_t rays_per_patch,
                                  const std::atomic<bool>* cancel) {
    const uint32_t count = patches.size();
    FormFactors out;
    out.sky_irradiance.assign(count, Rgb(0.0f));
    std::vector<uint32_t> row_lengths(count, 0);
    const uint32_t blocks = (count + kBlockPatches - 1) / kBlockPatches;
    std::vector<Block> block_rows(blocks);
    const SobolSampler sampler(SamplerSettings{rays_per_patch, kFormFactorSeed, 1, 1});
    const float inv_rays = 1.0f / static_cast<float>(rays_per_patch);
    const RayQuery query{0.0f, kVisibleDiffuse};
    tbb::parallel_for(
        tbb::blocked_range<uint32_t>(0, blocks, 1), [&](const tbb::blocked_range<uint32_t>& range) {
            std::vector<uint32_t> hits;
            hits.reserve(rays_per_patch);
            for (uint32_t b = range.begin(); b != range.end(); ++b) {
                if (cancel && cancel->load(std::memory_order_relaxed)) return;
                const uint32_t end = std::min(count, (b + 1) * kBlockPatches);
                for (uint32_t i = b * kBlockPatches; i < end; ++i) {
                    const Patch& patch = patches.patch(i);
                    const Frame frame = Frame::from_normal(patch.normal);
                    hits.clear();
                    Rgb sky(0.0f);
                    for (uint32_t k = 0; k < rays_per_patch; ++k) {
                        const PixelSample s(i & 0xffffu, i >> 16, k);
                        const Vec3 point = patch.point(sample_uniform_triangle(sampler.get_2d(s, 0)));
                        const Vec3 dir = frame.to_world(sample_cosine_hemisphere(sampler.get_2d(s, 2)));
                        RayHit hit;
                        if (scene.intersect_triangle(patch_ray_origin(point, patch.normal), dir, 0.0f,
                                                     kInfinity, &hit, query)) {
                            const uint32_t j = patches.patch_of(hit, dir);
                            if (j != kNoPatch) hits.push_back(j);
                        } else {
                            sky += scene.background(dir);
                        }
                    }
                    out.sky_irradiance[i] = sky * (kPi * inv_rays);
                    std::sort(hits.begin(), hits.end());
                    std::vector<SparseEntry>& entries = block_rows[b].entries;
                    for (size_t h = 0; h < hits.size();) {
                        size_t same = h;
                        while (same < hits.size() && hits[same] == hits[h]) ++same;
                        entries.push_back({hits[h], static_cast<float>(same - h) * inv_rays});
                        ++row_lengths[i];
                        h = same;
                    }
                }
            }
        });
    if (cancel && cancel->load(std::memory_order_relaxed)) throw RenderScene::BuildCancelled();
    size_t total = 0;
    for (const Block& b : block_rows) total += b.entries.size();
    std::vector<SparseEntry> entries;
    entries.reserve(total);
    for (Block& b : block_rows) {
        entries.insert(entries.end(), b.entries.begin(), b.entries.end());
        b.entries = {};
    }
    out.gather = SparseMatrix(row_lengths, std::move(entries));
    out.rays = static_cast<uint64_t>(count) * rays_per_patch;
    return out;
}

}  // namespace stratum
