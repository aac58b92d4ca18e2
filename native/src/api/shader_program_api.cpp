// The shader-program entry points (stratum/shader_nodes.h).
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "api/abi_guard.h"
#include "api/scene_handle.h"
#include "api/shader_program_validation.h"
#include "render_scene/world_baking.h"
#include "shading/light_path_state.h"
#include "shading/program_layout.h"
#include "stratum/stratum.h"

// The layers below the API use shading/program_layout.h's copy of the public values.
static_assert(stratum::shader_input::kPosition == STRATUM_INPUT_POSITION);
static_assert(stratum::shader_input::kNormal == STRATUM_INPUT_NORMAL);
static_assert(stratum::shader_input::kTrueNormal == STRATUM_INPUT_TRUE_NORMAL);
static_assert(stratum::shader_input::kIncoming == STRATUM_INPUT_INCOMING);
static_assert(stratum::shader_input::kUv == STRATUM_INPUT_UV);
static_assert(stratum::shader_input::kGenerated == STRATUM_INPUT_GENERATED);
static_assert(stratum::shader_input::kObject == STRATUM_INPUT_OBJECT);
static_assert(stratum::shader_input::kCamera == STRATUM_INPUT_CAMERA);
static_assert(stratum::shader_input::kWindow == STRATUM_INPUT_WINDOW);
static_assert(stratum::shader_input::kObjectLocation == STRATUM_INPUT_OBJECT_LOCATION);
static_assert(stratum::shader_input::kBackfacing == STRATUM_INPUT_BACKFACING);
static_assert(stratum::shader_input::kObjectRandom == STRATUM_INPUT_OBJECT_RANDOM);
static_assert(stratum::shader_input::kRayLength == STRATUM_INPUT_RAY_LENGTH);
static_assert(stratum::shader_input::kObjectIndex == STRATUM_INPUT_OBJECT_INDEX);
static_assert(stratum::shader_input::kMaterialIndex == STRATUM_INPUT_MATERIAL_INDEX);
static_assert(stratum::shader_input::kObjectColor == STRATUM_INPUT_OBJECT_COLOR);
static_assert(stratum::shader_input::kObjectAlpha == STRATUM_INPUT_OBJECT_ALPHA);
static_assert(stratum::shader_input::kTangent == STRATUM_INPUT_TANGENT);
static_assert(stratum::shader_input::kParametric == STRATUM_INPUT_PARAMETRIC);
static_assert(stratum::shader_input::kObjectNormal == STRATUM_INPUT_OBJECT_NORMAL);
static_assert(stratum::shader_input::kDpdx == STRATUM_INPUT_DPDX);
static_assert(stratum::shader_input::kDpdy == STRATUM_INPUT_DPDY);
static_assert(stratum::shader_input::kDgeneratedDx == STRATUM_INPUT_DGENERATED_DX);
static_assert(stratum::shader_input::kDgeneratedDy == STRATUM_INPUT_DGENERATED_DY);
static_assert(stratum::shader_input::kDobjectDx == STRATUM_INPUT_DOBJECT_DX);
static_assert(stratum::shader_input::kDobjectDy == STRATUM_INPUT_DOBJECT_DY);
static_assert(stratum::shader_input::kDuvDx == STRATUM_INPUT_DUV_DX);
static_assert(stratum::shader_input::kDuvDy == STRATUM_INPUT_DUV_DY);
static_assert(stratum::shader_input::kReflection == STRATUM_INPUT_REFLECTION);
static_assert(stratum::shader_input::kUvTangent == STRATUM_INPUT_UV_TANGENT);
static_assert(stratum::shader_input::kPixelFootprint == STRATUM_INPUT_PIXEL_FOOTPRINT);
static_assert(stratum::shader_input::kAttribute0 == STRATUM_INPUT_ATTRIBUTE_0);
static_assert(stratum::shader_input::kAttribute3 == STRATUM_INPUT_ATTRIBUTE_3);
static_assert(stratum::shader_input::kTriangle == STRATUM_INPUT_TRIANGLE);
static_assert(stratum::shader_input::kMikktspaceTangent == STRATUM_INPUT_MIKKTSPACE_TANGENT);
static_assert(stratum::shader_input::kNormalTransform == STRATUM_INPUT_NORMAL_TRANSFORM);
static_assert(stratum::shader_input::kIsCameraRay == STRATUM_INPUT_IS_CAMERA_RAY);
static_assert(stratum::shader_input::kIsShadowRay == STRATUM_INPUT_IS_SHADOW_RAY);
static_assert(stratum::shader_input::kIsDiffuseRay == STRATUM_INPUT_IS_DIFFUSE_RAY);
static_assert(stratum::shader_input::kIsGlossyRay == STRATUM_INPUT_IS_GLOSSY_RAY);
static_assert(stratum::shader_input::kIsSingularRay == STRATUM_INPUT_IS_SINGULAR_RAY);
static_assert(stratum::shader_input::kIsReflectionRay == STRATUM_INPUT_IS_REFLECTION_RAY);
static_assert(stratum::shader_input::kIsTransmissionRay == STRATUM_INPUT_IS_TRANSMISSION_RAY);
static_assert(stratum::shader_input::kIsVolumeScatterRay == STRATUM_INPUT_IS_VOLUME_SCATTER_RAY);
static_assert(stratum::shader_input::kRayDepth == STRATUM_INPUT_RAY_DEPTH);
static_assert(stratum::shader_input::kDiffuseDepth == STRATUM_INPUT_DIFFUSE_DEPTH);
static_assert(stratum::shader_input::kGlossyDepth == STRATUM_INPUT_GLOSSY_DEPTH);
static_assert(stratum::shader_input::kTransparentDepth == STRATUM_INPUT_TRANSPARENT_DEPTH);
static_assert(stratum::shader_input::kTransmissionDepth == STRATUM_INPUT_TRANSMISSION_DEPTH);
static_assert(stratum::shader_input::kPortalDepth == STRATUM_INPUT_PORTAL_DEPTH);
static_assert(stratum::shader_input::kAttributeSlots == STRATUM_ATTRIBUTE_SLOTS);
static_assert(stratum::shader_input::kCount == STRATUM_SHADER_INPUT_REGISTERS);

namespace {

// Program `program_id` of the scene and the scene's textures (shared, so that the program runs
// outside the scene's lock); throws naming a program id the scene does not have.
std::pair<std::shared_ptr<const stratum::ShaderProgram>, std::vector<std::shared_ptr<const stratum::Texture>>>
program_and_textures(const StratumScene& scene, uint32_t program_id) {
    return scene.live->read([&](const stratum::Scene& s) {
        stratum::require(program_id < s.programs.size(), "program_id " + std::to_string(program_id) +
                                                             " is not a program (the scene has " +
                                                             std::to_string(s.programs.size()) + ")");
        return std::make_pair(s.programs[program_id], s.textures);
    });
}

}  // namespace

extern "C" {

StratumStatus stratum_scene_add_shader_program(StratumScene* scene, const StratumShaderProgramDesc* program,
                                               uint32_t* out_id) {
    using namespace stratum::abi;
    return guarded("stratum_scene_add_shader_program", [&] {
        require(scene && program, "scene or program is NULL");
        const size_t textures = scene->live->read([](const stratum::Scene& s) { return s.textures.size(); });
        auto checked = stratum::validate_shader_program(*program, textures);
        const uint32_t id = scene->live->edit(stratum::LiveScene::Part::Materials, [&](stratum::Scene& s) {
            s.programs.push_back(std::move(checked));
            return static_cast<uint32_t>(s.programs.size() - 1);
        });
        if (out_id) *out_id = id;
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_set_shader_program(StratumScene* scene, uint32_t program_id,
                                               const StratumShaderProgramDesc* program) {
    using namespace stratum::abi;
    return guarded("stratum_scene_set_shader_program", [&] {
        require(scene && program, "scene or program is NULL");
        const size_t textures = scene->live->read([&](const stratum::Scene& s) {
            require(program_id < s.programs.size(), "program_id " + std::to_string(program_id) +
                                                        " is not a program (the scene has " +
                                                        std::to_string(s.programs.size()) + ")");
            return s.textures.size();
        });
        auto checked = stratum::validate_shader_program(*program, textures);
        scene->live->edit(stratum::LiveScene::Part::Materials,
                          [&](stratum::Scene& s) { s.programs[program_id] = std::move(checked); });
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_bind_program(StratumScene* scene, const StratumProgramBinding* binding) {
    using namespace stratum::abi;
    return guarded("stratum_scene_bind_program", [&] {
        require(scene && binding, "scene or binding is NULL");
        scene->live->edit(stratum::LiveScene::Part::Structure, [&](stratum::Scene& s) {
            const stratum::ProgramBinding b = stratum::validate_program_binding(*binding, s);
            for (stratum::ProgramBinding& existing : s.program_bindings) {
                if (existing.material_id == b.material_id && existing.closure_index == b.closure_index &&
                    existing.param == b.param) {
                    existing = b;
                    return;
                }
            }
            s.program_bindings.push_back(b);
        });
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_set_background_program(StratumScene* scene, uint32_t program_id,
                                                   uint32_t register_index, uint32_t width, uint32_t height) {
    using namespace stratum::abi;
    return guarded("stratum_scene_set_background_program", [&] {
        require(scene, "scene is NULL");
        require(width >= 4 && width <= 16384,
                "background width " + std::to_string(width) + " is outside [4, 16384]");
        require(height >= 2 && height <= 8192,
                "background height " + std::to_string(height) + " is outside [2, 8192]");
        const auto [program, textures] = program_and_textures(*scene, program_id);
        require(static_cast<uint64_t>(register_index) + 3 <= program->registers.size(),
                "background register " + std::to_string(register_index) + " (3 wide) is outside program " +
                    std::to_string(program_id) + "'s " + std::to_string(program->registers.size()) +
                    " registers");
        // Baked outside the scene's lock: a large map takes a while, and renders may be reading.
        stratum::Environment e = stratum::bake_environment(*program, textures, register_index, width, height);
        if (stratum::reads_light_path(*program)) {
            e.program = program;
            e.program_color = register_index;
            e.program_textures = textures;
        }
        scene->live->edit(stratum::LiveScene::Part::World,
                          [&](stratum::Scene& s) { s.environment = std::move(e); });
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_set_light_program(StratumScene* scene, uint32_t light_id, uint32_t program_id,
                                              uint32_t register_index) {
    using namespace stratum::abi;
    return guarded("stratum_scene_set_light_program", [&] {
        require(scene, "scene is NULL");
        scene->live->edit(stratum::LiveScene::Part::Lights, [&](stratum::Scene& s) {
            auto& programs = s.light_programs;
            const auto same_light = [&](const stratum::LightProgram& p) { return p.light_id == light_id; };
            if (program_id == STRATUM_NO_PROGRAM) {
                require(light_id < s.lights.size(), "light_id " + std::to_string(light_id) +
                                                        " is not a light (the scene has " +
                                                        std::to_string(s.lights.size()) + ")");
                std::erase_if(programs, same_light);
                return;
            }
            const stratum::LightProgram p =
                stratum::validate_light_program(light_id, program_id, register_index, s);
            const auto existing = std::find_if(programs.begin(), programs.end(), same_light);
            if (existing != programs.end())
                *existing = p;
            else
                programs.push_back(p);
        });
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_set_mesh_texture_space(StratumScene* scene, uint32_t mesh_id,
                                                   const float location[3], const float size[3]) {
    using namespace stratum::abi;
    return guarded("stratum_scene_set_mesh_texture_space", [&] {
        require(scene && location && size, "scene, location or size is NULL");
        stratum::Vec3 loc(location[0], location[1], location[2]), half(size[0], size[1], size[2]);
        for (int k = 0; k < 3; ++k) {
            require(std::isfinite(location[k]) && std::abs(location[k]) <= 1e12f,
                    "texture space location[" + std::to_string(k) + "] = " + std::to_string(location[k]) +
                        " is not a finite value within 1e12");
            require(std::isfinite(size[k]) && std::abs(size[k]) <= 1e12f,
                    "texture space size[" + std::to_string(k) + "] = " + std::to_string(size[k]) +
                        " is not a finite value within 1e12");
        }
        half = stratum::texture_space_half_size(half);
        scene->live->edit(stratum::LiveScene::Part::Structure, [&](stratum::Scene& s) {
            require(mesh_id < s.meshes.size(), "mesh_id " + std::to_string(mesh_id) +
                                                   " is not a mesh (the scene has " +
                                                   std::to_string(s.meshes.size()) + ")");
            s.meshes[mesh_id].texture_space = std::array<stratum::Vec3, 2>{loc, half};
        });
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_set_mesh_attribute(StratumScene* scene, uint32_t mesh_id, uint32_t slot,
                                               int32_t kind, const float* corner_rgba,
                                               uint32_t triangle_count) {
    using namespace stratum::abi;
    return guarded("stratum_scene_set_mesh_attribute", [&] {
        require(scene && corner_rgba, "scene or corner_rgba is NULL");
        require(slot < STRATUM_ATTRIBUTE_SLOTS,
                "attribute slot " + std::to_string(slot) + " is outside [0, 3]");
        require(kind == STRATUM_ATTRIBUTE_SCALAR || kind == STRATUM_ATTRIBUTE_VECTOR,
                "attribute kind " + std::to_string(kind) + " is not a StratumAttributeKind (0 or 1)");
        const size_t count = static_cast<size_t>(triangle_count) * 12;
        for (size_t i = 0; i < count; ++i)
            require(std::isfinite(corner_rgba[i]), "attribute value " + std::to_string(i) + " = " +
                                                       std::to_string(corner_rgba[i]) + " is not finite");
        scene->live->edit(stratum::LiveScene::Part::Structure, [&](stratum::Scene& s) {
            require(mesh_id < s.meshes.size(), "mesh_id " + std::to_string(mesh_id) +
                                                   " is not a mesh (the scene has " +
                                                   std::to_string(s.meshes.size()) + ")");
            stratum::Mesh& mesh = s.meshes[mesh_id];
            require(triangle_count == mesh.triangles.size(),
                    "attribute triangle_count " + std::to_string(triangle_count) + " is not mesh " +
                        std::to_string(mesh_id) + "'s " + std::to_string(mesh.triangles.size()));
            mesh.attributes[slot] = {std::vector<float>(corner_rgba, corner_rgba + count), kind};
        });
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_evaluate_program(const StratumScene* scene, uint32_t program_id,
                                             const float* inputs, uint32_t first, uint32_t count,
                                             float* out) {
    using namespace stratum::abi;
    return guarded("stratum_scene_evaluate_program", [&] {
        require(scene && inputs && (out || count == 0), "scene, inputs or out is NULL");
        const auto [program, textures] = program_and_textures(*scene, program_id);
        require(static_cast<uint64_t>(first) + count <= program->registers.size(),
                "registers [" + std::to_string(first) + ", +" + std::to_string(count) +
                    ") are outside program " + std::to_string(program_id) + "'s " +
                    std::to_string(program->registers.size()) + " registers");
        stratum::ShaderRegisters r(*program);
        std::copy(inputs, inputs + stratum::kShaderInputRegisters, r.data());
        stratum::evaluate(*program, stratum::ShaderEvalContext{program.get(), &textures}, r);
        std::copy(r.data() + first, r.data() + first + count, out);
        return STRATUM_OK;
    });
}

}  // extern "C"
