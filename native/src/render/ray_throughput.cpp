#include "render/ray_throughput.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <stdexcept>

#include "integrators/ray_offset.h"
#include "render_scene/render_scene.h"
#include "sampling/hash.h"
#include "sampling/pcg32.h"
#include "sampling/warps.h"

namespace stratum {

RayThroughput measure_ray_throughput(const Scene& scene, uint32_t width, uint32_t height, uint32_t samples,
                                     uint32_t max_bounces, uint32_t threads) {
    if (!scene.camera) throw std::runtime_error("the scene has no camera");
    tbb::task_arena arena(threads == 0 ? tbb::task_arena::automatic : static_cast<int>(threads));
    std::unique_ptr<RenderScene> rs;
    arena.execute([&] { rs = std::make_unique<RenderScene>(scene); });
    const Camera camera(*scene.camera, width, height);
    const auto t0 = std::chrono::steady_clock::now();
    const uint64_t rays = arena.execute([&] {
        return tbb::parallel_reduce(
            tbb::blocked_range<uint32_t>(0, height), uint64_t{0},
            [&](const tbb::blocked_range<uint32_t>& rows, uint64_t count) {
                for (uint32_t y = rows.begin(); y < rows.end(); ++y) {
                    Pcg32 rng(hash_words(y, width), 1);
                    const auto u = [&] { return bits_to_unit_float(rng.next_u32()); };
                    for (uint32_t x = 0; x < width; ++x) {
                        for (uint32_t s = 0; s < samples; ++s) {
                            const CameraRay cr = camera.generate_ray(static_cast<float>(x) + 0.5f,
                                                                     static_cast<float>(y) + 0.5f);
                            Vec3 origin = cr.origin, dir = cr.direction;
                            float t_min = cr.t_min, t_max = cr.t_max;
                            for (uint32_t vertex = 0; vertex <= max_bounces; ++vertex) {
                                SurfaceHit hit;
                                ++count;
                                if (!rs->intersect(origin, dir, t_min, t_max, &hit)) break;
                                const Vec3 n = dot(hit.geometric_normal, dir) > 0.0f ? -hit.geometric_normal
                                                                                     : hit.geometric_normal;
                                const Frame frame = Frame::from_normal(n);
                                origin = offset_ray_origin(hit.position, n);
                                ++count;
                                rs->occluded(origin, frame.to_world(sample_cosine_hemisphere({u(), u()})),
                                             0.0f, kInfinity);
                                dir = frame.to_world(sample_cosine_hemisphere({u(), u()}));
                                t_min = 0.0f;
                                t_max = kInfinity;
                            }
                        }
                    }
                }
                return count;
            },
            [](uint64_t a, uint64_t b) { return a + b; });
    });
    return {static_cast<double>(rays),
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()};
}

}  // namespace stratum
