// stratum-native: the small native tool. Lists the registries and renders a captured scene
// (stratum_scene_save) without Blender, e.g. for benchmarks and bug reports.
//
//   stratum-native samplers
//   stratum-native render SCENE.json OUT.(exr|png) [name=value ...]
//
// Settings are passed as name=value and typed by the value: an integer is set_int, another number
// (with a point or an exponent: 1.5, 1e-05, 1.0) is set_float, anything else set_string;
// filter_width is always a float. An unknown name or bad value exits with status 2 and the
// library's message.
#include <stratum/stratum.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

int usage() {
    std::fprintf(stderr,
                 "usage: stratum-native samplers\n"
                 "       stratum-native render SCENE.json OUT.(exr|png) [name=value ...]\n");
    return 2;
}

int failed(const char* what) {
    std::fprintf(stderr, "stratum-native: %s: %s\n", what, stratum_last_error());
    return 2;
}

int list_samplers() {
    for (int32_t setting = 0; setting < stratum_setting_count(); ++setting) {
        StratumSettingInfo info{};
        if (stratum_setting_info(setting, &info) != STRATUM_OK) return failed("settings");
        if (std::string(info.name) != "sampler") continue;
        for (int32_t i = 0; i < info.choice_count; ++i) {
            const char *name, *description;
            if (stratum_setting_choice(setting, i, &name, nullptr, &description) != STRATUM_OK) {
                return failed("sampler choices");
            }
            std::printf("%-12s %s\n", name, description);
        }
    }
    return 0;
}

bool is_integer(const std::string& s) {
    char* end = nullptr;
    std::strtoll(s.c_str(), &end, 10);
    return !s.empty() && *end == '\0';
}

bool is_number(const std::string& s) {
    char* end = nullptr;
    std::strtod(s.c_str(), &end);
    return !s.empty() && *end == '\0';
}

StratumStatus apply_setting(StratumRenderer* r, const std::string& arg) {
    const auto eq = arg.find('=');
    const std::string name = arg.substr(0, eq), value = eq == std::string::npos ? "" : arg.substr(eq + 1);
    if (name == "filter_width" || (!is_integer(value) && is_number(value)))
        return stratum_renderer_set_float(r, name.c_str(), std::strtod(value.c_str(), nullptr));
    if (is_integer(value))
        return stratum_renderer_set_int(r, name.c_str(), std::strtoll(value.c_str(), nullptr, 10));
    return stratum_renderer_set_string(r, name.c_str(), value.c_str());
}

int render(int argc, char** argv) {
    StratumScene* scene = nullptr;
    if (stratum_scene_load(argv[2], &scene) != STRATUM_OK) return failed("load");
    StratumRenderer* renderer = nullptr;
    const StratumStatus created = stratum_renderer_create(scene, &renderer);
    stratum_scene_destroy(scene);
    if (created != STRATUM_OK) return failed("create");
    int code = 0;
    for (int i = 4; i < argc && code == 0; ++i) {
        if (apply_setting(renderer, argv[i]) != STRATUM_OK) code = failed(argv[i]);
    }
    if (code == 0 && stratum_renderer_start(renderer) != STRATUM_OK) code = failed("start");
    int32_t done = 0;
    while (code == 0 && !done) {
        if (stratum_renderer_wait(renderer, 1000, &done) != STRATUM_OK) code = failed("wait");
    }
    StratumProgress p{};
    if (code == 0 && stratum_renderer_progress(renderer, &p) != STRATUM_OK) code = failed("render");
    if (code == 0 && stratum_renderer_write_image(renderer, argv[3]) != STRATUM_OK) code = failed("write");
    if (code == 0) {
        std::printf("%s: %d samples, build %.3f s, render %.3f s, %.3g rays/s\n", argv[3], p.samples_done,
                    p.build_seconds, p.render_seconds,
                    p.render_seconds > 0 ? p.rays / p.render_seconds : 0.0);
    }
    stratum_renderer_destroy(renderer);
    return code;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc >= 2 && std::strcmp(argv[1], "samplers") == 0) return list_samplers();
    if (argc >= 4 && std::strcmp(argv[1], "render") == 0) return render(argc, argv);
    return usage();
}
