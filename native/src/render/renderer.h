// Progressive renderer: runs passes of samples on TBB worker threads in a background thread,
// publishes pixels as tiles finish, stops on cancel.
//
// Passes cover sample ranges [0,1), [1,2), [2,4), [4,8), ... capped at kMaxPassSamples: every
// intermediate image holds a power-of-two-aligned prefix of each pixel's samples, so
// low-discrepancy properties hold at every update (research/samplers.md §5.6). At the pass ends
// that are powers of two, the film estimates each pixel's error (film/error_estimate.h) and
// adaptive sampling stops the pixels that have converged (render/adaptive_sampling.h), which
// take no samples after that: each pixel holds a power-of-two prefix of its sequence. The film's sums
// are exact (film/film.h), so the image is bit-identical for any thread count.
// Within a pass, tiles of at most kTileSize² pixels publish as they finish and count their
// pixel samples, so the image and the progress move many times per pass (a 512² frame has
// 1024 tiles): the last pass of a 64-sample render is half its time.
// The renderer knows no integrator by type: an integrator that traces light paths (light
// tracing) gets, after each pass of camera samples, its light paths of the same sample indices,
// whose splats reach the film in a fixed chunk order (trace_light_paths); such a film is
// published once per pass (film/film.h).
#pragma once

#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "film/film.h"
#include "integrators/integrator.h"
#include "render/adaptive_sampling.h"
#include "render/progress_counters.h"
#include "render/render_settings.h"
#include "render_scene/render_scene.h"
#include "scene/live_scene.h"
#include "scene/scene.h"

namespace stratum {

struct RenderProgress {
    bool done = false, cancelled = false;
    // samples_done: samples every pixel has; samples_in_progress: what the pass in progress (or
    // the last one started) brings every pixel to, so each pixel holds one or the other.
    uint32_t samples_done = 0, samples_total = 0, samples_in_progress = 0;
    // Sample indices done per pixel on average, from the work finished (camera samples and light
    // paths): samples_done plus the finished part of the pass in progress. It moves with every
    // tile; Cycles' "Sample N/M" counts the same quantity (there, all pixels hold N at once).
    double samples_average = 0;
    uint32_t update_serial = 0;
    double rays = 0, build_seconds = 0, render_seconds = 0;
    double fraction_done = 0;
    // What the render's features report (light tree, radiosity, guiding), by name.
    ProgressCounters counters;
    std::string error;  // a failure inside the render thread
};

class Renderer {
public:
    // Renders `scene` as it is at each start(): edits made in between are applied then,
    // rebuilding only what they changed.
    explicit Renderer(std::shared_ptr<const LiveScene> scene);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    RenderSettings& settings() { return settings_; }
    bool running() const { return worker_.joinable() && !done_.load(); }
    // Validates the settings against the scene; returns an error message or "".
    std::string start();
    // What the render cannot show and why, one sentence per line ("" if nothing): what the
    // chosen integrator cannot render in this scene (set by start()), placements the scene
    // build skipped (added when the build ends), samples and rays dropped as not finite or
    // out of range (added when the render ends).
    std::string notices() const;
    void cancel() { cancel_.store(true); }
    // True when the render has ended within the timeout.
    bool wait(int timeout_ms);
    RenderProgress progress() const;
    // The radiosity integrator's solver iterations of the last render (empty for the others).
    std::vector<IterationReport> radiosity_iterations() const;
    // width()*height()*4 floats, rows bottom to top: the border region (the whole frame when
    // there is none).
    void read_pixels(float* rgba) const;
    // The published values of a pass of the current (or last) render: width()*height() times
    // its channels, rows bottom to top. False when the render does not hold the pass.
    bool read_pass(Pass pass, float* out) const;
    // Light group `group`'s RGB (1..the setting lightgroups); false when the film holds none.
    bool read_lightgroup(uint32_t group, float* out) const;
    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    // The exact sums of the last render (film/film_exchange.cpp), or an error message in *error
    // when there is none, it is still running or it was cancelled.
    std::vector<uint8_t> sums_bytes(std::string* error) const;
    // Adds the sums of another render of this frame's sample indices (read by sums_bytes) to the
    // film, which then shows all of them; a renderer that has rendered nothing takes them as its
    // film. Returns an error message when it is rendering or the sums do not fit.
    std::string add_sums(std::unique_ptr<Film> sums);

private:
    using Clock = std::chrono::steady_clock;
    static double seconds_since(Clock::time_point t0);

    // start(): adaptive sampling as the settings ask and the integrator and sampler allow
    // (notices say why it is off or weaker), or an error message when it cannot render the
    // sample indices [first_sample, last_sample).
    std::string resolve_adaptive(uint64_t light_paths, uint32_t first_sample, uint32_t last_sample,
                                 AdaptiveSampling* out);
    // start(): the film of `region`, or an error message when it would not fit in memory.
    // `catcher`: what Combined shows of the scene's shadow catchers (film/shadow_catcher_film.h).
    std::string make_film(const PixelRegion& region, uint64_t light_paths, bool adaptive,
                          CatcherCombined catcher, uint32_t lightgroups);
    // start(): the progress of a render of `samples` sample indices that has not begun.
    void reset_progress(uint32_t samples);
    void join();

    // The render thread, in its steps (render/renderer.cpp):
    void run();
    // Applies the edits since the last render to the render scene, or builds it anew. Returns
    // whether the scene the last integrator prepared for is still there (only the camera, or
    // nothing, changed): then that integrator's preparation may stand (Integrator::adopt).
    bool bring_scene_up_to_date(const RenderSettings& s, tbb::task_arena& arena);
    // Adopts what the last integrator prepared, or prepares the integrator (radiosity's solve,
    // the light tree), and reports what it built.
    void prepare_integrator(const RenderSettings& s, bool scene_kept, tbb::task_arena& arena);
    // Every pass of the render's sample indices, until they are done or the render is cancelled
    // (render/render_passes.cpp).
    void render_passes(const RenderSettings& s, const Camera& camera, tbb::task_arena& arena);
    // Sample indices [first_sample_ + done, first_sample_ + next) of every pixel, their light
    // paths, and what follows a pass: the integrator's learning, the error estimate and
    // adaptive sampling's decisions at powers of two, publishing.
    void render_pass(const RenderSettings& s, const Camera& camera, uint32_t done, uint32_t next,
                     tbb::task_arena& arena);
    // At a pass end that is a power of two (`next` samples): the film's error estimate (with the
    // sampler's gain) and adaptive sampling's stops.
    void check_convergence(const RenderSettings& s, uint32_t next);
    // Camera samples [begin, end) of every pixel of the region into the film.
    void trace_camera_samples(const Camera& camera, uint32_t begin, uint32_t end, tbb::task_arena& arena);
    // The light paths of sample indices [begin, end), splatted into the film deterministically;
    // returns early on cancel.
    void trace_light_paths(const Camera& camera, uint32_t begin, uint32_t end, tbb::task_arena& arena);
    // Ends the render: done, cancelled or failed with `error`.
    void finish(const std::string& error);

    // What the render reports (render/render_reports.cpp):
    void add_notice(const std::string& notice);
    // The radiosity solve into the counters, and a notice when it did not converge.
    void report_radiosity();
    // The integrator's guiding report (if it guides) into the counters.
    void report_guiding();
    // The light tree, if this render chooses lights by it (`selection`) and it is built.
    void report_light_tree(LightSelection selection);
    // Adds the notices of the samples dropped (dropped_samples_) or clamped (clamped_samples_) and
    // the rays dropped by this render.
    void report_dropped(uint64_t refused_rays);

    std::shared_ptr<const LiveScene> live_;
    Scene scene_;           // the renderer's copy, brought up to date by start()
    SceneVersion synced_;   // what scene_ holds of live_
    SceneChanges pending_;  // edits synced into scene_ and not yet into render_scene_
    RenderSettings settings_;
    std::unique_ptr<RenderScene> render_scene_;
    // Of the current render, made by start() from the settings.
    std::unique_ptr<Integrator> integrator_;
    // The last render's integrator, until this render has adopted what it prepared or prepared
    // its own (Integrator::adopt).
    std::unique_ptr<Integrator> previous_integrator_;
    std::unique_ptr<Sampler> sampler_;
    std::unique_ptr<Film> film_;
    uint32_t width_ = 0, height_ = 0;              // the region's size
    uint64_t light_paths_ = 0;                     // light paths per sample index
    uint32_t first_sample_ = 0, last_sample_ = 0;  // the sample indices rendered (sample_range)
    double work_per_sample_ = 0;                   // progress units per sample index (fraction_done)
    AdaptiveSampling adaptive_;                    // resolved; off with light paths
    std::vector<uint8_t> stopped_;                 // per pixel of the region: adaptive sampling stopped it

    std::thread worker_;
    std::atomic<bool> cancel_{false}, done_{true};
    std::atomic<uint32_t> samples_done_{0}, samples_total_{0}, samples_in_progress_{0}, update_serial_{0};
    std::atomic<uint64_t> rays_{0};
    std::atomic<uint64_t> pixel_samples_done_{0};
    mutable std::mutex state_mutex_;
    std::condition_variable done_cv_;
    double build_seconds_ = 0, render_seconds_ = 0;
    ProgressCounters counters_;
    std::vector<IterationReport> radiosity_history_;
    Clock::time_point render_start_;
    bool rendering_ = false;  // path tracing (not BVH build) in progress
    bool cancelled_ = false;
    std::string error_;
    mutable std::mutex notices_mutex_;
    std::string notices_;
    std::atomic<uint64_t> dropped_samples_{0};
    std::atomic<uint64_t> clamped_samples_{0};  // samples clamped to the film's exact range
};

}  // namespace stratum
