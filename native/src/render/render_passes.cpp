// The passes of a render (render/renderer.h): sample indices in passes [0,1), [1,2), [2,4), ...
// each traced tile by tile on the task arena (camera samples, then the integrator's light
// paths), and between passes what the render learns and decides: the integrator's learning
// (path guiding), the error estimate and adaptive sampling's stops at powers of two, publishing.
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>

#include "integrators/integrator.h"
#include "render/renderer.h"
#include "sampling/dimensions.h"
#include "sampling/sampler_registry.h"

namespace stratum {

namespace {

constexpr uint32_t kTileSize = 16;
// Tiles under adaptive sampling: in its late passes few pixels still sample, often in a few
// clusters, and a 16² tile holding a cluster kept one core busy while the other idled (Wolf,
// 64², metric mse: 5% of the render's time).
constexpr uint32_t kAdaptiveTileSize = 4;
constexpr uint32_t kMaxPassSamples = 64;
// Light paths are traced in chunks of consecutive path indices, a batch of chunks in parallel;
// each chunk collects its splats, and the batch's chunks are added to the film in chunk order,
// so the sums do not depend on the thread count or scheduling. A batch holds 16384 paths'
// splats (light tracing: at most (max_bounces + 1) connections × 16 pixels each).
constexpr uint32_t kLightPathChunk = 256;
constexpr uint32_t kChunksPerBatch = 64;

bool is_finite(const Rgb& c) { return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b); }

// Runs body on every tile of `tiles`, split down to at most kTileSize pixels a side
// (tbb::simple_partitioner; the default partitioner leaves tiles of 32² and more): each tile
// publishes its pixels and counts its samples when it ends, so small tiles are what makes the
// image and the progress move within a pass. The split does not change any pixel: the film's
// sums are exact (film/film.h), whatever tile a pixel falls in.
template <typename Body>
void parallel_for_tile(const tbb::blocked_range2d<uint32_t>& tiles, const Body& body) {
    tbb::parallel_for(tiles, body, tbb::simple_partitioner());
}

}  // namespace

void Renderer::render_passes(const RenderSettings& s, const Camera& camera, tbb::task_arena& arena) {
    // Sample indices [first_sample_, last_sample_); progress counts them from first_sample_.
    // Pass ends stay at powers of two of the count (a subset starting at 0 is the full
    // render's prefix).
    const uint32_t total = last_sample_ - first_sample_;
    uint32_t done = 0;
    while (done < total && !cancel_.load()) {
        const uint32_t next = std::min({total, std::max(done + 1, 2 * done), done + kMaxPassSamples});
        render_pass(s, camera, done, next, arena);
        done = next;
    }
}

void Renderer::render_pass(const RenderSettings& s, const Camera& camera, uint32_t done, uint32_t next,
                           tbb::task_arena& arena) {
    const uint32_t begin = first_sample_ + done, end = first_sample_ + next;
    samples_in_progress_.store(next);
    trace_camera_samples(camera, begin, end, arena);
    // Between passes, with no sample running: what the integrator learns (path guiding's
    // tree) is folded in one thread, in a fixed order, and reported.
    if (!cancel_.load()) {
        integrator_->end_pass(begin, end);
        report_guiding();
    }
    if (!cancel_.load() && film_->tracks_prefixes() && (next & (next - 1)) == 0) check_convergence(s, next);
    if (light_paths_ > 0 && !cancel_.load()) {
        trace_light_paths(camera, begin, end, arena);
        if (!cancel_.load()) {
            film_->publish_all(end - first_sample_);
            update_serial_.fetch_add(1);
        }
    }
    if (!cancel_.load()) {
        film_->set_sample_range(first_sample_, end);
        samples_done_.store(next);
    }
}

void Renderer::check_convergence(const RenderSettings& s, uint32_t next) {
    // The samplers' gains (independent samples have G = 1, nothing to measure), shown by the
    // error pass (films with light paths publish after their light paths), and adaptive
    // sampling's check, which stops on s/√n alone.
    if (s.sampler->structure != SampleStructure::Independent) {
        film_->estimate_errors();
        if (light_paths_ == 0) {
            film_->publish_everything();
            update_serial_.fetch_add(1);
        }
    }
    if (adaptive_.checks_at(next, last_sample_ - first_sample_))
        stop_converged_pixels(*film_, adaptive_, stopped_);
}

void Renderer::trace_camera_samples(const Camera& camera, uint32_t begin, uint32_t end,
                                    tbb::task_arena& arena) {
    const PixelRegion& region = film_->region();
    const PixelFilter& filter = film_->filter();
    const Sampler& sampler = *sampler_;
    const Integrator& integrator = *integrator_;
    const RenderScene& scene = *render_scene_;
    const bool motion = scene.has_motion();
    const FilmLayout& layout = film_->layout();
    const uint32_t stride = film_->sums_stride();
    const uint32_t tile_side = stopped_.empty() ? kTileSize : kAdaptiveTileSize;
    arena.execute([&] {
        parallel_for_tile(tbb::blocked_range2d<uint32_t>(region.y, region.y + region.height, tile_side,
                                                         region.x, region.x + region.width, tile_side),
                          [&](const tbb::blocked_range2d<uint32_t>& tile) {
                              uint64_t rays = 0, pixel_samples = 0, dropped = 0, clamped = 0;
                              // One pixel's sums (radiance, alpha, extra passes) and one sample's extra
                              // values.
                              std::vector<FilmSum> sums(stride);
                              std::vector<float> extra(layout.extra_channels());
                              for (uint32_t y = tile.rows().begin(); y < tile.rows().end(); ++y) {
                                  for (uint32_t x = tile.cols().begin(); x < tile.cols().end(); ++x) {
                                      if (cancel_.load(std::memory_order_relaxed)) break;
                                      const size_t p = region.index(x, y);
                                      // A pixel adaptive sampling stopped is done with this pass too.
                                      if (!stopped_.empty() && stopped_[p]) {
                                          pixel_samples += end - begin;
                                          continue;
                                      }
                                      film_->load_sums(p, sums.data());
                                      uint32_t i = begin;
                                      for (; i < end; ++i) {
                                          // Per sample, not per pixel: one sample of a 1024-bounce path is
                                          // already long, a pass holds up to 64 of them.
                                          if (cancel_.load(std::memory_order_relaxed)) break;
                                          const PixelSample ps{x, y, i};
                                          const Vec2 offset = filter.sample(sampler.get_2d(ps, kDimFilter));
                                          // The lens pair is drawn only by a thin-lens camera, so pinhole
                                          // renders do exactly the work they did before.
                                          const Vec2 lens = camera.has_aperture()
                                                                ? sampler.get_2d(ps, kDimLens)
                                                                : Vec2{0.5f, 0.5f};
                                          CameraRay ray = camera.generate_ray(
                                              static_cast<float>(x) + 0.5f + offset.x,
                                              static_cast<float>(y) + 0.5f + offset.y, lens);
                                          // Drawn only with motion, so static renders stay bit-identical.
                                          if (motion) ray.time = sampler.get_1d(ps, kDimTime);
                                          std::fill(extra.begin(), extra.end(), 0.0f);
                                          PassValues passes(&layout, extra.data(), &camera);
                                          const RadianceSample r =
                                              integrator.estimate(scene, sampler, ps, ray, passes, rays);
                                          // A NaN or Inf sample would poison the pixel forever: it is
                                          // dropped (0), counted, and reported when the render ends.
                                          if (is_finite(r.radiance) && std::isfinite(r.alpha) &&
                                              std::all_of(extra.begin(), extra.end(),
                                                          [](float v) { return std::isfinite(v); })) {
                                              if (film_->add_sample(sums.data(), /*sample_index=*/i,
                                                                    r.radiance, r.alpha, extra.data()))
                                                  ++clamped;
                                          } else {
                                              ++dropped;
                                          }
                                      }
                                      // A pixel cancelled mid-pass keeps its previous, complete sum.
                                      if (i < end) break;
                                      film_->store_sums(p, sums.data(), end - first_sample_);
                                      pixel_samples += end - begin;
                                  }
                              }
                              rays_.fetch_add(rays, std::memory_order_relaxed);
                              dropped_samples_.fetch_add(dropped, std::memory_order_relaxed);
                              clamped_samples_.fetch_add(clamped, std::memory_order_relaxed);
                              // Published (films without light paths) before the samples are
                              // counted: a progress that shows them has the serial of their pixels.
                              if (light_paths_ == 0) {
                                  film_->publish(tile.cols().begin(), tile.cols().end(), tile.rows().begin(),
                                                 tile.rows().end());
                                  update_serial_.fetch_add(1);
                              }
                              pixel_samples_done_.fetch_add(pixel_samples);
                          });
    });
}

void Renderer::trace_light_paths(const Camera& camera, uint32_t begin, uint32_t end, tbb::task_arena& arena) {
    const uint32_t frame_width = film_->frame_width();
    const uint64_t paths = light_paths_;
    const uint64_t chunks = (paths + kLightPathChunk - 1) / kLightPathChunk;
    std::vector<std::vector<Splat>> batch(kChunksPerBatch);
    for (uint32_t i = begin; i < end; ++i) {
        for (uint64_t first = 0; first < chunks; first += kChunksPerBatch) {
            if (cancel_.load()) return;
            const uint64_t last = std::min<uint64_t>(chunks, first + kChunksPerBatch);
            arena.execute([&] {
                tbb::parallel_for(first, last, [&](uint64_t chunk) {
                    std::vector<Splat>& out = batch[chunk - first];
                    out.clear();
                    uint64_t rays = 0;
                    const uint64_t k_end = std::min(paths, (chunk + 1) * kLightPathChunk);
                    for (uint64_t k = chunk * kLightPathChunk; k < k_end; ++k) {
                        const PixelSample path{static_cast<uint32_t>(k % frame_width),
                                               static_cast<uint32_t>(k / frame_width), i};
                        integrator_->trace_light_path(*render_scene_, *sampler_, camera, *film_, path, out,
                                                      rays);
                    }
                    rays_.fetch_add(rays, std::memory_order_relaxed);
                    pixel_samples_done_.fetch_add(k_end - chunk * kLightPathChunk, std::memory_order_relaxed);
                });
            });
            uint64_t clamped = 0;
            for (uint64_t chunk = first; chunk < last; ++chunk)
                dropped_samples_.fetch_add(film_->add_splats(batch[chunk - first], &clamped),
                                           std::memory_order_relaxed);
            clamped_samples_.fetch_add(clamped, std::memory_order_relaxed);
        }
    }
}

}  // namespace stratum
