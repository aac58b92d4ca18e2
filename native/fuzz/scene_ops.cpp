// The scene-building operations: each draws a description, calls the ABI and keeps the
// counts a host would keep. Descriptions are drawn even when a size limit skips the call, so
// the rest of the input reads the same.
#include <string>
#include <vector>

#include "checked_call.h"
#include "describe.h"
#include "descriptors.h"
#include "program.h"
#include "texture_sources.h"

namespace stratum::fuzz {

namespace {

// Ids are handed out 0, 1, 2, ... in order (stratum.h): a different id is a finding.
void expect_id(const char* call, uint32_t id, uint32_t expected) {
    if (id != expected)
        finding(std::string(call) + " returned id " + std::to_string(id) + ", expected " +
                std::to_string(expected));
}

std::string matrix_text(const float* m) { return describe_floats(m, 16); }

std::string describe_uints(const std::vector<uint32_t>& v) {
    std::string text;
    for (size_t i = 0; i < v.size(); ++i) text += (i ? ", " : "") + std::to_string(v[i]);
    return text;
}

}  // namespace

void op_add_material(ByteReader& in, ProgramState& s) {
    const StratumMaterialDesc d = draw_material(in);
    if (s.materials() >= kMaxMaterials) return;
    uint32_t id = UINT32_MAX;
    const StratumStatus status = checked(
        "stratum_scene_add_material", [&] { return stratum_scene_add_material(s.scene, &d, &id); },
        [&] { return "scene, &(StratumMaterialDesc)" + describe(d) + ", &id"; });
    if (status != STRATUM_OK) return;
    expect_id("stratum_scene_add_material", id, s.materials());
    s.closures.push_back(1);
}

void op_add_closure_material(ByteReader& in, ProgramState& s) {
    // 0 and kMaxClosures + 1 = 9 closures are refused. The count byte's tens are the material's
    // pass index (no new byte: the corpus keeps its meaning); 25 is one past the largest accepted.
    const uint8_t count_byte = in.u8();
    std::vector<StratumClosureDesc> closures(count_byte % 10);
    for (StratumClosureDesc& c : closures) {
        for (float& w : c.weight) w = in.f32(FloatKind::Unit);
        c.closure = draw_material(in);
    }
    if (s.materials() >= kMaxMaterials) return;
    const auto count = static_cast<uint32_t>(closures.size());
    uint32_t id = UINT32_MAX;
    const StratumStatus status = checked(
        "stratum_scene_add_closure_material",
        [&] {
            return stratum_scene_add_closure_material(s.scene, closures.empty() ? nullptr : closures.data(),
                                                      count, &id);
        },
        [&] {
            std::string text = "scene, (StratumClosureDesc[]){";
            for (const StratumClosureDesc& c : closures)
                text += "{" + describe_floats(c.weight, 3) + ", " + describe(c.closure) + "}, ";
            return text + "}, " + std::to_string(count) + ", &id";
        });
    if (status != STRATUM_OK) return;
    expect_id("stratum_scene_add_closure_material", id, s.materials());
    s.closures.push_back(count);
    const uint32_t pass_index = count_byte / 10 == 25 ? STRATUM_MAX_PASS_INDEX + 1 : count_byte / 10;
    checked(
        "stratum_scene_set_material_pass_index",
        [&] { return stratum_scene_set_material_pass_index(s.scene, id, pass_index); },
        [&] { return "scene, " + std::to_string(id) + ", " + std::to_string(pass_index); });
}

void op_add_texture(ByteReader& in, ProgramState& s) {
    TextureArrays t = draw_texture(in);
    t.bind();
    if (s.textures >= kMaxTextures) return;
    uint32_t id = UINT32_MAX;
    const StratumStatus status = checked(
        "stratum_scene_add_texture", [&] { return stratum_scene_add_texture(s.scene, &t.desc, &id); },
        [&] { return "scene, &(StratumTextureDesc)" + describe(t.desc) + ", &id"; });
    if (status != STRATUM_OK) return;
    expect_id("stratum_scene_add_texture", id, s.textures);
    ++s.textures;
    // The texture's info: a size the source can have and at most every texel replaced.
    StratumTextureInfo info{};
    if (checked(
            "stratum_scene_texture_info", [&] { return stratum_scene_texture_info(s.scene, id, &info); },
            [&] { return "scene, " + std::to_string(id) + ", &info"; }) != STRATUM_OK)
        finding("stratum_scene_texture_info failed for texture " + std::to_string(id));
    if (info.width == 0 || info.height == 0 ||
        info.replaced_texels > static_cast<uint64_t>(info.width) * info.height ||
        (t.use_pixels && (info.width != t.desc.width || info.height != t.desc.height))) {
        finding("stratum_scene_texture_info: " + std::to_string(info.width) + " x " +
                std::to_string(info.height) + " with " + std::to_string(info.replaced_texels) +
                " replaced texels");
    }
}

void op_bind_texture(ByteReader& in, ProgramState& s) {
    StratumTextureBinding b{};
    b.material_id = in.id(s.materials());
    b.closure_index = in.id(b.material_id < s.materials() ? s.closures[b.material_id] : 1);
    b.param = draw_enum(in, STRATUM_PARAM_SPECULAR + 1);
    b.texture_id = in.id(s.textures);
    b.channel = draw_enum(in, 5) - 1;
    b.scale = in.f32(FloatKind::Signed);
    b.offset = in.f32(FloatKind::Signed);
    b.emission_strength = in.u8() < 224 ? 0.0f : in.f32(FloatKind::Positive);
    checked(
        "stratum_scene_bind_texture", [&] { return stratum_scene_bind_texture(s.scene, &b); },
        [&] { return "scene, &(StratumTextureBinding)" + describe(b); });
}

void op_add_mesh(ByteReader& in, ProgramState& s) {
    const MeshArrays m = draw_mesh(in, s.materials());
    if (s.meshes >= kMaxMeshes) return;
    const StratumMeshDesc d = m.desc();
    uint32_t id = UINT32_MAX;
    const StratumStatus status = checked(
        "stratum_scene_add_mesh", [&] { return stratum_scene_add_mesh(s.scene, &d, &id); },
        [&] { return "scene, &(StratumMeshDesc)" + describe(d) + ", &id"; });
    if (status != STRATUM_OK) return;
    expect_id("stratum_scene_add_mesh", id, s.meshes);
    ++s.meshes;
}

void op_add_instance(ByteReader& in, ProgramState& s) {
    const uint32_t mesh = in.id(s.meshes);
    const Matrix m = draw_matrix(in, translation(0.0f, 0.0f, 0.0f));
    if (s.instances >= kMaxInstances) return;
    if (checked(
            "stratum_scene_add_instance", [&] { return stratum_scene_add_instance(s.scene, mesh, m.data()); },
            [&] { return "scene, " + std::to_string(mesh) + ", (float[16])" + matrix_text(m.data()); }) ==
        STRATUM_OK)
        ++s.instances;
}

// A batch of count % 5 rows (0: an empty batch), each a mesh id and matrix drawn as by
// op_add_instance, then a byte whose bits pass NULL for mesh_ids (1) or transforms (2). A
// refused batch names a row below count (or none, for a refused call); an accepted one none.
void op_add_instances(ByteReader& in, ProgramState& s) {
    const uint32_t count = in.u8() % 5u;
    std::vector<uint32_t> ids;
    std::vector<float> transforms;
    for (uint32_t i = 0; i < count; ++i) {
        ids.push_back(in.id(s.meshes));
        const Matrix m = draw_matrix(in, translation(0.0f, 0.0f, 0.0f));
        transforms.insert(transforms.end(), m.begin(), m.end());
    }
    const uint8_t nulls = in.u8();
    const uint32_t* id_array = (nulls & 1) ? nullptr : ids.data();
    const float* transform_array = (nulls & 2) ? nullptr : transforms.data();
    if (s.instances + count > kMaxInstances) return;
    uint32_t failed = 0;
    const StratumStatus status = checked(
        "stratum_scene_add_instances",
        [&] { return stratum_scene_add_instances(s.scene, count, id_array, transform_array, &failed); },
        [&] {
            return "scene, " + std::to_string(count) + ", (uint32_t[])" +
                   (id_array ? "{" + describe_uints(ids) + "}" : std::string("NULL")) + ", (float[])" +
                   (transform_array ? describe_floats(transforms.data(), transforms.size()) : "NULL") +
                   ", &failed";
        });
    if (status == STRATUM_OK) {
        if (failed != UINT32_MAX)
            finding("stratum_scene_add_instances succeeded and named row " + std::to_string(failed));
        s.instances += count;
    } else if (failed != UINT32_MAX && failed >= count) {
        finding("stratum_scene_add_instances named row " + std::to_string(failed) + " of " +
                std::to_string(count));
    }
}

void op_add_instance_ex(ByteReader& in, ProgramState& s) {
    const StratumInstanceDesc d = draw_instance(in, s.meshes);
    if (s.instances >= kMaxInstances) return;
    if (checked(
            "stratum_scene_add_instance_ex", [&] { return stratum_scene_add_instance_ex(s.scene, &d); },
            [&] { return "scene, &(StratumInstanceDesc)" + describe(d); }) == STRATUM_OK)
        ++s.instances;
}

void op_add_light(ByteReader& in, ProgramState& s) {
    const StratumLightDesc d = draw_light(in);
    if (s.lights >= kMaxLights) return;
    if (checked(
            "stratum_scene_add_light", [&] { return stratum_scene_add_light(s.scene, &d); },
            [&] { return "scene, &(StratumLightDesc)" + describe(d); }) == STRATUM_OK)
        ++s.lights;
}

void op_set_camera(ByteReader& in, ProgramState& s) {
    const StratumCameraDesc d = draw_camera(in);
    checked(
        "stratum_scene_set_camera", [&] { return stratum_scene_set_camera(s.scene, &d); },
        [&] { return "scene, &(StratumCameraDesc)" + describe(d); });
}

void op_set_background(ByteReader& in, ProgramState& s) {
    float rgb[3];
    for (float& c : rgb) c = in.f32(FloatKind::Unit);
    checked(
        "stratum_scene_set_background", [&] { return stratum_scene_set_background(s.scene, rgb); },
        [&] { return "scene, (float[3])" + describe_floats(rgb, 3); });
}

void op_set_environment(ByteReader& in, ProgramState& s) {
    const EnvironmentArrays e = draw_environment(in);
    const float* rgb = e.null_rgb ? nullptr : e.rgb.data();
    const float* rotation = e.with_rotation ? e.rotation.data() : nullptr;
    checked(
        "stratum_scene_set_environment",
        [&] { return stratum_scene_set_environment(s.scene, rgb, e.width, e.height, e.strength, rotation); },
        [&] {
            return "scene, " +
                   (rgb ? "(float[])" + describe_floats(rgb, e.rgb.size()) : std::string("NULL")) + ", " +
                   std::to_string(e.width) + ", " + std::to_string(e.height) + ", " +
                   describe_float(e.strength) + ", " +
                   (rotation ? "(float[9])" + describe_floats(rotation, 9) : std::string("NULL"));
        });
}

void op_new_scene(ByteReader&, ProgramState& s) { s.new_scene(); }

}  // namespace stratum::fuzz
