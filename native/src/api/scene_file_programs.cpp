#include "api/scene_file_programs.h"

#include <vector>

#include "api/scene_file_numbers.h"

namespace stratum {

using nlohmann::json;
using scene_file::field;
using scene_file::numbers;

void save_programs(const Scene& scene, json& j) {
    json spaces = json::array();
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        if (!scene.meshes[m].texture_space) continue;
        const auto& [loc, size] = *scene.meshes[m].texture_space;
        spaces.push_back(
            {{"mesh", m}, {"location", {loc.x, loc.y, loc.z}}, {"size", {size.x, size.y, size.z}}});
    }
    if (!spaces.empty()) j["texture_spaces"] = spaces;
    json attributes = json::array();
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        for (size_t slot = 0; slot < scene.meshes[m].attributes.size(); ++slot) {
            const Mesh::CornerAttribute& a = scene.meshes[m].attributes[slot];
            if (a.rgba.empty()) continue;
            attributes.push_back({{"mesh", m}, {"slot", slot}, {"kind", a.kind}, {"rgba", a.rgba}});
        }
    }
    if (!attributes.empty()) j["mesh_attributes"] = attributes;
    if (scene.programs.empty()) return;
    json programs = json::array(), bindings = json::array();
    for (const auto& p : scene.programs) {
        // One row of 32 integers per node: type, modes[6], inputs[12], outputs[6], data range.
        json nodes = json::array();
        for (const ShaderNode& n : p->nodes) {
            json row = json::array({n.type});
            for (int32_t v : n.modes) row.push_back(v);
            for (uint32_t v : n.inputs) row.push_back(v);
            for (uint32_t v : n.outputs) row.push_back(v);
            row.push_back(n.data_offset);
            row.push_back(n.data_count);
            nodes.push_back(row);
        }
        programs.push_back({{"nodes", nodes}, {"registers", p->registers}, {"data", p->data}});
    }
    for (const ProgramBinding& b : scene.program_bindings) {
        bindings.push_back({{"material", b.material_id},
                            {"closure", b.closure_index},
                            {"param", static_cast<int>(b.param)},
                            {"program", b.program_id},
                            {"register", b.register_index}});
    }
    json lights = json::array();
    for (const LightProgram& l : scene.light_programs)
        lights.push_back({{"light", l.light_id}, {"program", l.program_id}, {"register", l.register_index}});
    j["programs"] = {{"programs", programs}, {"bindings", bindings}};
    if (!lights.empty()) j["programs"]["lights"] = lights;
}

namespace {

// The input registers of a version `version` file (STRATUM_SHADER_INPUT_REGISTERS then).
uint32_t file_inputs(int version) {
    if (version == 1) return 100;
    if (version == 2) return 128;
    return STRATUM_SHADER_INPUT_REGISTERS;
}

// A register number of a version `version` file, as today's layout numbers it.
uint32_t moved(uint32_t reg, int version) {
    const uint32_t inputs = file_inputs(version);
    if (reg < inputs) return reg;
    return reg - inputs + STRATUM_SHADER_INPUT_REGISTERS;
}

}  // namespace

StratumStatus load_programs(const json& j, StratumScene* scene, int version) {
    StratumStatus status = STRATUM_OK;
    if (j.contains("texture_spaces")) {
        for (const json& t : j.at("texture_spaces")) {
            const auto loc = numbers<float>(t, "location"), size = numbers<float>(t, "size");
            if (loc.size() != 3 || size.size() != 3)
                throw std::runtime_error("texture space needs 3 + 3 numbers");
            status = stratum_scene_set_mesh_texture_space(scene, field<uint32_t>(t, "mesh"), loc.data(),
                                                          size.data());
            if (status != STRATUM_OK) return status;
        }
    }
    if (j.contains("mesh_attributes")) {
        for (const json& a : j.at("mesh_attributes")) {
            const auto rgba = numbers<float>(a, "rgba");
            if (rgba.size() % 12) throw std::runtime_error("mesh attribute needs 12 numbers per triangle");
            status = stratum_scene_set_mesh_attribute(scene, field<uint32_t>(a, "mesh"),
                                                      field<uint32_t>(a, "slot"), field<int32_t>(a, "kind"),
                                                      rgba.data(), static_cast<uint32_t>(rgba.size() / 12));
            if (status != STRATUM_OK) return status;
        }
    }
    if (!j.contains("programs")) return STRATUM_OK;
    for (const json& p : j.at("programs").at("programs")) {
        std::vector<StratumShaderNode> nodes;
        for (const json& row : p.at("nodes")) {
            if (!row.is_array() || row.size() != 27)
                throw std::runtime_error("a program node needs 27 numbers");
            StratumShaderNode n{};
            size_t k = 0;
            const auto next_int = [&] { return scene_file::number<int32_t>(row.at(k++), "program node"); };
            const auto next_uint = [&] { return scene_file::number<uint32_t>(row.at(k++), "program node"); };
            n.type = next_int();
            for (int32_t& v : n.modes) v = next_int();
            for (uint32_t& v : n.inputs) v = moved(next_uint(), version);
            for (uint32_t& v : n.outputs) v = moved(next_uint(), version);
            n.data_offset = next_uint();
            n.data_count = next_uint();
            nodes.push_back(n);
        }
        auto registers = numbers<float>(p, "registers");
        const uint32_t inputs = file_inputs(version);
        if (inputs < STRATUM_SHADER_INPUT_REGISTERS && registers.size() >= inputs)
            registers.insert(registers.begin() + inputs, STRATUM_SHADER_INPUT_REGISTERS - inputs, 0.0f);
        const auto data = numbers<float>(p, "data");
        const StratumShaderProgramDesc d{nodes.data(),     static_cast<uint32_t>(nodes.size()),
                                         registers.data(), static_cast<uint32_t>(registers.size()),
                                         data.data(),      static_cast<uint32_t>(data.size())};
        if ((status = stratum_scene_add_shader_program(scene, &d, nullptr)) != STRATUM_OK) return status;
    }
    for (const json& b : j.at("programs").at("bindings")) {
        const StratumProgramBinding d{field<uint32_t>(b, "material"), field<uint32_t>(b, "closure"),
                                      field<int32_t>(b, "param"), field<uint32_t>(b, "program"),
                                      moved(field<uint32_t>(b, "register"), version)};
        if ((status = stratum_scene_bind_program(scene, &d)) != STRATUM_OK) return status;
    }
    if (j.at("programs").contains("lights")) {
        for (const json& l : j.at("programs").at("lights")) {
            status = stratum_scene_set_light_program(scene, field<uint32_t>(l, "light"),
                                                     field<uint32_t>(l, "program"),
                                                     moved(field<uint32_t>(l, "register"), version));
            if (status != STRATUM_OK) return status;
        }
    }
    return STRATUM_OK;
}

}  // namespace stratum
