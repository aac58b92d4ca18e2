// What a render reports (render/renderer.h): its progress, read from any thread while it runs,
// with the counters its features fill in (render/progress_counters.h: the light tree, the
// radiosity solve, path guiding's tree), and its notices: what it cannot show and why.
#include <cmath>
#include <string>

#include "integrators/integrator.h"
#include "render/renderer.h"

namespace stratum {

void Renderer::report_radiosity() {
    const RadiosityReport* radiosity = integrator_->radiosity_report();
    if (!radiosity) return;
    {
        std::lock_guard lock(state_mutex_);
        counters_[ProgressCounter::RadiosityPatches] = static_cast<double>(radiosity->patches);
        counters_[ProgressCounter::RadiosityBytes] = radiosity->peak_bytes;
        counters_[ProgressCounter::RadiositySeconds] =
            radiosity->form_factor_seconds + radiosity->solve_seconds;
        counters_[ProgressCounter::RadiosityIterations] = static_cast<double>(radiosity->iterations.size());
        radiosity_history_ = radiosity->iterations;
    }
    if (radiosity->converged || radiosity->iterations.empty()) return;
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
    add_notice("radiosity: the solve stopped after " + std::to_string(radiosity->iterations.size()) +
               " iterations without reaching radiosity_tolerance (its last Delta E is " +
               std::to_string(radiosity->iterations.back().relative) + " of the mean radiance" + reach +
               "): the image shows that iterate");
}

void Renderer::report_guiding() {
    if (const GuidingReport* guiding = integrator_->guiding_report()) {
        std::lock_guard lock(state_mutex_);
        counters_[ProgressCounter::GuidingNodes] = static_cast<double>(guiding->nodes);
        counters_[ProgressCounter::GuidingBytes] = static_cast<double>(guiding->bytes);
    }
}

void Renderer::report_light_tree(LightSelection selection) {
    // The light tree, if this render chooses lights by it and prepare() built it (a tree an
    // earlier render built is reported only when this one uses it too).
    const LightSet& lights = render_scene_->lights();
    const auto tree = lights.tree_report();
    if (tree && lights.resolve(selection) == LightSelection::Tree) {
        std::lock_guard lock(state_mutex_);
        counters_[ProgressCounter::LightTreeSeconds] = tree->seconds;
        counters_[ProgressCounter::LightTreeBytes] = static_cast<double>(tree->bytes);
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
    p.counters = counters_;
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

}  // namespace stratum
