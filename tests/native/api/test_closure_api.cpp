// stratum_scene_add_closure_material and the material models added with it, at the C ABI:
// every bad value is rejected with a message naming it, good ones are accepted, and scene files
// keep every closure (and still load files written with one flat closure per material).
#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "scene_handle.h"

using stratum_test::SceneHandle;

namespace {

StratumMaterialDesc diffuse(float grey) {
    return {STRATUM_MATERIAL_DIFFUSE, {grey, grey, grey}, 0.5f, 0, 0.5f, 1.45f, {0, 0, 0},
            STRATUM_MICROFACET_GGX};
}

void expect_rejected(StratumStatus status, const std::string& fragment) {
    EXPECT_EQ(status, STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find(fragment), std::string::npos) << stratum_last_error();
}

TEST(ClosureApi, AcceptsEveryModelAndReturnsIds) {
    SceneHandle h;
    uint32_t id = 99;
    // Every model the library lists, with its defaults: a model added to the registry is
    // covered without touching this test.
    const int32_t count = stratum_model_count(STRATUM_MODEL_CLOSURE);
    ASSERT_GE(count, 8);
    for (int32_t index = 0; index < count; ++index) {
        StratumMaterialDesc d = diffuse(0.5f);
        ASSERT_EQ(stratum_model_entry(STRATUM_MODEL_CLOSURE, index, nullptr, &d.model), STRATUM_OK);
        ASSERT_EQ(stratum_scene_add_material(h.scene, &d, &id), STRATUM_OK) << stratum_last_error();
        EXPECT_EQ(id, static_cast<uint32_t>(index));
    }
    const StratumClosureDesc closures[] = {{{0.5f, 0.5f, 0.5f}, diffuse(0.8f)},
                                           {{0.5f, 0.2f, 0.1f}, diffuse(0.2f)}};
    ASSERT_EQ(stratum_scene_add_closure_material(h.scene, closures, 2, &id), STRATUM_OK)
        << stratum_last_error();
    EXPECT_EQ(id, static_cast<uint32_t>(count));
}

TEST(ClosureApi, RejectsBadClosuresNamingTheValue) {
    SceneHandle h;
    StratumClosureDesc c{{1, 1, 1}, diffuse(0.5f)};
    expect_rejected(stratum_scene_add_closure_material(h.scene, nullptr, 1, nullptr), "closures is NULL");
    expect_rejected(stratum_scene_add_closure_material(h.scene, &c, 0, nullptr), "closure_count 0");
    StratumClosureDesc nine[9];
    for (auto& n : nine) n = c;
    expect_rejected(stratum_scene_add_closure_material(h.scene, nine, 9, nullptr), "closure_count 9");
    c.weight[1] = -1.0f;
    expect_rejected(stratum_scene_add_closure_material(h.scene, &c, 1, nullptr), "closure 0 weight");
    c.weight[1] = 1.0f;
    c.closure.model = 1000;  // past every value a model can have (bsdf.h: kMaxClosureModels)
    expect_rejected(stratum_scene_add_closure_material(h.scene, &c, 1, nullptr), "material model 1000");
    c.closure.model = STRATUM_MATERIAL_PRINCIPLED_V2;
    c.closure.transmission = 1.5f;
    expect_rejected(stratum_scene_add_closure_material(h.scene, &c, 1, nullptr), "transmission");
    c.closure.transmission = 0.5f;
    c.closure.coat = 1.0f;  // a coat needs a positive coat_ior
    expect_rejected(stratum_scene_add_closure_material(h.scene, &c, 1, nullptr), "coat_ior");
    c.closure.coat_ior = 1.5f;
    c.closure.coat_tint[0] = 2.0f;
    expect_rejected(stratum_scene_add_closure_material(h.scene, &c, 1, nullptr), "coat_tint");
    c.closure.coat_tint[0] = c.closure.coat_tint[1] = c.closure.coat_tint[2] = 1.0f;
    c.closure.coat_roughness = -0.1f;
    expect_rejected(stratum_scene_add_closure_material(h.scene, &c, 1, nullptr), "coat_roughness");
    c.closure.coat_roughness = 0.1f;
    EXPECT_EQ(stratum_scene_add_closure_material(h.scene, &c, 1, nullptr), STRATUM_OK)
        << stratum_last_error();
}

std::string read(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

TEST(ClosureApi, SceneFileKeepsEveryClosure) {
    const std::string a = ::testing::TempDir() + "closures_a.json",
                      b = ::testing::TempDir() + "closures_b.json";
    {
        SceneHandle h;
        StratumMaterialDesc coated = diffuse(0.7f);
        coated.model = STRATUM_MATERIAL_PRINCIPLED_V2;
        coated.transmission = 0.25f;
        coated.coat = 0.5f;
        coated.coat_roughness = 0.3f;
        coated.coat_ior = 1.6f;
        coated.coat_tint[0] = 0.9f, coated.coat_tint[1] = 0.8f, coated.coat_tint[2] = 0.7f;
        StratumMaterialDesc holdout = diffuse(1.0f);
        holdout.model = STRATUM_MATERIAL_HOLDOUT;
        const StratumClosureDesc closures[] = {{{0.25f, 0.5f, 0.75f}, coated},
                                               {{0.75f, 0.5f, 0.25f}, holdout}};
        ASSERT_EQ(stratum_scene_add_closure_material(h.scene, closures, 2, nullptr), STRATUM_OK);
        ASSERT_EQ(stratum_scene_save(h.scene, a.c_str()), STRATUM_OK) << stratum_last_error();
    }
    StratumScene* loaded = nullptr;
    ASSERT_EQ(stratum_scene_load(a.c_str(), &loaded), STRATUM_OK) << stratum_last_error();
    ASSERT_EQ(stratum_scene_save(loaded, b.c_str()), STRATUM_OK);
    stratum_scene_destroy(loaded);
    const std::string text = read(a);
    EXPECT_EQ(text, read(b));  // nothing lost or changed by a round trip
    for (const char* field :
         {"\"closures\"", "\"weight\"", "\"coat_tint\"", "\"transmission\"", "\"coat_ior\""})
        EXPECT_NE(text.find(field), std::string::npos) << field;
    std::remove(a.c_str());
    std::remove(b.c_str());
}

TEST(ClosureApi, LoadsFilesWithOneFlatClosurePerMaterial) {
    const std::string path = ::testing::TempDir() + "flat_material.json";
    {
        std::ofstream out(path);
        out << R"({"format": "stratum-scene", "version": 1,
                   "materials": [{"model": 1, "base_color": [0.8, 0.8, 0.8], "roughness": 0.5,
                                  "metallic": 0.0, "specular": 0.5, "ior": 1.45,
                                  "emission": [0, 0, 0], "distribution": 0}],
                   "meshes": [], "instances": [], "lights": [], "background": [0, 0, 0]})";
    }
    StratumScene* loaded = nullptr;
    ASSERT_EQ(stratum_scene_load(path.c_str(), &loaded), STRATUM_OK) << stratum_last_error();
    const std::string resaved = path + ".resaved";
    ASSERT_EQ(stratum_scene_save(loaded, resaved.c_str()), STRATUM_OK);
    stratum_scene_destroy(loaded);
    const std::string text = read(resaved);
    // Re-saved as one closure of weight 1 with the new fields at their "none" values.
    EXPECT_NE(text.find("\"closures\":[{"), std::string::npos) << text;
    EXPECT_NE(text.find("\"weight\":[1.0,1.0,1.0]"), std::string::npos) << text;
    EXPECT_NE(text.find("\"transmission\":0.0"), std::string::npos) << text;
    std::remove(path.c_str());
    std::remove(resaved.c_str());
}

}  // namespace
