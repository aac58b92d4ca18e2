#include "program.h"

#include <string>

#include "checked_call.h"

namespace stratum::fuzz {

ProgramState::~ProgramState() {
    // The renderer first: destroying it cancels and joins its render.
    if (renderer) {
        if (tracing()) trace_line("stratum_renderer_destroy(renderer)");
        stratum_renderer_destroy(renderer);
    }
    if (scene) {
        if (tracing()) trace_line("stratum_scene_destroy(scene)");
        stratum_scene_destroy(scene);
    }
}

void ProgramState::new_scene() {
    if (scene) {
        if (tracing()) trace_line("stratum_scene_destroy(scene)");
        stratum_scene_destroy(scene);
        scene = nullptr;
    }
    closures.clear();
    meshes = textures = instances = lights = programs = 0;
    if (checked(
            "stratum_scene_create", [&] { return stratum_scene_create(&scene); }, [] { return "&scene"; }) !=
        STRATUM_OK)
        finding("stratum_scene_create failed");
    if (!scene) finding("stratum_scene_create returned STRATUM_OK and a NULL scene");
}

std::vector<const char*> setting_choice_names(const char* setting) {
    std::vector<const char*> names;
    for (int32_t i = 0; i < stratum_setting_count(); ++i) {
        StratumSettingInfo info{};
        if (stratum_setting_info(i, &info) != STRATUM_OK || std::string(info.name) != setting) continue;
        for (int32_t c = 0; c < info.choice_count; ++c) {
            const char* name = nullptr;
            if (stratum_setting_choice(i, c, &name, nullptr, nullptr) == STRATUM_OK) names.push_back(name);
        }
    }
    return names;
}

void run_program(ByteReader& in) {
    using Operation = void (*)(ByteReader&, ProgramState&);
    // The opcode is the operation's index; the order is part of the corpus encoding (README).
    static constexpr Operation kOperations[] = {
        op_add_material,    op_add_closure_material,
        op_add_texture,     op_bind_texture,
        op_add_mesh,        op_add_instance,
        op_add_instance_ex, op_add_light,
        op_set_camera,      op_set_background,
        op_set_environment, op_new_scene,
        op_save_load,       op_render,
        op_rerender,        op_measure_throughput,
        op_sampling,        op_models,
    };
    constexpr size_t kCount = sizeof kOperations / sizeof kOperations[0];
    // Operations added later take the top byte values, which the modulo gave to the first
    // operations: every committed input that does not use them replays as it was written.
    constexpr uint8_t kAddInstances = 254, kVertexNormals = 253, kAddShaderProgram = 252, kBindProgram = 251,
                      kSetLightProgram = 249;
    ProgramState state;
    state.new_scene();
    for (unsigned i = 0; i < kMaxOperations && !in.exhausted(); ++i) {
        const uint8_t opcode = in.u8();
        if (opcode == kAddInstances)
            op_add_instances(in, state);
        else if (opcode == kVertexNormals)
            op_vertex_normals(in, state);
        else if (opcode == kAddShaderProgram)
            op_add_shader_program(in, state);
        else if (opcode == kBindProgram)
            op_bind_program(in, state);
        else if (opcode == kSetLightProgram)
            op_set_light_program(in, state);
        else
            kOperations[opcode % kCount](in, state);
    }
}

}  // namespace stratum::fuzz
