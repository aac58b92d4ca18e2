// Progressive renderer: runs passes of samples on TBB worker threads in a background thread,
// publishes pixels as tiles finish, stops on cancel.
//
// Passes cover sample ranges [0,1), [1,2), [2,4), [4,8), ... capped at kMaxPassSamples: every
// intermediate image holds a power-of-two-aligned prefix of each pixel's samples, so
// low-discrepancy properties hold at every update (research/samplers.md §5.6). Each pixel sums
// its own samples in index order, so the image is bit-identical for any thread count.
// Light tracing (integrator `light`) adds, per pass, W×H particles per sample index over the
// full frame, whose splats are summed in a fixed chunk order (trace_particles); its image is
// published once per pass: the camera-ray mean plus the splat sums over the samples done.
#pragma once

#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <shared_mutex>
#include <string>
#include <thread>
#include <vector>

#include "integrators/light_tracer.h"
#include "render/render_settings.h"
#include "render_scene/render_scene.h"
#include "scene/scene.h"

namespace stratum {

struct RenderProgress {
    bool done = false, cancelled = false;
    uint32_t samples_done = 0, samples_total = 0;
    uint32_t update_serial = 0;
    double rays = 0, build_seconds = 0, render_seconds = 0;
    double fraction_done = 0;
    std::string error;  // a failure inside the render thread
};

class Renderer {
public:
    explicit Renderer(Scene scene);
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
    // width()*height()*4 floats, rows bottom to top: the border region (the whole frame when
    // there is none).
    void read_pixels(float* rgba) const;
    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }

private:
    void run();
    void join();
    void add_notice(const std::string& notice);
    // Adds the notices of the samples (dropped_samples_) and rays dropped by this render.
    void report_dropped(uint64_t refused_rays);
    // Light tracing: the particles of sample indices [begin, end), splatted into splat_sums
    // (RGB per region pixel) deterministically; returns early on cancel.
    void trace_particles(const LightTracer& tracer, const Sampler& sampler, const ParticleFilm& film,
                         uint32_t begin, uint32_t end, tbb::task_arena& arena,
                         std::vector<double>& splat_sums);

    Scene scene_;
    RenderSettings settings_;
    std::unique_ptr<RenderScene> render_scene_;
    PixelRegion region_;               // of the current render, set by start()
    uint32_t width_ = 0, height_ = 0;  // the region's size
    double work_per_sample_ = 0;       // progress units per sample index (fraction_done)

    // Published image (RGBA, averaged). Tiles write disjoint regions under a shared lock;
    // read_pixels takes it exclusively.
    mutable std::shared_mutex image_mutex_;
    std::vector<float> image_;

    std::thread worker_;
    std::atomic<bool> cancel_{false}, done_{true};
    std::atomic<uint32_t> samples_done_{0}, samples_total_{0}, update_serial_{0};
    std::atomic<uint64_t> rays_{0};
    std::atomic<uint64_t> pixel_samples_done_{0};
    mutable std::mutex state_mutex_;
    std::condition_variable done_cv_;
    double build_seconds_ = 0, render_seconds_ = 0;
    std::chrono::steady_clock::time_point render_start_;
    bool rendering_ = false;  // path tracing (not BVH build) in progress
    bool cancelled_ = false;
    std::string error_;
    mutable std::mutex notices_mutex_;
    std::string notices_;
    std::atomic<uint64_t> dropped_samples_{0};
};

}  // namespace stratum
