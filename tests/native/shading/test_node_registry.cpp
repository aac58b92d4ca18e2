// The shader node registry (shading/node_registry.h): every node files its own value and name,
// the values published so far never change, a value or name filed twice is refused and named,
// and a node added by a file outside the library (this one) is listed and runs like the others.
#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <map>
#include <set>
#include <string>
#include <vector>

#include "node_types.h"
#include "scene_handle.h"
#include "shading/node_registry.h"

namespace {

using stratum::NodeEntry;
using stratum::NodeRegistry;
using stratum_test::node_type;

std::map<std::string, int32_t> listing() {
    std::map<std::string, int32_t> nodes;
    const int32_t count = stratum_model_count(STRATUM_MODEL_SHADER_NODE);
    for (int32_t i = 0; i < count; ++i) {
        const char* name = nullptr;
        int32_t value = -1;
        EXPECT_EQ(stratum_model_entry(STRATUM_MODEL_SHADER_NODE, i, &name, &value), STRATUM_OK);
        nodes[name] = value;
    }
    return nodes;
}

std::string no_problem(const stratum::ShaderNode&, const stratum::ShaderProgram&) { return ""; }
void add_one(const stratum::ShaderNode& n, const stratum::ShaderEvalContext&, stratum::ShaderRegisters& r) {
    r[n.outputs[0]] = r[n.inputs[0]] + 1.0f;
}

// A node filed from outside the library, as a node file files it: the whole recipe is this line
// (and the two functions above).
const stratum::NodeRegistration kAddOneNode{{.value = 1023,
                                             .name = "test_add_one",
                                             .input_widths = {1},
                                             .output_widths = {1},
                                             .check = no_problem,
                                             .evaluate = add_one}};

TEST(NodeRegistry, EveryRegistrationWasFiled) { EXPECT_EQ(stratum::node_registry_problem(), ""); }

TEST(NodeRegistry, ListsEachValueAndNameOnceInValueOrder) {
    const int32_t count = stratum_model_count(STRATUM_MODEL_SHADER_NODE);
    ASSERT_GE(count, 36);
    std::set<std::string> names;
    int32_t previous = -1;
    for (int32_t i = 0; i < count; ++i) {
        const char* name = nullptr;
        int32_t value = -1;
        ASSERT_EQ(stratum_model_entry(STRATUM_MODEL_SHADER_NODE, i, &name, &value), STRATUM_OK);
        EXPECT_GT(value, previous) << name;
        EXPECT_TRUE(names.insert(name).second) << name << " is listed twice";
        previous = value;
    }
    EXPECT_EQ(stratum_model_entry(STRATUM_MODEL_SHADER_NODE, count, nullptr, nullptr),
              STRATUM_ERROR_INVALID_ARGUMENT);
}

// Published values: programs in captured scene files and the fuzzer's corpus hold them, so each
// node keeps its value for good. A node added later need not be added here.
TEST(NodeRegistry, PublishedValuesNeverChange) {
    const std::map<std::string, int32_t> published = {{"math", 0},
                                                      {"vector_math", 1},
                                                      {"mix", 2},
                                                      {"map_range", 3},
                                                      {"clamp", 4},
                                                      {"invert", 5},
                                                      {"gamma", 6},
                                                      {"bright_contrast", 7},
                                                      {"hsv", 8},
                                                      {"separate_color", 9},
                                                      {"combine_color", 10},
                                                      {"rgb_to_bw", 11},
                                                      {"color_ramp", 12},
                                                      {"curves", 13},
                                                      {"mapping", 14},
                                                      {"vector_rotate", 15},
                                                      {"fresnel", 16},
                                                      {"layer_weight", 17},
                                                      {"image", 18},
                                                      {"noise", 19},
                                                      {"voronoi", 20},
                                                      {"wave", 21},
                                                      {"checker", 22},
                                                      {"brick", 23},
                                                      {"gradient", 24},
                                                      {"magic", 25},
                                                      {"white_noise", 26},
                                                      {"musgrave", 27},
                                                      {"sky", 28},
                                                      {"bump", 29},
                                                      {"normal_map", 30},
                                                      {"blackbody", 31},
                                                      {"wavelength", 32},
                                                      {"vector_transform", 33},
                                                      {"normal", 34},
                                                      {"copy", 35}};
    const std::map<std::string, int32_t> listed = listing();
    for (const auto& [name, value] : published) {
        ASSERT_TRUE(listed.count(name)) << name << " is no longer listed";
        EXPECT_EQ(listed.at(name), value) << name;
    }
}

TEST(NodeRegistry, RefusesAValueOrANameFiledTwiceNamingBoth) {
    NodeRegistry registry;
    const NodeEntry first{.value = 3, .name = "first", .check = no_problem, .evaluate = add_one};
    const NodeEntry same_value{.value = 3, .name = "second", .check = no_problem, .evaluate = add_one};
    const NodeEntry same_name{.value = 4, .name = "first", .check = no_problem, .evaluate = add_one};
    const NodeEntry out_of_range{
        .value = NodeRegistry::kValueLimit, .name = "far", .check = no_problem, .evaluate = add_one};
    const NodeEntry negative{.value = -1, .name = "negative", .check = no_problem, .evaluate = add_one};
    const NodeEntry unnamed{.value = 5, .name = "", .check = no_problem, .evaluate = add_one};
    const NodeEntry no_evaluation{.value = 6, .name = "inert", .check = no_problem};
    EXPECT_EQ(registry.file(first), "");
    const std::string value_conflict = registry.file(same_value);
    EXPECT_NE(value_conflict.find("'second'"), std::string::npos) << value_conflict;
    EXPECT_NE(value_conflict.find("filed already, by 'first'"), std::string::npos) << value_conflict;
    const std::string name_conflict = registry.file(same_name);
    EXPECT_NE(name_conflict.find("the name is filed already, with value 3"), std::string::npos)
        << name_conflict;
    EXPECT_NE(registry.file(out_of_range).find("outside [0, 1024)"), std::string::npos);
    EXPECT_NE(registry.file(negative).find("outside"), std::string::npos);
    EXPECT_NE(registry.file(unnamed).find("no name"), std::string::npos);
    EXPECT_NE(registry.file(no_evaluation).find("no check or no evaluation"), std::string::npos);
    // Only the first is filed; what was refused changed nothing.
    EXPECT_EQ(registry.count(), 1);
    EXPECT_EQ(registry.find(3), &first);
    EXPECT_EQ(registry.find(4), nullptr);
    EXPECT_EQ(registry.listed(0), &first);
    EXPECT_EQ(registry.listed(1), nullptr);
}

TEST(NodeRegistry, ANodeFiledOutsideTheLibraryIsListedAndRuns) {
    const int32_t value = node_type("test_add_one");
    ASSERT_EQ(value, 1023);  // the last value the registry takes
    stratum_test::SceneHandle h;
    StratumShaderNode node{};
    node.type = value;
    node.inputs[0] = STRATUM_SHADER_INPUT_REGISTERS;
    node.outputs[0] = STRATUM_SHADER_INPUT_REGISTERS + 1;
    std::vector<float> registers(STRATUM_SHADER_INPUT_REGISTERS + 2, 0.0f);
    registers[STRATUM_SHADER_INPUT_REGISTERS] = 41.0f;
    const StratumShaderProgramDesc desc{&node,   1, registers.data(), static_cast<uint32_t>(registers.size()),
                                        nullptr, 0};
    uint32_t id = 0;
    ASSERT_EQ(stratum_scene_add_shader_program(h.scene, &desc, &id), STRATUM_OK) << stratum_last_error();
    std::vector<float> inputs(STRATUM_SHADER_INPUT_REGISTERS, 0.0f);
    float out = 0.0f;
    ASSERT_EQ(stratum_scene_evaluate_program(h.scene, id, inputs.data(), STRATUM_SHADER_INPUT_REGISTERS + 1,
                                             1, &out),
              STRATUM_OK);
    EXPECT_EQ(out, 42.0f);
    // Its widths are checked like a library node's.
    node.outputs[0] = static_cast<uint32_t>(registers.size());
    EXPECT_EQ(stratum_scene_add_shader_program(h.scene, &desc, &id), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("(test_add_one): output 0"), std::string::npos)
        << stratum_last_error();
}

TEST(NodeRegistry, AnUnlistedTypeIsRefusedWithItsValue) {
    stratum_test::SceneHandle h;
    StratumShaderNode node{};
    node.type = 999;
    std::vector<float> registers(STRATUM_SHADER_INPUT_REGISTERS, 0.0f);
    const StratumShaderProgramDesc desc{&node,   1, registers.data(), static_cast<uint32_t>(registers.size()),
                                        nullptr, 0};
    EXPECT_EQ(stratum_scene_add_shader_program(h.scene, &desc, nullptr), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("unknown type 999"), std::string::npos)
        << stratum_last_error();
}

}  // namespace
