// The renderer's life (render/renderer.h): start() checks the settings against the scene and
// makes the film; the render thread, run(), brings the render scene up to date, prepares the
// integrator, renders the passes (render/render_passes.cpp) and ends; the film is read or
// exchanged after. What it reports is in render/render_reports.cpp.
#include "render/renderer.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>

#include "core/memory_budget.h"
#include "integrators/integrator.h"
#include "integrators/shadow_catcher.h"
#include "sampling/sampler_registry.h"

namespace stratum {

Renderer::Renderer(std::shared_ptr<const LiveScene> scene) : live_(std::move(scene)) {}

Renderer::~Renderer() {
    cancel();
    join();
}

void Renderer::join() {
    if (worker_.joinable()) worker_.join();
}

double Renderer::seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
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
    for (const std::string& notice :
         unsplit_catcher_notices(scene_, *integrator, settings_.integrator->info.name))
        add_notice(notice);
    if (settings_.lightgroups > 0 && !integrator->writes_light_groups())
        add_notice("the " + std::string(settings_.integrator->info.name) +
                   " integrator writes no light groups (only 'path' does): their passes are black");
    // A scene already built keeps its build notices for every render of it.
    if (render_scene_)
        for (const std::string& notice : render_scene_->notices()) add_notice(notice);
    const uint64_t light_paths = integrator->light_paths_per_sample(settings_.width, settings_.height);
    AdaptiveSampling adaptive;
    const std::string adaptive_error = resolve_adaptive(light_paths, first_sample, last_sample, &adaptive);
    if (!adaptive_error.empty()) return adaptive_error;
    const std::string film_error = make_film(
        region, light_paths, adaptive.enabled,
        catcher_combined_shown(scene_, *integrator, settings_.passes, settings_.estimator.film_transparent),
        settings_.lightgroups);
    if (!film_error.empty()) return film_error;
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
    reset_progress(last_sample - first_sample);
    worker_ = std::thread([this] { run(); });
    return {};
}

std::string Renderer::resolve_adaptive(uint64_t light_paths, uint32_t first_sample, uint32_t last_sample,
                                       AdaptiveSampling* out) {
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
    *out = adaptive;
    return {};
}

std::string Renderer::make_film(const PixelRegion& region, uint64_t light_paths, bool adaptive,
                                CatcherCombined catcher, uint32_t lightgroups) {
    // The film of a 65536 x 20000 render asks for 63.5 GiB: refused here, naming the size, rather
    // than granted by overcommit and OOM-killed.
    const double film_bytes =
        static_cast<double>(region.pixel_count()) *
        (Film::bytes_per_pixel(settings_.passes, light_paths > 0, adaptive, catcher, lightgroups) +
         (adaptive ? 1 : 0));
    if (film_bytes > memory_budget_bytes())
        return "a " + std::to_string(region.width) + " x " + std::to_string(region.height) +
               " pixel render needs " + gib(film_bytes) + " for its film, more than half of this machine's " +
               gib(physical_memory_bytes()) + " of memory";
    film_ = std::make_unique<Film>(region, settings_.width, settings_.height,
                                   PixelFilter(settings_.filter_type, settings_.filter_width),
                                   settings_.passes, light_paths > 0, adaptive, catcher, lightgroups);
    return {};
}

void Renderer::reset_progress(uint32_t samples) {
    cancel_.store(false);
    done_.store(false);
    samples_done_.store(0);
    samples_in_progress_.store(0);
    samples_total_.store(samples);
    rays_.store(0);
    pixel_samples_done_.store(0);
    std::lock_guard lock(state_mutex_);
    render_seconds_ = 0;
    counters_ = {};
    radiosity_history_.clear();
    cancelled_ = false;
    error_.clear();
}

void Renderer::run() {
    const RenderSettings s = settings_;
    std::string error;
    try {
        tbb::task_arena arena(s.threads == 0 ? tbb::task_arena::automatic : static_cast<int>(s.threads));
        const bool scene_kept = bring_scene_up_to_date(s, arena);
        const uint64_t refused_before = render_scene_->refused_rays();
        const Clock::time_point t0 = Clock::now();
        {
            std::lock_guard lock(state_mutex_);
            render_start_ = t0;
            rendering_ = true;
        }
        prepare_integrator(s, scene_kept, arena);
        // Camera and sampler see the full frame and full-frame pixel coordinates, so a pixel of a
        // border render is bit-identical to the same pixel of the full render.
        const Camera camera(*scene_.camera, s.width, s.height);
        render_passes(s, camera, arena);
        report_dropped(render_scene_->refused_rays() - refused_before);
        std::lock_guard lock(state_mutex_);
        render_seconds_ = seconds_since(t0);
    } catch (const RenderScene::BuildCancelled&) {
        // Esc during the BVH build: the render ends cancelled, with nothing to report.
    } catch (const std::exception& e) {
        error = e.what();
    }
    finish(error);
}

bool Renderer::bring_scene_up_to_date(const RenderSettings& s, tbb::task_arena& arena) {
    // Edits since the last render: applied in place where the built scene can take them
    // (RenderScene::update), else the scene is built anew.
    const bool scene_kept = render_scene_ && !pending_.rebuild && pending_.instances.empty() &&
                            !pending_.materials && !pending_.lights && !pending_.world;
    if (render_scene_ && pending_.any()) {
        const Clock::time_point t0 = Clock::now();
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
        const Clock::time_point t0 = Clock::now();
        arena.execute([&] { render_scene_ = std::make_unique<RenderScene>(scene_, &cancel_, s.bvh); });
        std::lock_guard lock(state_mutex_);
        build_seconds_ = seconds_since(t0);
        for (const std::string& notice : render_scene_->notices()) add_notice(notice);
    }
    pending_ = {};
    return scene_kept;
}

void Renderer::prepare_integrator(const RenderSettings& s, bool scene_kept, tbb::task_arena& arena) {
    const bool adopted = scene_kept && previous_integrator_ && integrator_->adopt(*previous_integrator_);
    previous_integrator_.reset();
    if (!adopted) arena.execute([&] { integrator_->prepare(*render_scene_, cancel_); });
    report_radiosity();
    report_guiding();
    report_light_tree(s.estimator.light_selection);
}

void Renderer::finish(const std::string& error) {
    std::lock_guard lock(state_mutex_);
    rendering_ = false;
    cancelled_ = cancel_.load();
    error_ = error;
    done_.store(true);
    update_serial_.fetch_add(1);
    done_cv_.notify_all();
}

bool Renderer::wait(int timeout_ms) {
    std::unique_lock lock(state_mutex_);
    return done_cv_.wait_for(lock, std::chrono::milliseconds(std::max(0, timeout_ms)),
                             [&] { return done_.load(); });
}

void Renderer::read_pixels(float* rgba) const {
    if (film_) film_->read(Pass::Combined, rgba);
}

bool Renderer::read_pass(Pass pass, float* out) const { return film_ && film_->read(pass, out); }
bool Renderer::read_lightgroup(uint32_t group, float* out) const {
    return film_ && film_->read_lightgroup(group, out);
}

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
