// An empty StratumScene owned by a test: created on construction (a failure fails the test),
// destroyed with the handle. Fixtures that build a scene derive from it.
#pragma once

#include <gtest/gtest.h>
#include <stratum/stratum.h>

namespace stratum_test {

struct SceneHandle {
    StratumScene* scene = nullptr;
    SceneHandle() { EXPECT_EQ(stratum_scene_create(&scene), STRATUM_OK); }
    ~SceneHandle() { stratum_scene_destroy(scene); }
    SceneHandle(const SceneHandle&) = delete;
    SceneHandle& operator=(const SceneHandle&) = delete;
};

}  // namespace stratum_test
