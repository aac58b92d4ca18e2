// The C entry points of stratum/render.h: renderers, their settings, start and progress,
// pixels and passes, and the sums of one frame's samples over many renders. Every input is
// validated here and every exception stops here (api/abi_guard.h).
#include <cstring>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "api/abi_guard.h"
#include "api/scene_handle.h"
#include "api/validation.h"
#include "render/image_output.h"
#include "render/progress_counters.h"
#include "render/renderer.h"
#include "render/setting_registry.h"
#include "stratum/stratum.h"

struct StratumRenderer {
    explicit StratumRenderer(std::shared_ptr<const stratum::LiveScene> scene) : renderer(std::move(scene)) {}
    stratum::Renderer renderer;
    // The notices as last handed out by stratum_renderer_notices (the renderer's grow while
    // it renders; the host's pointer must stay valid until its next call).
    mutable std::string notices;
};

namespace {

using stratum::require;
using stratum::abi::fail;
using stratum::abi::guarded;

template <typename F>
StratumStatus set_setting(const char* function, StratumRenderer* r, const char* name, F&& apply) {
    return guarded(function, [&] {
        require(r && name, "renderer or name is NULL");
        if (r->renderer.running()) {
            return fail(STRATUM_ERROR_INVALID_STATE,
                        std::string(function) + ": cannot change '" + name + "' while rendering");
        }
        const std::string error = apply(r->renderer.settings());
        require(error.empty(), error);
        return STRATUM_OK;
    });
}

}  // namespace

extern "C" {

StratumStatus stratum_renderer_create(const StratumScene* scene, StratumRenderer** out) {
    return guarded("stratum_renderer_create", [&] {
        require(scene && out, "scene or out is NULL");
        *out = new StratumRenderer(scene->live);
        return STRATUM_OK;
    });
}

void stratum_renderer_destroy(StratumRenderer* r) { delete r; }

StratumStatus stratum_renderer_set_int(StratumRenderer* r, const char* name, int64_t value) {
    return set_setting("stratum_renderer_set_int", r, name,
                       [&](stratum::RenderSettings& s) { return stratum::set_int_setting(s, name, value); });
}

StratumStatus stratum_renderer_set_float(StratumRenderer* r, const char* name, double value) {
    return set_setting("stratum_renderer_set_float", r, name, [&](stratum::RenderSettings& s) {
        return stratum::set_float_setting(s, name, value);
    });
}

StratumStatus stratum_renderer_set_string(StratumRenderer* r, const char* name, const char* value) {
    return set_setting("stratum_renderer_set_string", r, name, [&](stratum::RenderSettings& s) {
        require(value != nullptr, std::string("value of '") + name + "' is NULL");
        return stratum::set_string_setting(s, name, value);
    });
}

StratumStatus stratum_renderer_start(StratumRenderer* r) {
    return guarded("stratum_renderer_start", [&] {
        require(r != nullptr, "renderer is NULL");
        const std::string error = r->renderer.start();
        return error.empty() ? STRATUM_OK
                             : fail(STRATUM_ERROR_INVALID_STATE, "stratum_renderer_start: " + error);
    });
}

StratumStatus stratum_renderer_notices(const StratumRenderer* r, const char** out) {
    return guarded("stratum_renderer_notices", [&] {
        require(r && out, "renderer or out is NULL");
        r->notices = r->renderer.notices();
        *out = r->notices.c_str();
        return STRATUM_OK;
    });
}

StratumStatus stratum_renderer_cancel(StratumRenderer* r) {
    return guarded("stratum_renderer_cancel", [&] {
        require(r != nullptr, "renderer is NULL");
        r->renderer.cancel();
        return STRATUM_OK;
    });
}

StratumStatus stratum_renderer_wait(StratumRenderer* r, int32_t timeout_ms, int32_t* out_done) {
    return guarded("stratum_renderer_wait", [&] {
        require(r != nullptr, "renderer is NULL");
        const bool done = r->renderer.wait(timeout_ms);
        if (out_done) *out_done = done ? 1 : 0;
        return STRATUM_OK;
    });
}

StratumStatus stratum_renderer_progress(const StratumRenderer* r, StratumProgress* out) {
    return guarded("stratum_renderer_progress", [&] {
        require(r && out, "renderer or out is NULL");
        const stratum::RenderProgress p = r->renderer.progress();
        *out = StratumProgress{p.done ? 1 : 0,
                               p.cancelled ? 1 : 0,
                               static_cast<int32_t>(p.samples_done),
                               static_cast<int32_t>(p.samples_total),
                               p.update_serial,
                               p.rays,
                               p.build_seconds,
                               p.render_seconds,
                               p.fraction_done,
                               static_cast<int32_t>(p.samples_in_progress),
                               p.samples_average};
        // A failure inside the render thread is reported by the next progress call.
        return p.error.empty() ? STRATUM_OK : fail(STRATUM_ERROR_INTERNAL, "render failed: " + p.error);
    });
}

int32_t stratum_progress_counter_count(void) {
    return static_cast<int32_t>(stratum::kProgressCounterNames.size());
}

StratumStatus stratum_renderer_progress_counter(const StratumRenderer* r, int32_t index, const char** name,
                                                double* value) {
    return guarded("stratum_renderer_progress_counter", [&] {
        require(r != nullptr, "renderer is NULL");
        const int32_t count = stratum_progress_counter_count();
        require(index >= 0 && index < count, "progress counter index " + std::to_string(index) +
                                                 " out of range [0, " + std::to_string(count) + ")");
        const auto i = static_cast<size_t>(index);
        if (name) *name = stratum::kProgressCounterNames[i];
        if (value) *value = r->renderer.progress().counters.values[i];
        return STRATUM_OK;
    });
}

StratumStatus stratum_renderer_read_radiosity_iterations(const StratumRenderer* r, double* out,
                                                         size_t count) {
    return guarded("stratum_renderer_read_radiosity_iterations", [&] {
        require(r && out, "renderer or out is NULL");
        const std::vector<stratum::IterationReport> iterations = r->renderer.radiosity_iterations();
        require(count == 4 * iterations.size(), "buffer holds " + std::to_string(count) +
                                                    " doubles, the last render's radiosity solve needs " +
                                                    std::to_string(4 * iterations.size()) + " (4 x its " +
                                                    std::to_string(iterations.size()) + " iterations)");
        for (const stratum::IterationReport& it : iterations) {
            *out++ = it.delta_e;
            *out++ = it.relative;
            *out++ = it.residual;
            *out++ = it.seconds;
        }
        return STRATUM_OK;
    });
}

StratumStatus stratum_renderer_read_pixels(const StratumRenderer* r, float* rgba, size_t count) {
    return guarded("stratum_renderer_read_pixels", [&] {
        require(r && rgba, "renderer or rgba is NULL");
        const size_t needed = static_cast<size_t>(r->renderer.width()) * r->renderer.height() * 4;
        require(needed > 0, "nothing rendered yet: call stratum_renderer_start first");
        require(count == needed, "buffer holds " + std::to_string(count) + " floats, the image needs " +
                                     std::to_string(needed) + " (width*height*4)");
        r->renderer.read_pixels(rgba);
        return STRATUM_OK;
    });
}

StratumStatus stratum_renderer_read_lightgroup(const StratumRenderer* r, uint32_t group, float* out,
                                               size_t count) {
    return guarded("stratum_renderer_read_lightgroup", [&] {
        require(r && out, "renderer or out is NULL");
        const size_t pixels = static_cast<size_t>(r->renderer.width()) * r->renderer.height();
        require(pixels > 0, "nothing rendered yet: call stratum_renderer_start first");
        require(count == pixels * 3, "buffer holds " + std::to_string(count) +
                                         " floats, a light group needs " + std::to_string(pixels * 3) +
                                         " (width*height*3)");
        require(r->renderer.read_lightgroup(group, out), "this render does not hold light group " +
                                                             std::to_string(group) +
                                                             " (groups are 1..the setting 'lightgroups')");
        return STRATUM_OK;
    });
}

StratumStatus stratum_renderer_read_pass(const StratumRenderer* r, const char* name, float* out,
                                         size_t count) {
    return guarded("stratum_renderer_read_pass", [&] {
        require(r && name && out, "renderer, name or out is NULL");
        stratum::Pass pass = stratum::Pass::Combined;
        require(stratum::find_pass(name, &pass), "unknown pass '" + std::string(name) + "'");
        const size_t pixels = static_cast<size_t>(r->renderer.width()) * r->renderer.height();
        require(pixels > 0, "nothing rendered yet: call stratum_renderer_start first");
        const size_t needed = pixels * stratum::pass_info(pass).channels;
        require(count == needed, "buffer holds " + std::to_string(count) + " floats, pass '" +
                                     std::string(name) + "' needs " + std::to_string(needed) +
                                     " (width*height*" + std::to_string(stratum::pass_info(pass).channels) +
                                     ")");
        require(r->renderer.read_pass(pass, out), "this render does not hold pass '" + std::string(name) +
                                                      "' (add it to the setting 'passes')");
        return STRATUM_OK;
    });
}

StratumStatus stratum_renderer_sums_size(const StratumRenderer* r, size_t* out_bytes) {
    return guarded("stratum_renderer_sums_size", [&] {
        require(r && out_bytes, "renderer or out_bytes is NULL");
        std::string error;
        const std::vector<uint8_t> bytes = r->renderer.sums_bytes(&error);
        require(error.empty(), error);
        *out_bytes = bytes.size();
        return STRATUM_OK;
    });
}

StratumStatus stratum_renderer_read_sums(const StratumRenderer* r, void* out, size_t bytes) {
    return guarded("stratum_renderer_read_sums", [&] {
        require(r && out, "renderer or out is NULL");
        std::string error;
        const std::vector<uint8_t> sums = r->renderer.sums_bytes(&error);
        require(error.empty(), error);
        require(bytes == sums.size(), "buffer holds " + std::to_string(bytes) + " bytes, the sums are " +
                                          std::to_string(sums.size()) + " (stratum_renderer_sums_size)");
        std::memcpy(out, sums.data(), sums.size());
        return STRATUM_OK;
    });
}

StratumStatus stratum_renderer_add_sums(StratumRenderer* r, const void* sums, size_t bytes) {
    return guarded("stratum_renderer_add_sums", [&] {
        require(r, "renderer is NULL");
        std::unique_ptr<stratum::Film> film = stratum::validate_film_sums(sums, bytes);
        const std::string error = r->renderer.add_sums(std::move(film));
        require(error.empty(), error);
        return STRATUM_OK;
    });
}

StratumStatus stratum_renderer_write_image(const StratumRenderer* r, const char* path) {
    return guarded("stratum_renderer_write_image", [&] {
        require(r && path, "renderer or path is NULL");
        const size_t n = static_cast<size_t>(r->renderer.width()) * r->renderer.height() * 4;
        require(n > 0, "nothing rendered yet: call stratum_renderer_start first");
        std::vector<float> rgba(n);
        r->renderer.read_pixels(rgba.data());
        const std::string error = stratum::write_image(path, rgba, r->renderer.width(), r->renderer.height());
        return error.empty() ? STRATUM_OK : fail(STRATUM_ERROR_IO, "stratum_renderer_write_image: " + error);
    });
}

}  // extern "C"
