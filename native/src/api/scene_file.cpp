#include "api/scene_file.h"

#include <array>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

namespace stratum {

namespace {

using nlohmann::json;

constexpr const char* kFormat = "stratum-scene";
constexpr int kVersion = 1;

json rgb(Rgb c) { return json::array({c.r, c.g, c.b}); }
json matrix(const Transform& t) {
    json m = json::array();
    for (float v : t.m) m.push_back(v);
    for (float v : {0.0f, 0.0f, 0.0f, 1.0f}) m.push_back(v);
    return m;
}

template <typename T, size_t N>
void read_floats(const json& j, T (&out)[N]) {
    if (!j.is_array() || j.size() != N)
        throw std::runtime_error("expected " + std::to_string(N) + " numbers");
    for (size_t i = 0; i < N; ++i) out[i] = j[i].get<T>();
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
            {"coat_tint", rgb(m.coat_tint)}};
}

// The fields of one closure; those added with closures (transmission, coat) default to the
// all-zero "none" of StratumMaterialDesc when an older file lacks them.
StratumMaterialDesc material_desc(const json& m) {
    StratumMaterialDesc d{};
    d.model = m.at("model").get<int32_t>();
    read_floats(m.at("base_color"), d.base_color);
    d.roughness = m.at("roughness").get<float>();
    d.metallic = m.at("metallic").get<float>();
    d.specular = m.at("specular").get<float>();
    d.ior = m.at("ior").get<float>();
    read_floats(m.at("emission"), d.emission);
    d.distribution = m.at("distribution").get<int32_t>();
    d.transmission = m.value("transmission", 0.0f);
    d.coat = m.value("coat", 0.0f);
    d.coat_roughness = m.value("coat_roughness", 0.0f);
    d.coat_ior = m.value("coat_ior", 0.0f);
    if (m.contains("coat_tint")) read_floats(m.at("coat_tint"), d.coat_tint);
    return d;
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
        j["materials"].push_back({{"closures", closures}});
    }
    j["meshes"] = json::array();
    for (const Mesh& mesh : scene.meshes) {
        json pos = json::array(), tri = json::array(), nrm = json::array(), uv = json::array(),
             vnrm = json::array();
        for (Vec3 p : mesh.positions) pos.insert(pos.end(), {p.x, p.y, p.z});
        for (const auto& t : mesh.triangles) tri.insert(tri.end(), {t[0], t[1], t[2]});
        for (Vec3 n : mesh.corner_normals) nrm.insert(nrm.end(), {n.x, n.y, n.z});
        for (Vec3 n : mesh.vertex_normals) vnrm.insert(vnrm.end(), {n.x, n.y, n.z});
        for (Vec2 c : mesh.corner_uvs) uv.insert(uv.end(), {c.x, c.y});
        j["meshes"].push_back({{"positions", pos},
                               {"triangles", tri},
                               {"corner_normals", nrm},
                               {"vertex_normals", vnrm},
                               {"corner_uvs", uv},
                               {"material_ids", mesh.material_ids}});
    }
    j["instances"] = json::array();
    for (const Instance& i : scene.instances) {
        j["instances"].push_back({{"mesh", i.mesh_id},
                                  {"transform", matrix(i.object_to_world)},
                                  {"transform_end", matrix(i.object_to_world_end)},
                                  {"motion", i.motion ? 1 : 0},
                                  {"visibility", i.visibility},
                                  {"holdout", i.holdout ? 1 : 0}});
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
                               {"spread", l.spread}});
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
    if (scene.environment) {
        const Environment& e = *scene.environment;
        j["environment"] = {{"width", e.width},
                            {"height", e.height},
                            {"strength", e.strength},
                            {"rotation", e.rotation},
                            {"rgb", e.rgb}};
    }
    if (!scene.textures.empty()) {
        // Textures are saved decoded (linear RGBA, rows bottom to top) and reloaded as 4-channel
        // Non-Color pixels, so a file replays without the original images or OCIO config.
        json textures = json::array(), bindings = json::array();
        for (const auto& t : scene.textures) {
            textures.push_back({{"width", t->width},
                                {"height", t->height},
                                {"interpolation", static_cast<int>(t->interpolation)},
                                {"extension", static_cast<int>(t->extension)},
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
    std::ofstream out(path, std::ios::binary);
    if (!out) return std::string("cannot open '") + path + "' for writing";
    out << j.dump();
    return out.good() ? std::string() : std::string("cannot write '") + path + "'";
}

StratumStatus load_scene_file(const char* path, StratumScene* scene, std::string* error) {
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
        if (j.value("format", "") != kFormat || j.value("version", 0) != kVersion) {
            *error = std::string("not a ") + kFormat + " version " + std::to_string(kVersion) + " file";
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
                read_floats(c.at("weight"), cd.weight);
                cd.closure = material_desc(c);
                closures.push_back(cd);
            }
            if ((status = stratum_scene_add_closure_material(
                     scene, closures.data(), static_cast<uint32_t>(closures.size()), nullptr)) != STRATUM_OK)
                return entry_point_failed(status);
        }
        for (const json& m : j.at("meshes")) {
            const auto pos = m.at("positions").get<std::vector<float>>();
            const auto tri = m.at("triangles").get<std::vector<uint32_t>>();
            const auto nrm = m.at("corner_normals").get<std::vector<float>>();
            const auto uv = m.at("corner_uvs").get<std::vector<float>>();
            const auto vnrm = m.value("vertex_normals", std::vector<float>{});
            const auto mat = m.at("material_ids").get<std::vector<uint32_t>>();
            const size_t tris = tri.size() / 3;
            if (pos.size() % 3 || tri.size() % 3 || mat.size() != tris ||
                (!nrm.empty() && nrm.size() != 9 * tris) || (!uv.empty() && uv.size() != 6 * tris) ||
                (!vnrm.empty() && vnrm.size() != pos.size())) {
                throw std::runtime_error("mesh arrays have inconsistent sizes");
            }
            const StratumMeshDesc d{pos.data(),
                                    static_cast<uint32_t>(pos.size() / 3),
                                    tri.data(),
                                    static_cast<uint32_t>(tris),
                                    nrm.empty() ? nullptr : nrm.data(),
                                    uv.empty() ? nullptr : uv.data(),
                                    mat.data(),
                                    vnrm.empty() ? nullptr : vnrm.data()};
            if ((status = stratum_scene_add_mesh(scene, &d, nullptr)) != STRATUM_OK)
                return entry_point_failed(status);
        }
        for (const json& i : j.at("instances")) {
            StratumInstanceDesc d{};
            d.mesh_id = i.at("mesh").get<uint32_t>();
            read_floats(i.at("transform"), d.transform);
            // Files written before motion blur and ray visibility: a static instance seen by all rays.
            d.motion = i.value("motion", 0);
            if (d.motion) read_floats(i.at("transform_end"), d.transform_end);
            d.visibility = i.value("visibility", static_cast<uint32_t>(STRATUM_VISIBLE_ALL));
            d.holdout = i.value("holdout", 0);
            if ((status = stratum_scene_add_instance_ex(scene, &d)) != STRATUM_OK)
                return entry_point_failed(status);
        }
        for (const json& l : j.at("lights")) {
            StratumLightDesc d{};
            d.type = l.at("type").get<int32_t>();
            read_floats(l.at("color"), d.color);
            d.strength = l.at("strength").get<float>();
            d.radius = l.at("radius").get<float>();
            d.angle = l.at("angle").get<float>();
            d.size_x = l.at("size").at(0).get<float>();
            d.size_y = l.at("size").at(1).get<float>();
            // Files written before spot lights have no "spot": the defaults of LightParams.
            const json spot = l.value("spot", json::array({kPi, 0.0f}));
            d.spot_size = spot.at(0).get<float>();
            d.spot_blend = spot.at(1).get<float>();
            read_floats(l.at("transform"), d.transform);
            // Absent in older files: 0 reads as all rays and as spread pi.
            d.visibility = l.value("visibility", 0u);
            d.spread = l.value("spread", 0.0f);
            if ((status = stratum_scene_add_light(scene, &d)) != STRATUM_OK)
                return entry_point_failed(status);
        }
        if (j.contains("camera")) {
            const json& c = j["camera"];
            StratumCameraDesc d{};
            d.lens_mm = c.at("lens_mm").get<float>();
            d.sensor_width_mm = c.at("sensor_mm").at(0).get<float>();
            d.sensor_height_mm = c.at("sensor_mm").at(1).get<float>();
            d.sensor_fit = c.at("sensor_fit").get<int32_t>();
            d.shift_x = c.at("shift").at(0).get<float>();
            d.shift_y = c.at("shift").at(1).get<float>();
            d.clip_start = c.at("clip").at(0).get<float>();
            d.clip_end = c.at("clip").at(1).get<float>();
            read_floats(c.at("transform"), d.transform);
            // Absent in files written before orthographic and thin-lens cameras: a pinhole.
            d.type = c.value("type", 0);
            d.ortho_scale = c.value("ortho_scale", 0.0f);
            d.aperture_radius = c.value("aperture_radius", 0.0f);
            d.focus_distance = c.value("focus_distance", 0.0f);
            d.aperture_blades = c.value("aperture_blades", 0);
            d.aperture_rotation = c.value("aperture_rotation", 0.0f);
            const json latitude = c.value("latitude", json::array({-0.5f * kPi, 0.5f * kPi}));
            const json longitude = c.value("longitude", json::array({-kPi, kPi}));
            d.latitude_min = latitude.at(0).get<float>();
            d.latitude_max = latitude.at(1).get<float>();
            d.longitude_min = longitude.at(0).get<float>();
            d.longitude_max = longitude.at(1).get<float>();
            if ((status = stratum_scene_set_camera(scene, &d)) != STRATUM_OK)
                return entry_point_failed(status);
        }
        float bg[3];
        read_floats(j.at("background"), bg);
        if ((status = stratum_scene_set_background(scene, bg)) != STRATUM_OK)
            return entry_point_failed(status);
        if (j.contains("environment")) {
            const json& e = j.at("environment");
            const auto rgb = e.at("rgb").get<std::vector<float>>();
            const auto rotation = e.at("rotation").get<std::array<float, 9>>();
            const auto width = e.at("width").get<uint32_t>(), height = e.at("height").get<uint32_t>();
            if (rgb.size() != static_cast<size_t>(width) * height * 3) {
                *error = "malformed scene: environment rgb has " + std::to_string(rgb.size()) +
                         " values, expected " + std::to_string(static_cast<size_t>(width) * height * 3);
                return STRATUM_ERROR_IO;
            }
            if ((status = stratum_scene_set_environment(scene, rgb.data(), width, height,
                                                        e.at("strength").get<float>(), rotation.data())) !=
                STRATUM_OK)
                return entry_point_failed(status);
        }
        if (j.contains("textures")) {
            for (const json& t : j.at("textures").at("images")) {
                const auto rgba = t.at("rgba").get<std::vector<float>>();
                StratumTextureDesc d{};
                d.width = t.at("width").get<uint32_t>();
                d.height = t.at("height").get<uint32_t>();
                if (rgba.size() != static_cast<size_t>(d.width) * d.height * 4) {
                    *error = "malformed scene: texture rgba has " + std::to_string(rgba.size()) +
                             " values, expected " +
                             std::to_string(static_cast<size_t>(d.width) * d.height * 4);
                    return STRATUM_ERROR_IO;
                }
                d.pixels = rgba.data();
                d.channels = 4;
                d.color_space = "Non-Color";
                d.interpolation = t.at("interpolation").get<int32_t>();
                d.extension = t.at("extension").get<int32_t>();
                if ((status = stratum_scene_add_texture(scene, &d, nullptr)) != STRATUM_OK)
                    return entry_point_failed(status);
            }
            for (const json& b : j.at("textures").at("bindings")) {
                StratumTextureBinding d{};
                d.material_id = b.at("material").get<uint32_t>();
                d.closure_index = b.at("closure").get<uint32_t>();
                d.param = b.at("param").get<int32_t>();
                d.texture_id = b.at("texture").get<uint32_t>();
                d.channel = b.at("channel").get<int32_t>();
                d.scale = b.at("scale").get<float>();
                d.offset = b.at("offset").get<float>();
                if ((status = stratum_scene_bind_texture(scene, &d)) != STRATUM_OK)
                    return entry_point_failed(status);
            }
        }
        return STRATUM_OK;
    } catch (const std::exception& e) {
        *error = std::string("malformed scene: ") + e.what();
        return STRATUM_ERROR_IO;
    }
}

}  // namespace stratum
