#include "api/scene_file.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "api/scene_file_numbers.h"
#include "api/scene_file_programs.h"

namespace stratum {

namespace {

using nlohmann::json;
using scene_file::element;
using scene_file::field;
using scene_file::field_or;
using scene_file::numbers;
using scene_file::read_numbers;

constexpr const char* kFormat = "stratum-scene";
// Version 2: the renderer's inputs take 128 registers of a program (100 before); version 3: 144
// (the Light Path node's). Older files still load (api/scene_file_programs.h).
constexpr int kVersion = 3;

json rgb(Rgb c) { return json::array({c.r, c.g, c.b}); }
json matrix(const Transform& t) {
    json m = json::array();
    for (float v : t.m) m.push_back(v);
    for (float v : {0.0f, 0.0f, 0.0f, 1.0f}) m.push_back(v);
    return m;
}

json closure_json(const WeightedClosure& c) {
    const Material& m = c.params;
    return {{"weight", rgb(c.weight)},
            {"model", static_cast<int>(m.model)},
            {"base_color", rgb(m.base_color)},
            {"roughness", m.roughness},
            {"metallic", m.metallic},
            {"specular", m.specular},
            {"ior", m.ior},
            {"emission", rgb(m.emission)},
            {"distribution", static_cast<int>(m.distribution)},
            {"transmission", m.transmission},
            {"coat", m.coat},
            {"coat_roughness", m.coat_roughness},
            {"coat_ior", m.coat_ior},
            {"coat_tint", rgb(m.coat_tint)},
            {"bump_shadowing", static_cast<int>(m.bump_shadowing)}};
}

// The fields of one closure; those added with closures (transmission, coat) default to the
// all-zero "none" of StratumMaterialDesc when an older file lacks them.
StratumMaterialDesc material_desc(const json& m) {
    StratumMaterialDesc d{};
    d.model = field<int32_t>(m, "model");
    read_numbers(m, "base_color", d.base_color);
    d.roughness = field<float>(m, "roughness");
    d.metallic = field<float>(m, "metallic");
    d.specular = field<float>(m, "specular");
    d.ior = field<float>(m, "ior");
    read_numbers(m, "emission", d.emission);
    d.distribution = field<int32_t>(m, "distribution");
    d.transmission = field_or(m, "transmission", 0.0f);
    d.coat = field_or(m, "coat", 0.0f);
    d.coat_roughness = field_or(m, "coat_roughness", 0.0f);
    d.coat_ior = field_or(m, "coat_ior", 0.0f);
    if (m.contains("coat_tint")) read_numbers(m, "coat_tint", d.coat_tint);
    d.bump_shadowing = field_or(m, "bump_shadowing", 0);
    return d;
}

// What `path` is when it exists and is not a regular file ("a FIFO", ...), else nullptr. Opening
// a FIFO blocks until the other end opens it, and /dev/zero never ends: the ABI would hang.
const char* special_file(const char* path) {
    std::error_code ec;
    switch (std::filesystem::status(path, ec).type()) {
        case std::filesystem::file_type::directory:
            return "a directory";
        case std::filesystem::file_type::fifo:
            return "a FIFO";
        case std::filesystem::file_type::character:
        case std::filesystem::file_type::block:
            return "a device";
        case std::filesystem::file_type::socket:
            return "a socket";
        default:
            return nullptr;  // regular, absent, or unknown (left to the open to report)
    }
}

}  // namespace

std::string save_scene_file(const Scene& scene, const char* path) {
    json j;
    j["format"] = kFormat;
    j["version"] = kVersion;
    j["materials"] = json::array();
    // Each material is its list of weighted closures (files written before closures existed
    // hold one flat closure per material; load_scene_file reads both).
    for (const SceneMaterial& sm : scene.materials) {
        json closures = json::array();
        for (const WeightedClosure& c : sm.closures) closures.push_back(closure_json(c));
        j["materials"].push_back({{"closures", closures}, {"pass_index", sm.pass_index}});
    }
    j["meshes"] = json::array();
    for (const Mesh& mesh : scene.meshes) {
        json pos = json::array(), tri = json::array(), nrm = json::array(), uv = json::array(),
             vnrm = json::array(), tangents = json::array();
        for (Vec3 p : mesh.positions) pos.insert(pos.end(), {p.x, p.y, p.z});
        for (const auto& t : mesh.triangles) tri.insert(tri.end(), {t[0], t[1], t[2]});
        for (Vec3 n : mesh.corner_normals) nrm.insert(nrm.end(), {n.x, n.y, n.z});
        for (Vec3 n : mesh.vertex_normals) vnrm.insert(vnrm.end(), {n.x, n.y, n.z});
        for (Vec2 c : mesh.corner_uvs) uv.insert(uv.end(), {c.x, c.y});
        for (size_t c = 0; c < mesh.corner_tangents.size(); ++c) {
            const Vec3 t = mesh.corner_tangents[c];
            tangents.insert(tangents.end(), {t.x, t.y, t.z, mesh.corner_signs[c]});
        }
        j["meshes"].push_back({{"positions", pos},
                               {"triangles", tri},
                               {"corner_normals", nrm},
                               {"vertex_normals", vnrm},
                               {"corner_uvs", uv},
                               {"corner_tangents", tangents},
                               {"material_ids", mesh.material_ids}});
    }
    j["instances"] = json::array();
    for (const Instance& i : scene.instances) {
        j["instances"].push_back({{"mesh", i.mesh_id},
                                  {"transform", matrix(i.object_to_world)},
                                  {"transform_end", matrix(i.object_to_world_end)},
                                  {"motion", i.motion ? 1 : 0},
                                  {"visibility", i.visibility},
                                  {"holdout", i.holdout ? 1 : 0},
                                  {"pass_index", i.pass_index},
                                  {"random", i.random},
                                  {"color", {i.color.r, i.color.g, i.color.b, i.alpha}},
                                  {"lightgroup", i.lightgroup},
                                  {"links",
                                   {i.links.receiver_light_set, i.links.blocker_shadow_set,
                                    i.links.light_set_membership, i.links.shadow_set_membership}}});
    }
    j["lights"] = json::array();
    for (const LightParams& l : scene.lights) {
        j["lights"].push_back({{"type", static_cast<int>(l.type)},
                               {"color", rgb(l.color)},
                               {"strength", l.strength},
                               {"radius", l.radius},
                               {"angle", l.angle},
                               {"size", {l.size_x, l.size_y}},
                               {"spot", {l.spot_size, l.spot_blend}},
                               {"transform", matrix(l.light_to_world)},
                               {"visibility", l.visibility},
                               {"spread", l.spread},
                               {"lightgroup", l.lightgroup},
                               {"links", {l.links.light_set_membership, l.links.shadow_set_membership}}});
    }
    if (scene.camera) {
        const CameraParams& c = *scene.camera;
        j["camera"] = {{"lens_mm", c.lens_mm},
                       {"sensor_mm", {c.sensor_width_mm, c.sensor_height_mm}},
                       {"sensor_fit", static_cast<int>(c.fit)},
                       {"shift", {c.shift_x, c.shift_y}},
                       {"clip", {c.clip_start, c.clip_end}},
                       {"transform", matrix(c.camera_to_world)},
                       {"type", static_cast<int>(c.type)},
                       {"ortho_scale", c.ortho_scale},
                       {"aperture_radius", c.aperture_radius},
                       {"focus_distance", c.focus_distance},
                       {"aperture_blades", c.aperture_blades},
                       {"aperture_rotation", c.aperture_rotation},
                       {"latitude", {c.latitude_min, c.latitude_max}},
                       {"longitude", {c.longitude_min, c.longitude_max}}};
    }
    j["background"] = rgb(scene.background);
    j["world_lightgroup"] = scene.world_lightgroup;
    if (scene.environment) {
        const Environment& e = *scene.environment;
        j["environment"] = {{"width", e.width},
                            {"height", e.height},
                            {"strength", e.strength},
                            {"rotation", e.rotation},
                            {"rgb", e.rgb}};
        // A world program that reads the Light Path node runs per ray beside its map: saved by
        // its id, and baked again (to the same map) when the file loads.
        const auto program = std::find(scene.programs.begin(), scene.programs.end(), e.program);
        if (e.program && program != scene.programs.end())
            j["environment"]["program"] = {{"program", program - scene.programs.begin()},
                                           {"register", e.program_color}};
    }
    if (!scene.textures.empty()) {
        // Textures are saved as the renderer holds them (RGBA, rows bottom to top: linear, or
        // sRGB-encoded for sRGB images) and reloaded as 4-channel pixels in "Non-Color" or the
        // built-in "sRGB", so a file replays without the original images or OCIO config.
        json textures = json::array(), bindings = json::array();
        for (const auto& t : scene.textures) {
            textures.push_back({{"width", t->width},
                                {"height", t->height},
                                {"interpolation", static_cast<int>(t->interpolation)},
                                {"extension", static_cast<int>(t->extension)},
                                {"color_space", t->srgb_encoded ? "sRGB" : "Non-Color"},
                                {"rgba", t->rgba}});
        }
        for (const TextureBinding& b : scene.texture_bindings) {
            bindings.push_back({{"material", b.material_id},
                                {"closure", b.closure_index},
                                {"param", static_cast<int>(b.param)},
                                {"texture", b.texture_id},
                                {"channel", b.channel},
                                {"scale", b.scale},
                                {"offset", b.offset}});
        }
        j["textures"] = {{"images", textures}, {"bindings", bindings}};
    }
    save_programs(scene, j);
    if (const char* kind = special_file(path))
        return std::string("'") + path + "' is " + kind + ", not a regular file";
    std::ofstream out(path, std::ios::binary);
    if (!out) return std::string("cannot open '") + path + "' for writing";
    out << j.dump();
    return out.good() ? std::string() : std::string("cannot write '") + path + "'";
}

StratumStatus load_scene_file(const char* path, StratumScene* scene, std::string* error) {
    if (const char* kind = special_file(path)) {
        *error = std::string("it is ") + kind + ", not a regular file";
        return STRATUM_ERROR_IO;
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        *error = "cannot open the file";
        return STRATUM_ERROR_IO;
    }
    json j;
    try {
        j = json::parse(in);
    } catch (const json::exception& e) {
        *error = std::string("not valid JSON: ") + e.what();
        return STRATUM_ERROR_IO;
    }
    // Failures of the entry points below carry their own message in stratum_last_error().
    const auto entry_point_failed = [&](StratumStatus status) {
        *error = stratum_last_error();
        return status;
    };
    try {
        const int version =
            j.contains("version") && j.at("version").is_number_integer() ? j.at("version").get<int>() : 0;
        if (j.value("format", "") != kFormat || version < 1 || version > kVersion) {
            *error = std::string("not a ") + kFormat + " file of version 1 to " + std::to_string(kVersion);
            return STRATUM_ERROR_IO;
        }
        StratumStatus status = STRATUM_OK;
        for (const json& m : j.at("materials")) {
            if (!m.contains("closures")) {
                const StratumMaterialDesc d = material_desc(m);
                if ((status = stratum_scene_add_material(scene, &d, nullptr)) != STRATUM_OK)
                    return entry_point_failed(status);
                continue;
            }
            std::vector<StratumClosureDesc> closures;
            for (const json& c : m.at("closures")) {
                StratumClosureDesc cd{};
                read_numbers(c, "weight", cd.weight);
                cd.closure = material_desc(c);
                closures.push_back(cd);
            }
            uint32_t id = 0;
            if ((status = stratum_scene_add_closure_material(
                     scene, closures.data(), static_cast<uint32_t>(closures.size()), &id)) != STRATUM_OK)
                return entry_point_failed(status);
            // Files written before the index passes: pass index 0, Blender's default.
            if ((status = stratum_scene_set_material_pass_index(
                     scene, id, field_or(m, "pass_index", static_cast<uint32_t>(0)))) != STRATUM_OK)
                return entry_point_failed(status);
        }
        for (const json& m : j.at("meshes")) {
            const auto pos = numbers<float>(m, "positions");
            const auto tri = numbers<uint32_t>(m, "triangles");
            const auto nrm = numbers<float>(m, "corner_normals");
            const auto uv = numbers<float>(m, "corner_uvs");
            const auto vnrm = numbers<float>(m, "vertex_normals", true);
            const auto tangents = numbers<float>(m, "corner_tangents", true);
            const auto mat = numbers<uint32_t>(m, "material_ids");
            const size_t tris = tri.size() / 3;
            if (pos.size() % 3 || tri.size() % 3 || mat.size() != tris ||
                (!nrm.empty() && nrm.size() != 9 * tris) || (!uv.empty() && uv.size() != 6 * tris) ||
                (!vnrm.empty() && vnrm.size() != pos.size()) ||
                (!tangents.empty() && tangents.size() != 12 * tris)) {
                throw std::runtime_error("mesh arrays have inconsistent sizes");
            }
            const StratumMeshDesc d{pos.data(),
                                    static_cast<uint32_t>(pos.size() / 3),
                                    tri.data(),
                                    static_cast<uint32_t>(tris),
                                    nrm.empty() ? nullptr : nrm.data(),
                                    uv.empty() ? nullptr : uv.data(),
                                    mat.data(),
                                    vnrm.empty() ? nullptr : vnrm.data(),
                                    tangents.empty() ? nullptr : tangents.data()};
            if ((status = stratum_scene_add_mesh(scene, &d, nullptr)) != STRATUM_OK)
                return entry_point_failed(status);
        }
        uint32_t instance_index = 0;
        for (const json& i : j.at("instances")) {
            StratumInstanceDesc d{};
            d.mesh_id = field<uint32_t>(i, "mesh");
            read_numbers(i, "transform", d.transform);
            // Files written before motion blur and ray visibility: a static instance seen by all rays.
            d.motion = field_or<int32_t>(i, "motion", 0);
            if (d.motion) read_numbers(i, "transform_end", d.transform_end);
            d.visibility = field_or(i, "visibility", static_cast<uint32_t>(STRATUM_VISIBLE_ALL));
            d.holdout = field_or<int32_t>(i, "holdout", 0);
            d.pass_index = field_or(i, "pass_index", static_cast<uint32_t>(0));
            // Files written before light groups: none.
            d.lightgroup = field_or(i, "lightgroup", 0u);
            if ((status = stratum_scene_add_instance_ex(scene, &d)) != STRATUM_OK)
                return entry_point_failed(status);
            // Files written before Object Info: random 0, colour white.
            const float random = field_or(i, "random", 0.0f);
            float color[4] = {1.0f, 1.0f, 1.0f, 1.0f};
            if (i.contains("color")) read_numbers(i, "color", color);
            if ((status = stratum_scene_set_instance_object_info(scene, instance_index, 1, &random, color)) !=
                STRATUM_OK)
                return entry_point_failed(status);
            // Files written before light linking: no links.
            if (i.contains("links")) {
                const uint8_t receiver = element<uint8_t>(i, "links", 0),
                              blocker = element<uint8_t>(i, "links", 1);
                const uint64_t light = element<uint64_t>(i, "links", 2),
                               shadow = element<uint64_t>(i, "links", 3);
                if ((status = stratum_scene_set_light_linking(scene, STRATUM_LINK_INSTANCES, instance_index,
                                                              1, &receiver, &blocker, &light, &shadow)) !=
                    STRATUM_OK)
                    return entry_point_failed(status);
            }
            ++instance_index;
        }
        uint32_t light_index = 0;
        for (const json& l : j.at("lights")) {
            StratumLightDesc d{};
            d.type = field<int32_t>(l, "type");
            read_numbers(l, "color", d.color);
            d.strength = field<float>(l, "strength");
            d.radius = field<float>(l, "radius");
            d.angle = field<float>(l, "angle");
            d.size_x = element<float>(l, "size", 0);
            d.size_y = element<float>(l, "size", 1);
            // Files written before spot lights have no "spot": the defaults of LightParams.
            d.spot_size = l.contains("spot") ? element<float>(l, "spot", 0) : kPi;
            d.spot_blend = l.contains("spot") ? element<float>(l, "spot", 1) : 0.0f;
            read_numbers(l, "transform", d.transform);
            // Absent in older files: 0 reads as all rays and as spread pi.
            d.visibility = field_or(l, "visibility", 0u);
            d.spread = field_or(l, "spread", 0.0f);
            d.lightgroup = field_or(l, "lightgroup", 0u);
            if ((status = stratum_scene_add_light(scene, &d)) != STRATUM_OK)
                return entry_point_failed(status);
            if (l.contains("links")) {
                const uint64_t light = element<uint64_t>(l, "links", 0),
                               shadow = element<uint64_t>(l, "links", 1);
                if ((status = stratum_scene_set_light_linking(scene, STRATUM_LINK_LIGHTS, light_index, 1,
                                                              nullptr, nullptr, &light, &shadow)) !=
                    STRATUM_OK)
                    return entry_point_failed(status);
            }
            ++light_index;
        }
        if (j.contains("camera")) {
            const json& c = j["camera"];
            StratumCameraDesc d{};
            d.lens_mm = field<float>(c, "lens_mm");
            d.sensor_width_mm = element<float>(c, "sensor_mm", 0);
            d.sensor_height_mm = element<float>(c, "sensor_mm", 1);
            d.sensor_fit = field<int32_t>(c, "sensor_fit");
            d.shift_x = element<float>(c, "shift", 0);
            d.shift_y = element<float>(c, "shift", 1);
            d.clip_start = element<float>(c, "clip", 0);
            d.clip_end = element<float>(c, "clip", 1);
            read_numbers(c, "transform", d.transform);
            // Absent in files written before orthographic and thin-lens cameras: a pinhole.
            d.type = field_or<int32_t>(c, "type", 0);
            d.ortho_scale = field_or(c, "ortho_scale", 0.0f);
            d.aperture_radius = field_or(c, "aperture_radius", 0.0f);
            d.focus_distance = field_or(c, "focus_distance", 0.0f);
            d.aperture_blades = field_or<int32_t>(c, "aperture_blades", 0);
            d.aperture_rotation = field_or(c, "aperture_rotation", 0.0f);
            const bool latitude = c.contains("latitude"), longitude = c.contains("longitude");
            d.latitude_min = latitude ? element<float>(c, "latitude", 0) : -0.5f * kPi;
            d.latitude_max = latitude ? element<float>(c, "latitude", 1) : 0.5f * kPi;
            d.longitude_min = longitude ? element<float>(c, "longitude", 0) : -kPi;
            d.longitude_max = longitude ? element<float>(c, "longitude", 1) : kPi;
            if ((status = stratum_scene_set_camera(scene, &d)) != STRATUM_OK)
                return entry_point_failed(status);
        }
        float bg[3];
        read_numbers(j, "background", bg);
        if ((status = stratum_scene_set_background(scene, bg)) != STRATUM_OK ||
            (status = stratum_scene_set_world_lightgroup(scene, field_or(j, "world_lightgroup", 0u))) !=
                STRATUM_OK)
            return entry_point_failed(status);
        if (j.contains("environment")) {
            const json& e = j.at("environment");
            const auto rgb = numbers<float>(e, "rgb");
            float rotation[9];
            read_numbers(e, "rotation", rotation);
            const auto width = field<uint32_t>(e, "width"), height = field<uint32_t>(e, "height");
            if (rgb.size() != static_cast<size_t>(width) * height * 3) {
                *error = "malformed scene: environment rgb has " + std::to_string(rgb.size()) +
                         " values, expected " + std::to_string(static_cast<size_t>(width) * height * 3);
                return STRATUM_ERROR_IO;
            }
            if ((status = stratum_scene_set_environment(scene, rgb.data(), width, height,
                                                        field<float>(e, "strength"), rotation)) != STRATUM_OK)
                return entry_point_failed(status);
        }
        if (j.contains("textures")) {
            for (const json& t : j.at("textures").at("images")) {
                const auto rgba = numbers<float>(t, "rgba");
                StratumTextureDesc d{};
                d.width = field<uint32_t>(t, "width");
                d.height = field<uint32_t>(t, "height");
                if (rgba.size() != static_cast<size_t>(d.width) * d.height * 4) {
                    *error = "malformed scene: texture rgba has " + std::to_string(rgba.size()) +
                             " values, expected " +
                             std::to_string(static_cast<size_t>(d.width) * d.height * 4);
                    return STRATUM_ERROR_IO;
                }
                d.pixels = rgba.data();
                d.channels = 4;
                const auto space = t.find("color_space");
                const std::string color_space = space == t.end() ? "Non-Color" : space->get<std::string>();
                if (color_space != "Non-Color" && color_space != "sRGB")
                    throw std::runtime_error("texture color_space '" + color_space +
                                             "' is not Non-Color or sRGB");
                d.color_space = color_space == "sRGB" ? "sRGB" : "Non-Color";
                d.interpolation = field<int32_t>(t, "interpolation");
                d.extension = field<int32_t>(t, "extension");
                if ((status = stratum_scene_add_texture(scene, &d, nullptr)) != STRATUM_OK)
                    return entry_point_failed(status);
            }
            for (const json& b : j.at("textures").at("bindings")) {
                StratumTextureBinding d{};
                d.material_id = field<uint32_t>(b, "material");
                d.closure_index = field<uint32_t>(b, "closure");
                d.param = field<int32_t>(b, "param");
                d.texture_id = field<uint32_t>(b, "texture");
                d.channel = field<int32_t>(b, "channel");
                d.scale = field<float>(b, "scale");
                d.offset = field<float>(b, "offset");
                if ((status = stratum_scene_bind_texture(scene, &d)) != STRATUM_OK)
                    return entry_point_failed(status);
            }
        }
        if ((status = load_programs(j, scene, version)) != STRATUM_OK) return entry_point_failed(status);
        if (j.contains("environment") && j.at("environment").contains("program")) {
            const json& e = j.at("environment");
            const json& p = e.at("program");
            if ((status = stratum_scene_set_background_program(
                     scene, field<uint32_t>(p, "program"), field<uint32_t>(p, "register"),
                     field<uint32_t>(e, "width"), field<uint32_t>(e, "height"))) != STRATUM_OK)
                return entry_point_failed(status);
        }
        return STRATUM_OK;
    } catch (const std::exception& e) {
        *error = std::string("malformed scene: ") + e.what();
        return STRATUM_ERROR_IO;
    }
}

}  // namespace stratum
