// Rendering operations: named settings (known names and values, wrong kinds, garbage), then a
// tiny render that must end, honour cancel, and leave finite pixels; and the Embree-only ray
// throughput measurement.
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "checked_call.h"
#include "describe.h"
#include "program.h"
#include "texture_sources.h"

namespace stratum::fuzz {

namespace {

// A render of at most 8 x 8 pixels, 2 samples and 4 bounces takes milliseconds even under the
// sanitizers: one that has not ended after this long is hung.
constexpr int kRenderLimitMs = 20000;
// stratum.h: cancel "returns at once"; the issue asks for 0.5 s. Generous under the sanitizers
// on a loaded machine, and still a finding for a render that ignores cancel.
constexpr int kCancelLimitMs = 2000;

const char* const kSettingNames[] = {
    "width", "height", "samples", "max_bounces", "seed", "threads", "crop_x", "crop_y", "crop_width",
    "crop_height", "film_transparent", "rr_min_depth", "filter_width", "ao_distance", "control_variate",
    "sampler", "filter_type", "integrator", "hemisphere", "light_sampling", "mis_heuristic",
    "light_selection", "triangle_sampling", "rr_mode", "WIDTH", "",
    // Appended after the old entries, so that the corpus's programs keep naming what they named.
    "use_adaptive_sampling", "adaptive_threshold", "adaptive_min_samples", "adaptive_metric",
    "light_tree_splits", "sample_offset", "sample_count", "bvh", "mist_start", "mist_depth", "mist_falloff",
    "passes",
    // radiosity_rays is left out: at its maximum (2^20 rays per patch) a legitimate solve of the
    // fuzzer's scenes takes minutes, which kRenderLimitMs would report as a hang.
    "radiosity_patch_size", "radiosity_solver", "radiosity_tolerance", "use_guiding",
    "guiding_training_samples", "guiding_bsdf_fraction", "guiding_split"};

// Every value the string settings know (the settings' choices read from the library, so new
// entries are fuzzed too) and a few near misses.
const std::vector<const char*>& string_values() {
    static const std::vector<const char*> values = [] {
        std::vector<const char*> v = {"box",      "blackman_harris",
                                      "gaussian", "mis",
                                      "nee",      "bsdf",
                                      "power",    "balance",
                                      "max",      "mixed",
                                      "uniform",  "solid_angle",
                                      "area",     "throughput",
                                      "albedo",   "off",
                                      "on",       "",
                                      "Random",   "path ",
                                      "Depth",    "Normal,Debug Sample Count,Depth",
                                      "Mist,",    ",,"};
        for (const char* setting : {"sampler", "filter_type", "integrator", "hemisphere", "light_selection",
                                    "adaptive_metric", "bvh", "radiosity_solver", "guiding_split"}) {
            for (const char* name : setting_choice_names(setting)) v.push_back(name);
        }
        return v;
    }();
    return values;
}

StratumStatus set_int(ProgramState& s, const std::string& name, int64_t value) {
    const StratumStatus status = checked(
        "stratum_renderer_set_int", [&] { return stratum_renderer_set_int(s.renderer, name.c_str(), value); },
        [&] { return "renderer, " + describe_string(name.c_str()) + ", " + std::to_string(value); });
    if (status == STRATUM_OK && name == "crop_width") s.crop_width = static_cast<uint32_t>(value);
    if (status == STRATUM_OK && name == "crop_height") s.crop_height = static_cast<uint32_t>(value);
    return status;
}

void apply_settings(ByteReader& in, ProgramState& s) {
    const unsigned count = in.u8() % 8;
    for (unsigned i = 0; i < count; ++i) {
        const uint8_t kind = in.u8() % 3;
        const std::string name = in.name(kSettingNames);
        if (kind == 0) {
            set_int(s, name, in.i64());
        } else if (kind == 1) {
            const double value = in.f64(FloatKind::Positive);
            checked(
                "stratum_renderer_set_float",
                [&] { return stratum_renderer_set_float(s.renderer, name.c_str(), value); },
                [&] { return "renderer, " + describe_string(name.c_str()) + ", " + std::to_string(value); });
        } else {
            const std::string value = in.name(string_values());
            checked(
                "stratum_renderer_set_string",
                [&] { return stratum_renderer_set_string(s.renderer, name.c_str(), value.c_str()); },
                [&] {
                    return "renderer, " + describe_string(name.c_str()) + ", " +
                           describe_string(value.c_str());
                });
        }
    }
    // The limits that keep an execution fast, set last: valid values must be accepted.
    s.width = 1 + in.u8() % 8;
    s.height = 1 + in.u8() % 8;
    const std::pair<const char*, int64_t> limits[] = {{"width", s.width},
                                                      {"height", s.height},
                                                      {"samples", 1 + in.u8() % 2},
                                                      {"max_bounces", in.u8() % 5},
                                                      {"threads", 1 + in.u8() % 2}};
    for (const auto& [name, value] : limits) {
        if (set_int(s, name, value) != STRATUM_OK)
            finding(std::string("stratum_renderer_set_int refused ") + name + " = " + std::to_string(value));
    }
}

// Waits for the render to end; a render that does not is a finding.
void wait_for_end(ProgramState& s) {
    int32_t done = 0;
    checked(
        "stratum_renderer_wait", [&] { return stratum_renderer_wait(s.renderer, kRenderLimitMs, &done); },
        [] { return "renderer, " + std::to_string(kRenderLimitMs) + ", &done"; });
    if (done) return;
    checked(
        "stratum_renderer_cancel", [&] { return stratum_renderer_cancel(s.renderer); },
        [] { return "renderer"; });
    stratum_renderer_wait(s.renderer, kCancelLimitMs, &done);
    finding("a render of " + std::to_string(s.width) + " x " + std::to_string(s.height) +
            " pixels (<= 2 samples, <= 4 bounces) has not ended after " + std::to_string(kRenderLimitMs) +
            " ms" +
            (done ? "" : ", nor " + std::to_string(kCancelLimitMs) + " ms after stratum_renderer_cancel"));
}

void cancel_and_expect_end(ProgramState& s) {
    checked(
        "stratum_renderer_cancel", [&] { return stratum_renderer_cancel(s.renderer); },
        [] { return "renderer"; });
    int32_t done = 0;
    checked(
        "stratum_renderer_wait", [&] { return stratum_renderer_wait(s.renderer, kCancelLimitMs, &done); },
        [] { return "renderer, " + std::to_string(kCancelLimitMs) + ", &done"; });
    if (!done) finding("a render is still running " + std::to_string(kCancelLimitMs) + " ms after cancel");
}

// Every progress counter, and one index on each side of the list: a counter is a finite,
// non-negative number (seconds, bytes or a count) with a name; an index outside is refused.
// Reads no input, so that the corpus's programs keep their meaning.
void check_progress_counters(const ProgramState& s) {
    const int32_t count = stratum_progress_counter_count();
    for (int32_t i = -1; i <= count; ++i) {
        const char* name = nullptr;
        double value = 0.0;
        const StratumStatus status = checked(
            "stratum_renderer_progress_counter",
            [&] { return stratum_renderer_progress_counter(s.renderer, i, &name, &value); },
            [&] { return "renderer, " + std::to_string(i) + ", &name, &value"; });
        const bool inside = i >= 0 && i < count;
        if ((status == STRATUM_OK) != inside)
            finding("stratum_renderer_progress_counter(" + std::to_string(i) + ") returned " +
                    std::to_string(status) + " for a list of " + std::to_string(count));
        if (inside && (name == nullptr || !std::isfinite(value) || value < 0.0))
            finding("progress counter " + std::to_string(i) + " (" + (name ? name : "no name") +
                    ") = " + std::to_string(value));
    }
}

// After the render has ended: progress says so, the progress counters are numbers, and the
// pixels are finite with alpha in [0, 1].
void check_finished(ByteReader& in, ProgramState& s) {
    StratumProgress p{};
    const StratumStatus status = checked(
        "stratum_renderer_progress", [&] { return stratum_renderer_progress(s.renderer, &p); },
        [] { return "renderer, &progress"; });
    if (!p.done) finding("stratum_renderer_progress: done = 0 after the render ended");
    if (status == STRATUM_OK && !p.cancelled && p.samples_done != p.samples_total)
        finding("a finished render has samples_done " + std::to_string(p.samples_done) + " of " +
                std::to_string(p.samples_total));
    if (!(p.fraction_done >= 0.0 && p.fraction_done <= 1.0 + 1e-9))
        finding("stratum_renderer_progress: fraction_done = " + std::to_string(p.fraction_done));
    check_progress_counters(s);
    const char* notices = nullptr;
    if (checked(
            "stratum_renderer_notices", [&] { return stratum_renderer_notices(s.renderer, &notices); },
            [] { return "renderer, &notices"; }) != STRATUM_OK ||
        !notices)
        finding("stratum_renderer_notices failed after a render");
    const uint32_t w = s.crop_width ? s.crop_width : s.width, h = s.crop_width ? s.crop_height : s.height;
    std::vector<float> rgba(static_cast<size_t>(w) * h * 4);
    if (checked(
            "stratum_renderer_read_pixels",
            [&] { return stratum_renderer_read_pixels(s.renderer, rgba.data(), rgba.size()); },
            [&] { return "renderer, rgba, " + std::to_string(rgba.size()); }) != STRATUM_OK)
        finding(std::string("stratum_renderer_read_pixels failed after a render: ") + stratum_last_error());
    if (tracing()) {
        double sum[4] = {};
        for (size_t i = 0; i < rgba.size(); ++i) sum[i % 4] += rgba[i];
        const double n = static_cast<double>(rgba.size() / 4);
        trace_line("// pixel means: r " + std::to_string(sum[0] / n) + ", g " + std::to_string(sum[1] / n) +
                   ", b " + std::to_string(sum[2] / n) + ", alpha " + std::to_string(sum[3] / n));
    }
    for (size_t i = 0; i < rgba.size(); ++i) {
        const bool alpha = i % 4 == 3;
        if (std::isfinite(rgba[i]) && (!alpha || (rgba[i] >= 0.0f && rgba[i] <= 1.0f))) continue;
        finding("pixel (" + std::to_string(i / 4 % w) + ", " + std::to_string(i / 4 / w) + ") channel " +
                std::to_string(i % 4) + " = " + describe_float(rgba[i]) +
                (alpha ? " (alpha outside [0, 1])" : " (not finite)"));
    }
    static const char* const kImageNames[] = {"image.exr", "image.png", "image.hdr",
                                              "image.jpg", "image.txt", "image"};
    if (in.u8() % 8 == 0) {
        const std::string path = temp_dir() + "/" + in.name(kImageNames);
        checked(
            "stratum_renderer_write_image",
            [&] { return stratum_renderer_write_image(s.renderer, path.c_str()); },
            [&] { return "renderer, " + describe_string(path.c_str()); });
    }
}

// Starts the configured renderer and drives it to its end in one of several ways.
void start_and_finish(ByteReader& in, ProgramState& s) {
    apply_settings(in, s);
    const uint8_t mode = in.u8() % 5;
    if (s.renders >= kMaxRenders) return;
    ++s.renders;
    if (checked(
            "stratum_renderer_start", [&] { return stratum_renderer_start(s.renderer); },
            [] { return "renderer"; }) != STRATUM_OK)
        return;
    switch (mode) {
        case 1:
            cancel_and_expect_end(s);
            break;
        case 2: {
            // Changing a setting while rendering is refused (or accepted once the render ended).
            const StratumStatus status = set_int(s, "seed", 7);
            if (status != STRATUM_OK && status != STRATUM_ERROR_INVALID_STATE)
                finding("stratum_renderer_set_int during a render returned " + std::to_string(status));
            break;
        }
        case 3: {
            // Progress, its counters and pixels read while the render runs.
            StratumProgress p{};
            checked(
                "stratum_renderer_progress", [&] { return stratum_renderer_progress(s.renderer, &p); },
                [] { return "renderer, &progress"; });
            check_progress_counters(s);
            const uint32_t w = s.crop_width ? s.crop_width : s.width,
                           h = s.crop_width ? s.crop_height : s.height;
            std::vector<float> rgba(static_cast<size_t>(w) * h * 4);
            checked(
                "stratum_renderer_read_pixels",
                [&] { return stratum_renderer_read_pixels(s.renderer, rgba.data(), rgba.size()); },
                [&] { return "renderer, rgba, " + std::to_string(rgba.size()); });
            break;
        }
        case 4:
            // Destroyed while rendering: the destructor cancels and joins.
            if (tracing()) trace_line("stratum_renderer_destroy(renderer)");
            stratum_renderer_destroy(s.renderer);
            s.renderer = nullptr;
            return;
        default:
            break;
    }
    wait_for_end(s);
    check_finished(in, s);
}

}  // namespace

void op_render(ByteReader& in, ProgramState& s) {
    if (s.renderer) {
        if (tracing()) trace_line("stratum_renderer_destroy(renderer)");
        stratum_renderer_destroy(s.renderer);
        s.renderer = nullptr;
    }
    s.crop_width = s.crop_height = 0;
    if (checked(
            "stratum_renderer_create", [&] { return stratum_renderer_create(s.scene, &s.renderer); },
            [] { return "scene, &renderer"; }) != STRATUM_OK)
        finding("stratum_renderer_create failed");
    start_and_finish(in, s);
}

void op_rerender(ByteReader& in, ProgramState& s) {
    if (!s.renderer) return;
    start_and_finish(in, s);
}

void op_measure_throughput(ByteReader& in, ProgramState& s) {
    const uint32_t width = in.u8() % 6, height = in.u8() % 6, samples = in.u8() % 3, bounces = in.u8() % 5,
                   threads = 1 + in.u8() % 2;
    if (s.throughputs >= kMaxThroughputs) return;
    ++s.throughputs;
    double rays = -1.0, seconds = -1.0;
    const StratumStatus status = checked(
        "stratum_scene_measure_ray_throughput",
        [&] {
            return stratum_scene_measure_ray_throughput(s.scene, width, height, samples, bounces, threads,
                                                        &rays, &seconds);
        },
        [&] {
            return "scene, " + std::to_string(width) + ", " + std::to_string(height) + ", " +
                   std::to_string(samples) + ", " + std::to_string(bounces) + ", " + std::to_string(threads) +
                   ", &rays, &seconds";
        });
    if (status != STRATUM_OK) return;
    // At least one camera ray per pixel sample.
    const double camera_rays = static_cast<double>(width) * height * samples;
    if (!(rays >= camera_rays && std::isfinite(rays) && seconds >= 0.0 && std::isfinite(seconds)))
        finding("stratum_scene_measure_ray_throughput: rays = " + std::to_string(rays) +
                ", seconds = " + std::to_string(seconds));
}

}  // namespace stratum::fuzz
