#include "render/renderer.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/memory_budget.h"
#include "film/pixel_filter.h"
#include "integrators/integrator.h"
#include "integrators/light_tracer.h"
#include "sampling/dimensions.h"
#include "sampling/sampler_registry.h"

namespace stratum {

namespace {

constexpr uint32_t kTileSize = 16;
constexpr uint32_t kMaxPassSamples = 64;
// Light tracing: particles are traced in chunks of consecutive particle indices, a batch of
// chunks in parallel; each chunk collects its splats, and the batch's chunks are added to the
// film in chunk order, so the sums do not depend on the thread count or scheduling. A batch
// holds 16384 particles' splats: at most (max_bounces + 1) connections × 16 pixels each.
constexpr uint32_t kParticleChunk = 256;
constexpr uint32_t kChunksPerBatch = 64;

using Clock = std::chrono::steady_clock;

// Index of full-frame pixel (x, y) in the region's buffers (rows bottom to top).
size_t pixel_index(const PixelRegion& region, uint32_t x, uint32_t y) {
    return static_cast<size_t>(y - region.y) * region.width + (x - region.x);
}

// A pixel's running sum of radiance samples. In double: a float sum of samples near FLT_MAX
// (an emitter of strength 3e38 seen directly) overflows to Inf although their mean is finite.
struct RadianceSum {
    double r = 0, g = 0, b = 0;
    void add(const Rgb& c) {
        r += c.r;
        g += c.g;
        b += c.b;
    }
};

bool is_finite(const Rgb& c) { return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b); }

double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

Renderer::Renderer(Scene scene) : scene_(std::move(scene)) {}

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
    if (!scene_.camera) return "the scene has no camera";
    if (!find_sampler(settings_.sampler)) return "unknown sampler '" + settings_.sampler + "'";
    PixelRegion region;
    const std::string crop_error = crop_region(settings_, &region);
    if (!crop_error.empty()) return crop_error;
    region_ = region;
    {
        std::lock_guard lock(notices_mutex_);
        notices_.clear();
    }
    dropped_samples_.store(0);
    const std::unique_ptr<Integrator> integrator =
        find_integrator(settings_.integrator)->create(integrator_settings(settings_));
    for (const std::string& notice : integrator->notices(scene_)) add_notice(notice);
    // A scene already built keeps its build notices for every render of it.
    if (render_scene_)
        for (const std::string& notice : render_scene_->notices()) add_notice(notice);
    width_ = region.width;
    height_ = region.height;
    // Work per sample index: one camera sample per pixel of the region, plus, when light
    // tracing, one particle per pixel of the full frame.
    const bool light_tracing = dynamic_cast<const LightTracer*>(integrator.get()) != nullptr;
    work_per_sample_ = static_cast<double>(width_) * height_;
    if (light_tracing) work_per_sample_ += static_cast<double>(settings_.width) * settings_.height;
    // The film per pixel: the image (RGBA floats) and, while rendering, the sums of run() (radiance
    // and alpha in double, a sample count, the light tracer's splats). A 65536 x 20000 render asks
    // for 63.5 GiB: refused here, naming the size, rather than granted by overcommit and OOM-killed.
    const double film_bytes =
        static_cast<double>(width_) * height_ *
        static_cast<double>(4 * sizeof(float) + sizeof(RadianceSum) + sizeof(double) + sizeof(uint32_t) +
                            (light_tracing ? 3 * sizeof(double) : 0));
    if (film_bytes > memory_budget_bytes())
        return "a " + std::to_string(width_) + " x " + std::to_string(height_) + " pixel render needs " +
               gib(film_bytes) + " for its film, more than half of this machine's " +
               gib(physical_memory_bytes()) + " of memory";
    image_.assign(static_cast<size_t>(width_) * height_ * 4, 0.0f);
    cancel_.store(false);
    done_.store(false);
    samples_done_.store(0);
    samples_total_.store(settings_.samples);
    rays_.store(0);
    pixel_samples_done_.store(0);
    {
        std::lock_guard lock(state_mutex_);
        render_seconds_ = 0;
        cancelled_ = false;
        error_.clear();
    }
    worker_ = std::thread([this] { run(); });
    return {};
}

void Renderer::run() {
    const RenderSettings s = settings_;
    const PixelRegion region = region_;
    std::string error;
    try {
        tbb::task_arena arena(s.threads == 0 ? tbb::task_arena::automatic : static_cast<int>(s.threads));
        if (!render_scene_) {
            const auto t0 = Clock::now();
            arena.execute([&] { render_scene_ = std::make_unique<RenderScene>(scene_, &cancel_); });
            std::lock_guard lock(state_mutex_);
            build_seconds_ = seconds_since(t0);
            for (const std::string& notice : render_scene_->notices()) add_notice(notice);
        }
        const uint64_t refused_before = render_scene_->refused_rays();
        const auto t0 = Clock::now();
        {
            std::lock_guard lock(state_mutex_);
            render_start_ = t0;
            rendering_ = true;
        }
        const std::unique_ptr<Sampler> sampler =
            find_sampler(s.sampler)->create(SamplerSettings{s.samples, s.seed, s.width, s.height});
        const std::unique_ptr<Integrator> integrator =
            find_integrator(s.integrator)->create(integrator_settings(s));
        FilterType filter_type = FilterType::BlackmanHarris;
        parse_filter_type(s.filter_type, &filter_type);
        const PixelFilter filter(filter_type, s.filter_width);
        // Camera and sampler see the full frame and full-frame pixel coordinates, so a pixel of a
        // border render is bit-identical to the same pixel of the full render.
        const Camera camera(*scene_.camera, s.width, s.height);
        const bool motion = render_scene_->has_motion();
        // Light tracing adds a particle pass after each camera pass (the Integrator interface
        // is per camera ray; the particle part is the light tracer's own).
        const auto* light_tracer = dynamic_cast<const LightTracer*>(integrator.get());
        std::vector<RadianceSum> sums(static_cast<size_t>(region.width) * region.height);
        std::vector<double> alpha_sums(sums.size(), 0.0);
        std::vector<uint32_t> counts(sums.size(), 0);
        std::vector<double> splat_sums(light_tracer ? 3 * sums.size() : 0, 0.0);

        uint32_t begin = 0;
        while (begin < s.samples && !cancel_.load()) {
            const uint32_t end = std::min({s.samples, std::max(1u, 2 * begin), begin + kMaxPassSamples});
            arena.execute([&] {
                tbb::parallel_for(
                    tbb::blocked_range2d<uint32_t>(region.y, region.y + region.height, kTileSize, region.x,
                                                   region.x + region.width, kTileSize),
                    [&](const tbb::blocked_range2d<uint32_t>& tile) {
                        uint64_t rays = 0, pixel_samples = 0, dropped = 0;
                        for (uint32_t y = tile.rows().begin(); y < tile.rows().end(); ++y) {
                            for (uint32_t x = tile.cols().begin(); x < tile.cols().end(); ++x) {
                                if (cancel_.load(std::memory_order_relaxed)) break;
                                const size_t p = pixel_index(region, x, y);
                                RadianceSum sum = sums[p];
                                double alpha_sum = alpha_sums[p];
                                uint32_t i = begin;
                                for (; i < end; ++i) {
                                    // Per sample, not per pixel: one sample of a 1024-bounce
                                    // path is already long, a pass holds up to 64 of them.
                                    if (cancel_.load(std::memory_order_relaxed)) break;
                                    const PixelSample ps{x, y, i};
                                    const Vec2 offset = filter.sample(sampler->get_2d(ps, kDimFilter));
                                    // The lens pair is drawn only by a thin-lens camera, so
                                    // pinhole renders do exactly the work they did before.
                                    const Vec2 lens = camera.has_aperture() ? sampler->get_2d(ps, kDimLens)
                                                                            : Vec2{0.5f, 0.5f};
                                    CameraRay ray =
                                        camera.generate_ray(static_cast<float>(x) + 0.5f + offset.x,
                                                            static_cast<float>(y) + 0.5f + offset.y, lens);
                                    // Drawn only with motion, so static renders stay bit-identical.
                                    if (motion) ray.time = sampler->get_1d(ps, kDimTime);
                                    const RadianceSample r =
                                        integrator->radiance(*render_scene_, *sampler, ps, ray, rays);
                                    // A NaN or Inf sample would poison the pixel forever: it
                                    // is dropped (0), counted, and reported when the render ends.
                                    if (is_finite(r.radiance) && std::isfinite(r.alpha)) {
                                        sum.add(r.radiance);
                                        alpha_sum += r.alpha;
                                    } else {
                                        ++dropped;
                                    }
                                }
                                // A pixel cancelled mid-pass keeps its previous, complete sum.
                                if (i < end) break;
                                sums[p] = sum;
                                alpha_sums[p] = alpha_sum;
                                counts[p] = end;
                                pixel_samples += end - begin;
                            }
                        }
                        rays_.fetch_add(rays, std::memory_order_relaxed);
                        pixel_samples_done_.fetch_add(pixel_samples, std::memory_order_relaxed);
                        dropped_samples_.fetch_add(dropped, std::memory_order_relaxed);
                        if (light_tracer) return;  // published with the particles, below
                        std::shared_lock lock(image_mutex_);
                        for (uint32_t y = tile.rows().begin(); y < tile.rows().end(); ++y) {
                            for (uint32_t x = tile.cols().begin(); x < tile.cols().end(); ++x) {
                                const size_t p = pixel_index(region, x, y);
                                if (counts[p] == 0) continue;
                                const double n = counts[p];
                                float* px = &image_[4 * p];
                                px[0] = saturate_to_float(sums[p].r / n);
                                px[1] = saturate_to_float(sums[p].g / n);
                                px[2] = saturate_to_float(sums[p].b / n);
                                px[3] = saturate_to_float(alpha_sums[p] / n);
                            }
                        }
                        update_serial_.fetch_add(1);
                    });
            });
            if (light_tracer && !cancel_.load()) {
                trace_particles(*light_tracer, *sampler,
                                ParticleFilm{camera, filter, region, s.width, s.height,
                                             LightTracer::sky_probability(*render_scene_)},
                                begin, end, arena, splat_sums);
                if (!cancel_.load()) {
                    std::unique_lock lock(image_mutex_);
                    // Pixel = camera-ray part mean + splat sum / sample indices done.
                    for (size_t p = 0; p < sums.size(); ++p) {
                        const double n = end;
                        float* px = &image_[4 * p];
                        px[0] = saturate_to_float((sums[p].r + splat_sums[3 * p]) / n);
                        px[1] = saturate_to_float((sums[p].g + splat_sums[3 * p + 1]) / n);
                        px[2] = saturate_to_float((sums[p].b + splat_sums[3 * p + 2]) / n);
                        px[3] = saturate_to_float(alpha_sums[p] / n);
                    }
                    update_serial_.fetch_add(1);
                }
            }
            if (!cancel_.load()) samples_done_.store(end);
            begin = end;
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

void Renderer::trace_particles(const LightTracer& tracer, const Sampler& sampler, const ParticleFilm& film,
                               uint32_t begin, uint32_t end, tbb::task_arena& arena,
                               std::vector<double>& splat_sums) {
    const uint32_t frame_width = film.frame_width;
    const uint64_t particles = static_cast<uint64_t>(frame_width) * film.frame_height;
    const uint64_t chunks = (particles + kParticleChunk - 1) / kParticleChunk;
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
                    const uint64_t k_end = std::min(particles, (chunk + 1) * kParticleChunk);
                    for (uint64_t k = chunk * kParticleChunk; k < k_end; ++k) {
                        const PixelSample particle{static_cast<uint32_t>(k % frame_width),
                                                   static_cast<uint32_t>(k / frame_width), i};
                        tracer.trace_particle(*render_scene_, sampler, particle, film, out, rays);
                    }
                    rays_.fetch_add(rays, std::memory_order_relaxed);
                    pixel_samples_done_.fetch_add(k_end - chunk * kParticleChunk, std::memory_order_relaxed);
                });
            });
            for (uint64_t chunk = first; chunk < last; ++chunk) {
                for (const Splat& sp : batch[chunk - first]) {
                    if (!is_finite(sp.value)) {
                        dropped_samples_.fetch_add(1, std::memory_order_relaxed);
                        continue;
                    }
                    splat_sums[3 * sp.pixel] += sp.value.r;
                    splat_sums[3 * sp.pixel + 1] += sp.value.g;
                    splat_sums[3 * sp.pixel + 2] += sp.value.b;
                }
            }
        }
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
    p.done = done_.load();
    p.cancelled = cancelled_;
    p.samples_done = samples_done_.load();
    p.samples_total = samples_total_.load();
    p.update_serial = update_serial_.load();
    p.rays = static_cast<double>(rays_.load());
    p.build_seconds = build_seconds_;
    p.render_seconds = rendering_ ? seconds_since(render_start_) : render_seconds_;
    const double pixel_samples_total = work_per_sample_ * p.samples_total;
    p.fraction_done =
        pixel_samples_total > 0 ? static_cast<double>(pixel_samples_done_.load()) / pixel_samples_total : 0.0;
    p.error = error_;
    return p;
}

void Renderer::read_pixels(float* rgba) const {
    std::unique_lock lock(image_mutex_);
    std::copy(image_.begin(), image_.end(), rgba);
}

}  // namespace stratum
