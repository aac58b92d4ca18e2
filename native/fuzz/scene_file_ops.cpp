// Captured scene files: a saved scene must load and save to the same bytes again; a damaged
// or hostile file (numbers out of float range, wrong JSON types, not a regular file) must be
// refused with a message, never crash or hang.
#include <string>

#include "checked_call.h"
#include "describe.h"
#include "files.h"
#include "program.h"
#include "texture_sources.h"

namespace stratum::fuzz {

namespace {

StratumStatus save(const StratumScene* scene, const std::string& path) {
    return checked(
        "stratum_scene_save", [&] { return stratum_scene_save(scene, path.c_str()); },
        [&] { return "scene, " + describe_string(path.c_str()); });
}

StratumStatus load(const std::string& path, StratumScene** out) {
    return checked(
        "stratum_scene_load", [&] { return stratum_scene_load(path.c_str(), out); },
        [&] { return describe_string(path.c_str()) + ", &loaded"; });
}

void destroy(StratumScene* scene) {
    if (!scene) return;
    if (tracing()) trace_line("stratum_scene_destroy(loaded)");
    stratum_scene_destroy(scene);
}

// Replaces the n-th JSON number of `json` by a token the loader must refuse or convert
// safely: beyond float or uint32 range, negative where an index is expected, another type.
void replace_number(std::string& json, ByteReader& in) {
    static const char* const kTokens[] = {
        "1e300",  "-1e300", "1e39",  "-1e39", "1e-50", "-1",   "4294967296",
        "-0",     "null",   "\"x\"", "[]",    "{}",    "true", "18446744073709551616",
        "3.5e38", "1.5"};
    std::vector<size_t> starts;
    for (size_t i = 1; i < json.size(); ++i) {
        const char c = json[i], before = json[i - 1];
        if ((c == '-' || (c >= '0' && c <= '9')) && (before == '[' || before == ',' || before == ':'))
            starts.push_back(i);
    }
    const uint16_t which = in.u16();
    const char* token = kTokens[in.u8() % (sizeof kTokens / sizeof kTokens[0])];
    if (starts.empty()) return;
    const size_t start = starts[which % starts.size()];
    size_t end = start + 1;
    while (end < json.size() && std::string_view("+-.eE0123456789").find(json[end]) != std::string_view::npos)
        ++end;
    json.replace(start, end - start, token);
}

}  // namespace

void op_save_load(ByteReader& in, ProgramState& s) {
    const std::string path = temp_dir() + "/scene.json", again = temp_dir() + "/scene-again.json";
    const uint8_t mode = in.u8() % 4;
    if (mode <= 1) {
        // Round trip: what stratum_scene_save writes, stratum_scene_load must read back, and
        // saving the loaded scene must give the same bytes.
        if (save(s.scene, path) != STRATUM_OK) finding("stratum_scene_save failed in a writable directory");
        StratumScene* loaded = nullptr;
        if (load(path, &loaded) != STRATUM_OK)
            finding(std::string("a file written by stratum_scene_save does not load: ") +
                    stratum_last_error());
        if (save(loaded, again) != STRATUM_OK) finding("saving a loaded scene failed");
        if (read_file(path) != read_file(again)) finding("save, load, save: the two files differ");
        if (mode == 1) {
            // Continue with the loaded scene: it has the same materials, meshes and textures.
            std::swap(s.scene, loaded);
        }
        destroy(loaded);
        return;
    }
    if (mode == 2) {
        // A damaged capture: byte changes and a number replaced by a hostile token.
        save(s.scene, path);
        std::string json = read_file(path);
        const unsigned changes = in.u8() % 3;
        for (unsigned i = 0; i < changes && !json.empty(); ++i)
            json[in.u16() % json.size()] = static_cast<char>(in.u8());
        replace_number(json, in);
        write_file(path, json);
        StratumScene* loaded = nullptr;
        load(path, &loaded);
        destroy(loaded);
        return;
    }
    // Not a scene file at all, and paths that are no file to read or write.
    static const char* const kPaths[] = {"garbage.json", "missing.json", "", "fifo.png"};
    const uint8_t which = in.u8() % 7;
    std::string target = which < 4    ? temp_dir() + "/" + kPaths[which]
                         : which == 4 ? std::string("/dev/zero")
                         : which == 5 ? std::string("/dev/null")
                                      : temp_dir() + "/no-such-dir/scene.json";
    if (which == 0) write_file(target, in.bytes(512));
    StratumScene* loaded = nullptr;
    load(target, &loaded);
    destroy(loaded);
    if (which != 0 && which != 5) save(s.scene, target);
}

}  // namespace stratum::fuzz
