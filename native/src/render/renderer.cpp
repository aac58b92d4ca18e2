#include "render/renderer.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/memory_budget.h"
#include "integrators/integrator.h"
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

using Clock = std::chrono::steady_clock;

bool is_finite(const Rgb& c) { return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b); }

double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

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

Renderer::Renderer(std::shared_ptr<const LiveScene> scene) : live_(std::move(scene)) {}

Renderer::~Renderer() {
    cancel();
    join();
}

void Renderer::join() {
    if (worker_.joinable()) worker_.join();
}

std::string Renderer::start() {
    if (running()) return "a render is already running";
    join();
    pending_.merge(live_->sync(&scene_, &synced_));
    // A rebuilt scene description moves the meshes the built scene points into; another BVH
    // layout is another build.
    if (pending_.rebuild || (render_scene_ && render_scene_->bvh_layout() != settings_.bvh))
        render_scene_.reset();
    if (!scene_.camera) return "the scene has no camera";
    PixelRegion region;
    const std::string crop_error = crop_region(settings_, &region);
    if (!crop_error.empty()) return crop_error;
    uint32_t first_sample = 0, last_sample = 0;
    const std::string range_error = sample_range(settings_, &first_sample, &last_sample);
    if (!range_error.empty()) return range_error;
    {
        std::lock_guard lock(notices_mutex_);
        notices_.clear();
    }
    dropped_samples_.store(0);
    clamped_samples_.store(0);
    std::unique_ptr<Integrator> integrator = settings_.integrator->create(settings_.estimator);
    for (const std::string& notice : integrator->notices(scene_)) add_notice(notice);
    // A scene already built keeps its build notices for every render of it.
    if (render_scene_)
        for (const std::string& notice : render_scene_->notices()) add_notice(notice);
    const uint64_t light_paths = integrator->light_paths_per_sample(settings_.width, settings_.height);
    AdaptiveSampling adaptive = AdaptiveSampling::resolve(settings_.adaptive, settings_.samples);
    if (adaptive.enabled && light_paths > 0) {
        adaptive.enabled = false;
        add_notice("Adaptive sampling is off for the " + std::string(settings_.integrator->info.name) +
                   " integrator: its light paths reach every pixel in every pass, so every pixel takes all "
                   "samples.");
    }
    if (adaptive.enabled && settings_.sampler->structure == SampleStructure::WholeCount)
        add_notice("The " + std::string(settings_.sampler->info.name) +
                   " sampler lays its points out for the whole sample count: a pixel adaptive sampling stops "
                   "early holds part of them, without their stratification (progressive samplers such as "
                   "sobol keep a net at every power of two).");
    // A pixel stops on the error of its whole sequence so far: a subset has no such sequence.
    if (adaptive.enabled && (first_sample != 0 || last_sample != settings_.samples))
        return "adaptive sampling decides per pixel from its first sample on, so it cannot render the sample "
               "subset sample_offset = " +
               std::to_string(settings_.sample_offset) +
               ", sample_count = " + std::to_string(settings_.sample_count) +
               ": turn use_adaptive_sampling off, or render all samples";
    // The film of a 65536 x 20000 render asks for 63.5 GiB: refused here, naming the size, rather
    // than granted by overcommit and OOM-killed.
    const double film_bytes = static_cast<double>(region.pixel_count()) *
                              (Film::bytes_per_pixel(settings_.passes, light_paths > 0, adaptive.enabled) +
                               (adaptive.enabled ? 1 : 0));
    if (film_bytes > memory_budget_bytes())
        return "a " + std::to_string(region.width) + " x " + std::to_string(region.height) +
               " pixel render needs " + gib(film_bytes) + " for its film, more than half of this machine's " +
               gib(physical_memory_bytes()) + " of memory";
    film_ = std::make_unique<Film>(region, settings_.width, settings_.height,
                                   PixelFilter(settings_.filter_type, settings_.filter_width),
                                   settings_.passes, light_paths > 0, adaptive.enabled);
    adaptive_ = adaptive;
    if (settings_.sampler->screen_space) adaptive_.block = kScreenBlock;
    stopped_.assign(adaptive.enabled ? region.pixel_count() : 0, 0);
    previous_integrator_ = std::move(integrator_);
    integrator_ = std::move(integrator);
    sampler_ = settings_.sampler->create(
        SamplerSettings{settings_.samples, settings_.seed, settings_.width, settings_.height});
    width_ = region.width;
    height_ = region.height;
    light_paths_ = light_paths;
    first_sample_ = first_sample;
    last_sample_ = last_sample;
    // Work per sample index: one camera sample per pixel of the region, plus the light paths.
    work_per_sample_ = static_cast<double>(region.pixel_count()) + static_cast<double>(light_paths);
    cancel_.store(false);
    done_.store(false);
    samples_done_.store(0);
    samples_in_progress_.store(0);
    samples_total_.store(last_sample - first_sample);
    rays_.store(0);
    pixel_samples_done_.store(0);
    {
        std::lock_guard lock(state_mutex_);
        render_seconds_ = 0;
        light_tree_seconds_ = light_tree_bytes_ = 0;
        radiosity_patches_ = radiosity_bytes_ = radiosity_seconds_ = radiosity_iterations_ = 0;
        guiding_nodes_ = guiding_bytes_ = 0;
        radiosity_history_.clear();
        cancelled_ = false;
        error_.clear();
    }
    worker_ = std::thread([this] { run(); });
    return {};
}

void Renderer::run() {
    const RenderSettings s = settings_;
    std::string error;
    try {
        tbb::task_arena arena(s.threads == 0 ? tbb::task_arena::automatic : static_cast<int>(s.threads));
        // Edits since the last render: applied in place where the built scene can take them
        // (RenderScene::update), else the scene is built anew.
        // Only the camera changed since the last render (or nothing): what the last integrator
        // prepared for this render scene may stand (Integrator::adopt).
        const bool scene_kept = render_scene_ && !pending_.rebuild && pending_.instances.empty() &&
                                !pending_.materials && !pending_.lights && !pending_.world;
        if (render_scene_ && pending_.any()) {
            const auto t0 = Clock::now();
            bool updated = false;
            arena.execute([&] {
                try {
                    updated = render_scene_->update(scene_, pending_, &cancel_);
                } catch (...) {
                    // A half-applied update must not be rendered or updated again.
                    render_scene_.reset();
                    throw;
                }
            });
            if (!updated) render_scene_.reset();
            std::lock_guard lock(state_mutex_);
            build_seconds_ = seconds_since(t0);
        }
        if (!render_scene_) {
            const auto t0 = Clock::now();
            arena.execute([&] { render_scene_ = std::make_unique<RenderScene>(scene_, &cancel_, s.bvh); });
            std::lock_guard lock(state_mutex_);
            build_seconds_ = seconds_since(t0);
            for (const std::string& notice : render_scene_->notices()) add_notice(notice);
        }
        pending_ = {};
        const uint64_t refused_before = render_scene_->refused_rays();
        const auto t0 = Clock::now();
        {
            std::lock_guard lock(state_mutex_);
            render_start_ = t0;
            rendering_ = true;
        }
        const bool adopted = scene_kept && previous_integrator_ && integrator_->adopt(*previous_integrator_);
        previous_integrator_.reset();
        if (!adopted) arena.execute([&] { integrator_->prepare(*render_scene_, cancel_); });
        if (const RadiosityReport* radiosity = integrator_->radiosity_report()) {
            {
                std::lock_guard lock(state_mutex_);
                radiosity_patches_ = static_cast<double>(radiosity->patches);
                radiosity_bytes_ = radiosity->peak_bytes;
                radiosity_seconds_ = radiosity->form_factor_seconds + radiosity->solve_seconds;
                radiosity_iterations_ = static_cast<double>(radiosity->iterations.size());
                radiosity_history_ = radiosity->iterations;
            }
            if (!radiosity->converged && !radiosity->iterations.empty()) {
                const double projected = radiosity->projected_iterations;
                const std::string reach =
                    projected <= 0.0 ? ""
                    : std::isinf(projected)
                        ? ": it no longer shrinks (a closed space whose surfaces reflect all the light they "
                          "receive has no finite solution)"
                        : ": at the rate it shrinks it would need about " +
                              std::to_string(static_cast<uint64_t>(projected)) +
                              " iterations, more than the solver's cap (surfaces that reflect almost all "
                              "the light converge that slowly)";
                add_notice("radiosity: the solve stopped after " +
                           std::to_string(radiosity->iterations.size()) +
                           " iterations without reaching radiosity_tolerance (its last Delta E is " +
                           std::to_string(radiosity->iterations.back().relative) + " of the mean radiance" +
                           reach + "): the image shows that iterate");
            }
        }
        report_guiding();
        // The light tree, if this render chooses lights by it and prepare() built it (a tree an
        // earlier render built is reported only when this one uses it too).
        const LightSet& lights = render_scene_->lights();
        const auto tree = lights.tree_report();
        if (tree && lights.resolve(s.estimator.light_selection) == LightSelection::Tree) {
            std::lock_guard lock(state_mutex_);
            light_tree_seconds_ = tree->seconds;
            light_tree_bytes_ = static_cast<double>(tree->bytes);
        }
        // Camera and sampler see the full frame and full-frame pixel coordinates, so a pixel of a
        // border render is bit-identical to the same pixel of the full render.
        const Camera camera(*scene_.camera, s.width, s.height);
        // Sample indices [first_sample_, last_sample_); progress counts them from first_sample_.
        // Pass ends stay at powers of two of the count (a subset starting at 0 is the full
        // render's prefix).
        const uint32_t total = last_sample_ - first_sample_;
        uint32_t done = 0;
        while (done < total && !cancel_.load()) {
            const uint32_t next = std::min({total, std::max(done + 1, 2 * done), done + kMaxPassSamples});
            const uint32_t begin = first_sample_ + done, end = first_sample_ + next;
            samples_in_progress_.store(next);
            trace_camera_samples(camera, begin, end, arena);
            // Between passes, with no sample running: what the integrator learns (path guiding's
            // tree) is folded in one thread, in a fixed order, and reported.
            if (!cancel_.load()) {
                integrator_->end_pass(begin, end);
                report_guiding();
            }
            // At a power of two: the samplers' gains (independent samples have G = 1, nothing
            // to measure), shown by the error pass (films with light paths publish below), and
            // adaptive sampling's check, which stops on s/√n alone.
            if (!cancel_.load() && film_->tracks_prefixes() && (next & (next - 1)) == 0) {
                if (s.sampler->structure != SampleStructure::Independent) {
                    film_->estimate_errors();
                    if (light_paths_ == 0) {
                        film_->publish_everything();
                        update_serial_.fetch_add(1);
                    }
                }
                if (adaptive_.checks_at(next, total)) stop_converged_pixels(*film_, adaptive_, stopped_);
            }
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
            done = next;
        }
        report_dropped(render_scene_->refused_rays() - refused_before);
        std::lock_guard lock(state_mutex_);
        render_seconds_ = seconds_since(t0);
    } catch (const RenderScene::BuildCancelled&) {
        // Esc during the BVH build: the render ends cancelled, with nothing to report.
    } catch (const std::exception& e) {
        error = e.what();
    }
    std::lock_guard lock(state_mutex_);
    rendering_ = false;
    cancelled_ = cancel_.load();
    error_ = error;
    done_.store(true);
    update_serial_.fetch_add(1);
    done_cv_.notify_all();
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

void Renderer::report_guiding() {
    if (const GuidingReport* guiding = integrator_->guiding_report()) {
        std::lock_guard lock(state_mutex_);
        guiding_nodes_ = static_cast<double>(guiding->nodes);
        guiding_bytes_ = static_cast<double>(guiding->bytes);
    }
}

void Renderer::add_notice(const std::string& notice) {
    std::lock_guard lock(notices_mutex_);
    notices_ += (notices_.empty() ? "" : "\n") + notice;
}

std::string Renderer::notices() const {
    std::lock_guard lock(notices_mutex_);
    return notices_;
}

void Renderer::report_dropped(uint64_t refused_rays) {
    const uint64_t samples = dropped_samples_.load();
    if (samples > 0) {
        add_notice(std::to_string(samples) +
                   " samples were not finite (NaN or infinite radiance) and were dropped: the "
                   "pixels they belong to are darker there. A value in the scene is beyond what "
                   "floating point carries (e.g. an emitter or light near 3.4e38).");
    }
    const uint64_t clamped = clamped_samples_.load();
    if (clamped > 0) {
        add_notice(std::to_string(clamped) +
                   " samples were brighter than the film sums exactly (3.6e16, or 3.5e13 for a light "
                   "path's splat) and were clamped there: those pixels are darker than the scene's values.");
    }
    if (refused_rays > 0) {
        add_notice(std::to_string(refused_rays) +
                   " rays left the range the ray tracer accepts (an origin far outside the scene, "
                   "or a direction that is not a number) and were treated as missing everything.");
    }
}

bool Renderer::wait(int timeout_ms) {
    std::unique_lock lock(state_mutex_);
    return done_cv_.wait_for(lock, std::chrono::milliseconds(std::max(0, timeout_ms)),
                             [&] { return done_.load(); });
}

RenderProgress Renderer::progress() const {
    std::lock_guard lock(state_mutex_);
    RenderProgress p;
    // The counters in the order that makes one consistent snapshot, samples_done <=
    // samples_average <= samples_in_progress (all loads sequentially consistent). The render
    // thread stores samples_in_progress, then its tiles count their samples, then it stores
    // samples_done: so samples_done is read first (every sample it covers is counted by then) and
    // samples_in_progress last (it covers every sample counted before). The serial is read after
    // the samples: a tile publishes its pixels, then bumps the serial, then counts its samples,
    // so the serial read here covers every sample counted.
    p.samples_done = samples_done_.load();
    const double pixel_samples_done = static_cast<double>(pixel_samples_done_.load());
    p.samples_in_progress = samples_in_progress_.load();
    p.update_serial = update_serial_.load();
    p.done = done_.load();
    p.cancelled = cancelled_;
    p.samples_total = samples_total_.load();
    p.rays = static_cast<double>(rays_.load());
    p.build_seconds = build_seconds_;
    p.light_tree_seconds = light_tree_seconds_;
    p.light_tree_bytes = light_tree_bytes_;
    p.radiosity_patches = radiosity_patches_;
    p.radiosity_bytes = radiosity_bytes_;
    p.guiding_nodes = guiding_nodes_;
    p.guiding_bytes = guiding_bytes_;
    p.radiosity_seconds = radiosity_seconds_;
    p.radiosity_iterations = radiosity_iterations_;
    p.render_seconds = rendering_ ? seconds_since(render_start_) : render_seconds_;
    const double pixel_samples_total = work_per_sample_ * p.samples_total;
    p.fraction_done = pixel_samples_total > 0 ? pixel_samples_done / pixel_samples_total : 0.0;
    // Exact at the end: the work done is then samples_total × work_per_sample_, both integers.
    p.samples_average = work_per_sample_ > 0 ? pixel_samples_done / work_per_sample_ : 0.0;
    p.error = error_;
    return p;
}

std::vector<IterationReport> Renderer::radiosity_iterations() const {
    std::lock_guard lock(state_mutex_);
    return radiosity_history_;
}

void Renderer::read_pixels(float* rgba) const {
    if (film_) film_->read(Pass::Combined, rgba);
}

bool Renderer::read_pass(Pass pass, float* out) const { return film_ && film_->read(pass, out); }

std::vector<uint8_t> Renderer::sums_bytes(std::string* error) const {
    if (running()) {
        *error = "the render is still running: wait for it to end";
        return {};
    }
    if (!film_) {
        *error = "nothing rendered yet: call stratum_renderer_start first";
        return {};
    }
    {
        std::lock_guard lock(state_mutex_);
        // A cancelled pass leaves pixels with different sample counts: no range describes them.
        if (cancelled_ || !error_.empty()) {
            *error = "the render was cancelled or failed: its sums hold no complete sample range";
            return {};
        }
        if (adaptive_.enabled) {
            *error =
                "adaptive sampling stopped pixels at different sample counts: its sums hold no common "
                "sample range";
            return {};
        }
    }
    return film_->sums_bytes();
}

std::string Renderer::add_sums(std::unique_ptr<Film> sums) {
    if (running()) return "the render is still running: wait for it to end";
    {
        std::lock_guard lock(state_mutex_);
        if (film_ && cancelled_)
            return "this renderer's last render was cancelled: its sums hold no complete range";
    }
    if (film_ && adaptive_.enabled)
        return "this renderer's last render stopped pixels at different sample counts (adaptive sampling): "
               "other sums cannot continue it";
    if (film_) return film_->add_sums(*sums);
    film_ = std::move(sums);
    width_ = film_->region().width;
    height_ = film_->region().height;
    update_serial_.fetch_add(1);
    return {};
}

}  // namespace stratum
