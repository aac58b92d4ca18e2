// The fuzzer's program: a sequence of operations over the C ABI read from the input
// (native/fuzz/README.md). The state is what a host keeps between calls: one scene, at most one
// renderer, and the counts it needs to choose mostly valid ids.
#pragma once

#include <cstdint>
#include <vector>

#include "byte_reader.h"
#include "stratum/stratum.h"

namespace stratum::fuzz {

struct ProgramState {
    StratumScene* scene = nullptr;
    StratumRenderer* renderer = nullptr;
    std::vector<uint32_t> closures;  // closure count of each material, in id order
    uint32_t meshes = 0, textures = 0, instances = 0, lights = 0, programs = 0;
    // The renderer's border region as last accepted (crop_width 0 = the whole frame), to know
    // how many pixels a finished render has.
    uint32_t crop_width = 0, crop_height = 0;
    uint32_t width = 0, height = 0;  // the frame size the last render was given
    unsigned renders = 0, throughputs = 0;

    ProgramState() = default;
    ProgramState(const ProgramState&) = delete;
    ProgramState& operator=(const ProgramState&) = delete;
    ~ProgramState();

    uint32_t materials() const { return static_cast<uint32_t>(closures.size()); }
    // Replaces the scene (the renderer, which copied it, lives on) and forgets its counts.
    void new_scene();
};

// Limits that keep one execution to milliseconds: scene sizes, and renders of at most 8 x 8
// pixels, 2 samples and 4 bounces.
inline constexpr unsigned kMaxOperations = 64;
inline constexpr unsigned kMaxRenders = 3;
inline constexpr unsigned kMaxThroughputs = 2;
inline constexpr uint32_t kMaxTextures = 6;
inline constexpr uint32_t kMaxMeshes = 12;
inline constexpr uint32_t kMaxInstances = 24;
inline constexpr uint32_t kMaxLights = 12;
inline constexpr uint32_t kMaxMaterials = 16;

void run_program(ByteReader& in);

// The names of a CHOICE or LIST setting's choices, in menu order, read from the library
// (stratum_setting_choice); empty for an unknown setting.
std::vector<const char*> setting_choice_names(const char* setting);

// The operations, one per opcode (scene_ops.cpp, render_ops.cpp, library_ops.cpp).
void op_add_material(ByteReader& in, ProgramState& s);
void op_add_closure_material(ByteReader& in, ProgramState& s);
void op_add_texture(ByteReader& in, ProgramState& s);
void op_bind_texture(ByteReader& in, ProgramState& s);
void op_add_mesh(ByteReader& in, ProgramState& s);
void op_add_instance(ByteReader& in, ProgramState& s);
void op_add_instance_ex(ByteReader& in, ProgramState& s);
void op_add_light(ByteReader& in, ProgramState& s);
void op_set_camera(ByteReader& in, ProgramState& s);
void op_set_background(ByteReader& in, ProgramState& s);
void op_set_environment(ByteReader& in, ProgramState& s);
void op_new_scene(ByteReader& in, ProgramState& s);
void op_save_load(ByteReader& in, ProgramState& s);
void op_render(ByteReader& in, ProgramState& s);
void op_rerender(ByteReader& in, ProgramState& s);
void op_measure_throughput(ByteReader& in, ProgramState& s);
void op_sampling(ByteReader& in, ProgramState& s);
void op_models(ByteReader& in, ProgramState& s);
void op_add_instances(ByteReader& in, ProgramState& s);
void op_vertex_normals(ByteReader& in, ProgramState& s);
void op_add_shader_program(ByteReader& in, ProgramState& s);  // program_ops.cpp
void op_bind_program(ByteReader& in, ProgramState& s);
void op_set_light_program(ByteReader& in, ProgramState& s);

}  // namespace stratum::fuzz
