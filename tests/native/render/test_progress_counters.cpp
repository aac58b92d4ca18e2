// The named progress counters (stratum_renderer_progress_counter, render/progress_counters.h):
// listed by position with static names, an index outside the list refused with a message that
// names it, and the values of the features that report them: radiosity's solve, path guiding's
// tree as it learns pass after pass, 0 for a feature the render does not use.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "radiosity_scenes.h"
#include "render_helpers.h"

using namespace stratum_test;

namespace {

// What hosts find by name: the order only grows at the end (a host may keep a position).
const std::vector<std::string> kNames = {"light_tree.seconds", "light_tree.bytes",  "radiosity.patches",
                                         "radiosity.bytes",    "radiosity.seconds", "radiosity.iterations",
                                         "guiding.nodes",      "guiding.bytes"};

}  // namespace

TEST(ProgressCounters, ListsEveryCounterByName) {
    StratumScene* scene = make_cornell_box();
    ASSERT_NE(scene, nullptr) << stratum_last_error();
    StratumRenderer* r = nullptr;
    ASSERT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
    ASSERT_EQ(stratum_progress_counter_count(), static_cast<int32_t>(kNames.size()));
    for (int32_t i = 0; i < stratum_progress_counter_count(); ++i) {
        const char* name = nullptr;
        double value = -1.0;
        ASSERT_EQ(stratum_renderer_progress_counter(r, i, &name, &value), STRATUM_OK) << stratum_last_error();
        EXPECT_EQ(name, kNames[static_cast<size_t>(i)]);
        EXPECT_EQ(value, 0.0) << name << " before any render";
        // Either output may be left out.
        EXPECT_EQ(stratum_renderer_progress_counter(r, i, nullptr, &value), STRATUM_OK);
        EXPECT_EQ(stratum_renderer_progress_counter(r, i, &name, nullptr), STRATUM_OK);
    }
    stratum_renderer_destroy(r);
    stratum_scene_destroy(scene);
}

TEST(ProgressCounters, RefusesAnIndexOutsideTheListAndANullRenderer) {
    StratumScene* scene = make_cornell_box();
    ASSERT_NE(scene, nullptr) << stratum_last_error();
    StratumRenderer* r = nullptr;
    ASSERT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
    const int32_t count = stratum_progress_counter_count();
    for (const int32_t index : {-1, count, count + 100}) {
        const char* name = "untouched";
        double value = 7.0;
        EXPECT_EQ(stratum_renderer_progress_counter(r, index, &name, &value), STRATUM_ERROR_INVALID_ARGUMENT);
        EXPECT_EQ(std::string(stratum_last_error()),
                  "stratum_renderer_progress_counter: progress counter index " + std::to_string(index) +
                      " out of range [0, " + std::to_string(count) + ")");
        EXPECT_STREQ(name, "untouched");
        EXPECT_EQ(value, 7.0);
    }
    double value = 0.0;
    EXPECT_EQ(stratum_renderer_progress_counter(nullptr, 0, nullptr, &value), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(std::string(stratum_last_error()), "stratum_renderer_progress_counter: renderer is NULL");
    stratum_renderer_destroy(r);
    stratum_scene_destroy(scene);
}

// The radiosity solve's counters are there once a radiosity render has ended; the other
// features' stay 0.
TEST(ProgressCounters, ReportRadiosityAndNothingOfFeaturesNotUsed) {
    StratumScene* scene = make_cornell_box();
    ASSERT_NE(scene, nullptr) << stratum_last_error();
    const RenderOutput out = render(scene, {{"width", 8},
                                            {"height", 8},
                                            {"samples", 1},
                                            {"integrator", "radiosity"},
                                            {"radiosity_patch_size", 0.5}});
    ASSERT_TRUE(out.error.empty()) << out.error;
    ASSERT_EQ(out.counters.size(), kNames.size());
    EXPECT_GT(out.counters.at("radiosity.patches"), 0.0);
    EXPECT_GT(out.counters.at("radiosity.bytes"), 0.0);
    EXPECT_GT(out.counters.at("radiosity.iterations"), 0.0);
    for (const char* unused : {"light_tree.seconds", "light_tree.bytes", "guiding.nodes", "guiding.bytes"})
        EXPECT_EQ(out.counters.at(unused), 0.0) << unused;
    stratum_scene_destroy(scene);
}

// Path guiding reports its tree after every training pass: with more training samples (passes
// [0,1) [1,2) [2,4) [4,8) [8,16)) the tree has learned from more records and holds more nodes.
// Deterministic: the tree learns from the passes' records in a fixed order (test_determinism).
TEST(ProgressCounters, GuidingNodesGrowWithTheTrainingPasses) {
    StratumScene* scene = make_cornell_box();
    ASSERT_NE(scene, nullptr) << stratum_last_error();
    std::vector<double> nodes, bytes;
    for (const int64_t training : {1, 2, 4, 8, 16}) {
        const RenderOutput out = render(scene, Settings{{"width", 32},
                                                        {"height", 32},
                                                        {"samples", 16},
                                                        {"max_bounces", 6},
                                                        {"use_guiding", 1},
                                                        {"guiding_training_samples", training}});
        ASSERT_TRUE(out.error.empty()) << out.error;
        nodes.push_back(out.counters.at("guiding.nodes"));
        bytes.push_back(out.counters.at("guiding.bytes"));
        EXPECT_EQ(out.counters.at("radiosity.patches"), 0.0);
    }
    for (size_t k = 0; k < nodes.size(); ++k) EXPECT_GT(bytes[k], 0.0) << "training samples " << (1 << k);
    for (size_t k = 1; k < nodes.size(); ++k)
        EXPECT_GE(nodes[k], nodes[k - 1]) << "training samples " << (1 << k);
    EXPECT_GT(nodes.back(), nodes.front()) << "the tree did not grow over the training passes";
    stratum_scene_destroy(scene);
}
