// Captured scene files (stratum_scene_save / stratum_scene_load) against what the ABI fuzzer
// tried: paths that are no regular file must be refused at once (opening a FIFO blocks until a
// writer comes, /dev/zero never ends), numbers out of their type's range must be refused naming
// the key (converting 1e300 to float or 3.5e38 to int is undefined behaviour, which the
// sanitized build aborts on), and a saved scene must load and save to the same bytes.
#include <gtest/gtest.h>
#include <stratum/stratum.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;

std::string last_error() { return stratum_last_error(); }

std::string read_text(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void write_text(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
}

// A directory of this test process's own, removed afterwards.
struct TempDir {
    fs::path path = fs::temp_directory_path() / ("stratum-scene-file-" + std::to_string(getpid()));
    TempDir() { fs::create_directories(path); }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

// A small complete scene: a material, a triangle placed by an instance, a light and a camera.
StratumScene* small_scene(const StratumMaterialDesc& material) {
    StratumScene* scene = nullptr;
    EXPECT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    EXPECT_EQ(stratum_scene_add_material(scene, &material, nullptr), STRATUM_OK) << last_error();
    const float positions[9] = {-1, -1, 0, 1, -1, 0, 0, 1, 0};
    const uint32_t triangles[3] = {0, 1, 2}, material_ids[1] = {0};
    StratumMeshDesc mesh{};
    mesh.positions = positions;
    mesh.vertex_count = 3;
    mesh.triangles = triangles;
    mesh.triangle_count = 1;
    mesh.material_ids = material_ids;
    EXPECT_EQ(stratum_scene_add_mesh(scene, &mesh, nullptr), STRATUM_OK) << last_error();
    const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    EXPECT_EQ(stratum_scene_add_instance(scene, 0, identity), STRATUM_OK) << last_error();
    StratumLightDesc light{};
    light.type = STRATUM_LIGHT_POINT;
    light.color[0] = light.color[1] = light.color[2] = 1.0f;
    light.strength = 100.0f;
    std::copy(identity, identity + 16, light.transform);
    light.transform[11] = 3.0f;
    EXPECT_EQ(stratum_scene_add_light(scene, &light), STRATUM_OK) << last_error();
    StratumCameraDesc camera{};
    camera.lens_mm = 50.0f;
    camera.sensor_width_mm = 36.0f;
    camera.sensor_height_mm = 24.0f;
    camera.clip_start = 0.1f;
    camera.clip_end = 100.0f;
    std::copy(identity, identity + 16, camera.transform);
    camera.transform[11] = 5.0f;
    EXPECT_EQ(stratum_scene_set_camera(scene, &camera), STRATUM_OK) << last_error();
    return scene;
}

StratumMaterialDesc grey() {
    StratumMaterialDesc m{};
    m.model = STRATUM_MATERIAL_PRINCIPLED_V1;
    m.base_color[0] = m.base_color[1] = m.base_color[2] = 0.5f;
    m.roughness = 0.5f;
    m.specular = 0.5f;
    m.ior = 1.5f;
    return m;
}

TEST(SceneFile, PathsThatAreNoRegularFileAreRefusedWithoutBlocking) {
    TempDir dir;
    const fs::path fifo = dir.path / "scene.json";
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    StratumScene* loaded = nullptr;
    EXPECT_EQ(stratum_scene_load(fifo.c_str(), &loaded), STRATUM_ERROR_IO);
    EXPECT_NE(last_error().find("a FIFO"), std::string::npos) << last_error();
    EXPECT_EQ(loaded, nullptr);
    StratumScene* scene = small_scene(grey());
    EXPECT_EQ(stratum_scene_save(scene, fifo.c_str()), STRATUM_ERROR_IO);
    EXPECT_NE(last_error().find("a FIFO"), std::string::npos) << last_error();
    EXPECT_EQ(stratum_scene_load("/dev/zero", &loaded), STRATUM_ERROR_IO);
    EXPECT_NE(last_error().find("a device"), std::string::npos) << last_error();
    EXPECT_EQ(stratum_scene_load(dir.path.c_str(), &loaded), STRATUM_ERROR_IO);
    EXPECT_NE(last_error().find("a directory"), std::string::npos) << last_error();
    EXPECT_EQ(stratum_scene_save(scene, dir.path.c_str()), STRATUM_ERROR_IO);
    EXPECT_NE(last_error().find("a directory"), std::string::npos) << last_error();
    stratum_scene_destroy(scene);
}

TEST(SceneFile, NumbersOutOfTheirTypesRangeAreRefusedNamingTheKey) {
    TempDir dir;
    const fs::path path = dir.path / "scene.json";
    StratumScene* scene = small_scene(grey());
    ASSERT_EQ(stratum_scene_save(scene, path.c_str()), STRATUM_OK) << last_error();
    stratum_scene_destroy(scene);
    const std::string saved = read_text(path);
    // Each replaces one value of the saved text; the message must name the key.
    const struct {
        std::string from, to, key;
    } kCases[] = {
        {"\"roughness\":0.5", "\"roughness\":1e300", "roughness"},    // beyond float
        {"\"roughness\":0.5", "\"roughness\":-3.5e38", "roughness"},  // just beyond float
        {"\"roughness\":0.5", "\"roughness\":null", "roughness"},     // not a number
        {"\"sensor_fit\":0", "\"sensor_fit\":3.5e38", "sensor_fit"},  // beyond int, and not integral
        {"\"sensor_fit\":0", "\"sensor_fit\":2147483648", "sensor_fit"},
        {"\"mesh\":0", "\"mesh\":-1", "mesh"},  // a uint32 that would wrap to 4294967295
        {"\"motion\":0", "\"motion\":1.5", "motion"},
        {"\"holdout\":0", "\"holdout\":18446744073709551615", "holdout"},
    };
    for (const auto& c : kCases) {
        const size_t at = saved.find(c.from);
        ASSERT_NE(at, std::string::npos) << c.from << " not in " << saved;
        write_text(path, std::string(saved).replace(at, c.from.size(), c.to));
        StratumScene* loaded = nullptr;
        EXPECT_EQ(stratum_scene_load(path.c_str(), &loaded), STRATUM_ERROR_IO) << c.to;
        EXPECT_NE(last_error().find(c.key + " = "), std::string::npos) << c.to << ": " << last_error();
        EXPECT_EQ(loaded, nullptr);
    }
}

TEST(SceneFile, ASavedSceneLoadsAndSavesToTheSameBytes) {
    TempDir dir;
    // Values at the edges of what the ABI accepts: a denormal, -0, FLT_MAX emission.
    StratumMaterialDesc m = grey();
    m.model = STRATUM_MATERIAL_EMISSION;
    m.base_color[0] = std::numeric_limits<float>::denorm_min();
    m.base_color[1] = -0.0f;
    m.emission[0] = std::numeric_limits<float>::max();
    StratumScene* scene = small_scene(m);
    const fs::path first = dir.path / "first.json", second = dir.path / "second.json";
    ASSERT_EQ(stratum_scene_save(scene, first.c_str()), STRATUM_OK) << last_error();
    StratumScene* loaded = nullptr;
    ASSERT_EQ(stratum_scene_load(first.c_str(), &loaded), STRATUM_OK) << last_error();
    ASSERT_EQ(stratum_scene_save(loaded, second.c_str()), STRATUM_OK) << last_error();
    EXPECT_EQ(read_text(first), read_text(second));
    stratum_scene_destroy(loaded);
    stratum_scene_destroy(scene);
}

}  // namespace
