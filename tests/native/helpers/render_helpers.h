// Scene construction and rendering through the C ABI, shared by the render tests.
#pragma once

#include <stratum/stratum.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <initializer_list>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace stratum_test {

inline constexpr float kIdentity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

// A grey Lambertian material of reflectance k, not emitting.
inline StratumMaterialDesc diffuse_grey(float k) {
    return {STRATUM_MATERIAL_DIFFUSE, {k, k, k}, 1.0f, 0.0f, 0.0f, 1.5f, {0, 0, 0}, STRATUM_MICROFACET_GGX};
}

// A UV sphere of radius r centred at the origin, wound so normals point outward.
struct SphereMesh {
    std::vector<float> positions;
    std::vector<uint32_t> triangles;
};

inline SphereMesh make_sphere(float r, uint32_t rings, uint32_t segments) {
    SphereMesh m;
    const float pi = 3.14159265358979f;
    for (uint32_t i = 0; i <= rings; ++i) {
        const float theta = pi * static_cast<float>(i) / static_cast<float>(rings);
        for (uint32_t j = 0; j < segments; ++j) {
            const float phi = 2.0f * pi * static_cast<float>(j) / static_cast<float>(segments);
            m.positions.insert(m.positions.end(), {r * std::sin(theta) * std::cos(phi),
                                                   r * std::sin(theta) * std::sin(phi), r * std::cos(theta)});
        }
    }
    for (uint32_t i = 0; i < rings; ++i) {
        for (uint32_t j = 0; j < segments; ++j) {
            const uint32_t a = i * segments + j, b = i * segments + (j + 1) % segments;
            const uint32_t c = a + segments, d = b + segments;
            m.triangles.insert(m.triangles.end(), {a, c, b, b, c, d});
        }
    }
    return m;
}

// Adds `m` with material id `material` on every triangle, and one instance of it at the
// origin; false when the scene rejects either.
inline bool add_mesh_instance(StratumScene* scene, const SphereMesh& m, uint32_t material) {
    const std::vector<uint32_t> mats(m.triangles.size() / 3, material);
    const StratumMeshDesc mesh{m.positions.data(),
                               static_cast<uint32_t>(m.positions.size() / 3),
                               m.triangles.data(),
                               static_cast<uint32_t>(m.triangles.size() / 3),
                               nullptr,
                               nullptr,
                               mats.data()};
    uint32_t mesh_id = 0;
    return stratum_scene_add_mesh(scene, &mesh, &mesh_id) == STRATUM_OK &&
           stratum_scene_add_instance(scene, mesh_id, kIdentity) == STRATUM_OK;
}

// Adds the quad `corners` (four vertices x, y, z in order around it; two triangles 0-1-2 and
// 0-2-3) with material id `material` as a mesh; false if the scene refuses it.
inline bool add_quad_mesh(StratumScene* scene, const float (&corners)[12], uint32_t material,
                          uint32_t* mesh_id) {
    const uint32_t triangles[] = {0, 1, 2, 0, 2, 3};
    const uint32_t mats[] = {material, material};
    const StratumMeshDesc mesh{corners, 4, triangles, 2, nullptr, nullptr, mats};
    return stratum_scene_add_mesh(scene, &mesh, mesh_id) == STRATUM_OK;
}

// The quad and one instance of it at the origin.
inline bool add_quad_instance(StratumScene* scene, const float (&corners)[12], uint32_t material) {
    uint32_t mesh_id = 0;
    return add_quad_mesh(scene, corners, material, &mesh_id) &&
           stratum_scene_add_instance(scene, mesh_id, kIdentity) == STRATUM_OK;
}

// The quad and one static instance of it at the origin whose other fields (visibility,
// holdout, light group, ...) are `instance`'s; its mesh_id and transform are set here.
inline bool add_quad_instance(StratumScene* scene, const float (&corners)[12], uint32_t material,
                              StratumInstanceDesc instance) {
    if (!add_quad_mesh(scene, corners, material, &instance.mesh_id)) return false;
    std::copy(kIdentity, kIdentity + 16, instance.transform);
    return stratum_scene_add_instance_ex(scene, &instance) == STRATUM_OK;
}

// A horizontal square of half side `half` at height z, facing +Z, centred on the Z axis.
inline bool add_square_instance(StratumScene* scene, float z, float half, uint32_t material) {
    const float corners[12] = {-half, -half, z, half, -half, z, half, half, z, -half, half, z};
    return add_quad_instance(scene, corners, material);
}

struct RenderOutput {
    std::vector<float> rgba;
    StratumProgress progress{};
    std::map<std::string, double> counters;  // progress_counters() when the render has ended
    std::string notices;                     // stratum_renderer_notices when the render has ended
    std::string error;                       // stratum_last_error() of the first failed call; "" on success
};

// A camera at `position` looking down −Z with a 90° horizontal field of view.
inline StratumCameraDesc camera_at(float x, float y, float z) {
    StratumCameraDesc c{18.0f, 36.0f, 36.0f, STRATUM_SENSOR_FIT_AUTO, 0, 0, 1e-3f, 1e3f, {}, 0, 0, 0,
                        0,     0,     0};
    std::copy(kIdentity, kIdentity + 16, c.transform);
    c.transform[3] = x;
    c.transform[7] = y;
    c.transform[11] = z;
    return c;
}

// A closed sphere of radius 1 whose wall has `material`, seen from inside by a camera at
// (x, y, z); nullptr on failure. The caller destroys the scene.
inline StratumScene* make_sphere_interior(const StratumMaterialDesc& material, uint32_t rings, float x,
                                          float y, float z) {
    StratumScene* scene = nullptr;
    if (stratum_scene_create(&scene) != STRATUM_OK) return nullptr;
    uint32_t mat = 0;
    const StratumCameraDesc camera = camera_at(x, y, z);
    if (stratum_scene_add_material(scene, &material, &mat) != STRATUM_OK ||
        !add_mesh_instance(scene, make_sphere(1.0f, rings, 2 * rings), mat) ||
        stratum_scene_set_camera(scene, &camera) != STRATUM_OK) {
        stratum_scene_destroy(scene);
        return nullptr;
    }
    return scene;
}

// One named render setting of any kind (ABI stratum_renderer_set_int / _float / _string).
struct Setting {
    enum class Kind { Int, Float, String };
    template <std::integral T>
    Setting(const char* n, T v) : name(n), kind(Kind::Int), int_value(static_cast<int64_t>(v)) {}
    Setting(const char* n, double v) : name(n), kind(Kind::Float), float_value(v) {}
    Setting(const char* n, const char* v) : name(n), kind(Kind::String), string_value(v) {}
    std::string name;
    Kind kind;
    int64_t int_value = 0;
    double float_value = 0.0;
    std::string string_value;
};
using Settings = std::vector<Setting>;

// Sets `settings` on `r` in order, up to the first one it rejects: that one's
// stratum_last_error(), or "" when every setting is accepted.
inline std::string apply_settings(StratumRenderer* r, const Settings& settings) {
    for (const Setting& s : settings) {
        StratumStatus status = STRATUM_OK;
        switch (s.kind) {
            case Setting::Kind::Int:
                status = stratum_renderer_set_int(r, s.name.c_str(), s.int_value);
                break;
            case Setting::Kind::Float:
                status = stratum_renderer_set_float(r, s.name.c_str(), s.float_value);
                break;
            case Setting::Kind::String:
                status = stratum_renderer_set_string(r, s.name.c_str(), s.string_value.c_str());
                break;
        }
        if (status != STRATUM_OK) return stratum_last_error();
    }
    return "";
}

// The renderer's progress counters by name ("guiding.nodes": stratum_renderer_progress_counter).
inline std::map<std::string, double> progress_counters(const StratumRenderer* r) {
    std::map<std::string, double> counters;
    for (int32_t i = 0; i < stratum_progress_counter_count(); ++i) {
        const char* name = nullptr;
        double value = 0.0;
        if (stratum_renderer_progress_counter(r, i, &name, &value) == STRATUM_OK) counters[name] = value;
    }
    return counters;
}

// Starts `r` and waits until its render has ended; false when it does not start.
inline bool render_to_end(StratumRenderer* r) {
    if (stratum_renderer_start(r) != STRATUM_OK) return false;
    int32_t done = 0;
    while (!done) stratum_renderer_wait(r, 1000, &done);
    return true;
}

// Renders `scene` with `settings` (ints, floats and strings by name) and returns the pixels and
// the renderer's notices. A rejected setting leaves rgba empty and names the failure in `error`.
inline RenderOutput render(StratumScene* scene, const Settings& settings) {
    RenderOutput out;
    StratumRenderer* r = nullptr;
    if (stratum_renderer_create(scene, &r) != STRATUM_OK) {
        out.error = stratum_last_error();
        return out;
    }
    out.error = apply_settings(r, settings);
    if (!out.error.empty()) {
        stratum_renderer_destroy(r);
        return out;
    }
    int64_t width = 0, height = 0;
    for (const Setting& s : settings) {
        if (s.kind == Setting::Kind::Int && s.name == "width") width = s.int_value;
        if (s.kind == Setting::Kind::Int && s.name == "height") height = s.int_value;
    }
    if (render_to_end(r)) {
        // After the render: the notices of start, of the scene build and of the render's end.
        const char* notices = nullptr;
        if (stratum_renderer_notices(r, &notices) == STRATUM_OK && notices) out.notices = notices;
        stratum_renderer_progress(r, &out.progress);
        out.counters = progress_counters(r);
        out.rgba.resize(static_cast<size_t>(width * height * 4));
        stratum_renderer_read_pixels(r, out.rgba.data(), out.rgba.size());
    } else {
        out.error = stratum_last_error();
    }
    stratum_renderer_destroy(r);
    return out;
}

// How render_pixel_centres views the scene: from (0, 0, 3) down −Z, with a 90° field of view or
// orthographically across [−1, 1]².
enum class CentreView { kPerspective, kOrthographic };

// Binds register `first` (and the two after it) of program 0 to material 0's emission, sets the
// camera of `view` (its near clip plane `clip_start` deep) and renders size × size pixels with one sample
// each at the pixel's centre (a box filter 0.01 pixels wide): a program's value where its inputs are known in
// closed form.
inline RenderOutput render_pixel_centres(StratumScene* scene, uint32_t first, int size, CentreView view,
                                         float clip_start = 1e-3f) {
    RenderOutput out;
    const StratumProgramBinding binding{0, 0, STRATUM_PROGRAM_EMISSION, 0, first};
    StratumCameraDesc camera = camera_at(0.0f, 0.0f, 3.0f);
    camera.clip_start = clip_start;
    if (view == CentreView::kOrthographic) {
        camera.type = STRATUM_CAMERA_ORTHOGRAPHIC;
        camera.ortho_scale = 2.0f;
    }
    if (stratum_scene_bind_program(scene, &binding) != STRATUM_OK ||
        stratum_scene_set_camera(scene, &camera) != STRATUM_OK) {
        out.error = stratum_last_error();
        return out;
    }
    return render(scene, Settings{{"width", size},
                                  {"height", size},
                                  {"samples", 1},
                                  {"filter_type", "box"},
                                  {"filter_width", 0.01}});
}

// render(scene, settings) with the integer settings {name, value} followed by ("sampler", sampler).
inline RenderOutput render(StratumScene* scene, std::initializer_list<std::pair<const char*, int64_t>> ints,
                           const char* sampler = "random") {
    Settings settings;
    for (const auto& [name, value] : ints) settings.emplace_back(name, value);
    settings.emplace_back("sampler", sampler);
    return render(scene, settings);
}

// Mean of one channel over the pixels of an image and its standard error s/√P, s the sample
// standard deviation of the P pixel values: valid when pixel errors are independent (a sampler
// randomised per pixel, and an estimator whose samples each touch one pixel).
struct PixelStats {
    double mean = 0, standard_error = 0, variance = 0;  // variance: of one pixel value
    size_t pixels = 0;
};

inline PixelStats pixel_stats(const std::vector<float>& rgba, int channel = 0) {
    PixelStats st;
    st.pixels = rgba.size() / 4;
    if (st.pixels < 2) return st;
    double sum = 0;
    for (size_t i = 0; i < st.pixels; ++i) sum += rgba[4 * i + channel];
    st.mean = sum / static_cast<double>(st.pixels);
    double ss = 0;  // two-pass: no cancellation when the spread is tiny next to the mean
    for (size_t i = 0; i < st.pixels; ++i) {
        const double d = rgba[4 * i + channel] - st.mean;
        ss += d * d;
    }
    st.variance = ss / static_cast<double>(st.pixels - 1);
    st.standard_error = std::sqrt(st.variance / static_cast<double>(st.pixels));
    return st;
}

// The mean of R image means (R renders with different seeds) and its standard error. The
// spread of the image means over seeds, s_r/√R, captures any correlation between pixels (a
// lattice sampler, a light tracer splatting one particle into many pixels); the within-image
// term s_p/√(P R) is added so a test with few seeds is not judged by an unluckily small s_r.
struct SeedStats {
    double mean = 0, standard_error = 0;
};

inline SeedStats seed_stats(const std::vector<PixelStats>& images) {
    SeedStats st;
    const double r = static_cast<double>(images.size());
    if (images.size() < 2) return st;
    double sum = 0, pixel_var = 0;
    for (const PixelStats& p : images) {
        sum += p.mean;
        pixel_var = std::max(pixel_var, p.standard_error * p.standard_error);
    }
    st.mean = sum / r;
    double ss = 0;
    for (const PixelStats& p : images) ss += (p.mean - st.mean) * (p.mean - st.mean);
    const double seed_var = ss / (r - 1);
    st.standard_error = std::sqrt(pixel_var / r + seed_var / r);
    return st;
}

// ---- integrating spheres (textbook §3.3, research/textbook.md §2.1) ------------------------

// A UV sphere of radius 1 (rings × 2·rings quads, each split in two triangles, the degenerate
// halves at the poles left out) with the triangles of the top `port_rings` rings removed: a
// circular port around +Z. Mesh areas are summed in double from the float vertices, so the
// formulas can use the exact area of what is rendered.
struct PortedSphereMesh {
    SphereMesh mesh;
    double wall_area = 0;  // the triangles kept
    // Smallest distance from the centre to a triangle's plane: every point of the mesh lies at
    // a distance in [min_plane_distance, 1] from the centre (the vertices are on the unit sphere).
    double min_plane_distance = 1;
    double port_area = 0;  // the triangles removed (the cap the port replaces)
    double total_area() const { return wall_area + port_area; }
    // h: the port's share of the closed mesh's area.
    double port_fraction() const { return port_area / total_area(); }
};

inline PortedSphereMesh make_ported_sphere(uint32_t rings, uint32_t port_rings) {
    PortedSphereMesh out;
    const SphereMesh full = make_sphere(1.0f, rings, 2 * rings);
    out.mesh.positions = full.positions;
    const auto vertex = [&](uint32_t v) {
        return std::array<double, 3>{full.positions[3 * v], full.positions[3 * v + 1],
                                     full.positions[3 * v + 2]};
    };
    const auto area = [&](uint32_t a, uint32_t b, uint32_t c) {
        const auto pa = vertex(a), pb = vertex(b), pc = vertex(c);
        const double u[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]};
        const double v[3] = {pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2]};
        const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2],
                     z = u[0] * v[1] - u[1] * v[0];
        return 0.5 * std::sqrt(x * x + y * y + z * z);
    };
    const uint32_t triangles_per_ring = 2 * (2 * rings);
    for (size_t t = 0; t < full.triangles.size() / 3; ++t) {
        const uint32_t a = full.triangles[3 * t], b = full.triangles[3 * t + 1],
                       c = full.triangles[3 * t + 2];
        const double A = area(a, b, c);
        if (A < 1e-12) continue;  // the pole halves of the first and last rings
        {
            const auto pa = vertex(a), pb = vertex(b), pc = vertex(c);
            const double u[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]};
            const double v[3] = {pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2]};
            const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                                 u[0] * v[1] - u[1] * v[0]};
            const double d = std::abs(n[0] * pa[0] + n[1] * pa[1] + n[2] * pa[2]) / (2.0 * A);
            out.min_plane_distance = std::min(out.min_plane_distance, d);
        }
        if (t / triangles_per_ring < port_rings) {
            out.port_area += A;
        } else {
            out.wall_area += A;
            out.mesh.triangles.insert(out.mesh.triangles.end(), {a, b, c});
        }
    }
    return out;
}

// Relative bias bound of the image mean of a ported sphere (96 rings, port = top 20 rings,
// k = 0.5, camera looking away from the port), from the tessellation of the port. The formulas
// need every wall point to see the port with form factor h (exact on a sphere only). On the
// mesh, with h = the cap's exact share of the mesh area, the form factor F(x) to the port
// (Lambert's contour integral over the rim polygon, evaluated offline) differs from h because
// each facet's normal is tilted from the radial direction: |F − h| ≤ 0.0017 at facet centroids
// and ≤ 0.005 toward the corners, which by the maximum principle (δ = L − L₀ obeys
// δ = kL₀(h − F) + Kδ, ‖K‖ ≤ k) bounds the pointwise error by k·0.005/(1 − k) = 0.5%. The tilts
// alternate between the two triangles of each quad, though: the area mean of F − h over the
// wall the camera sees (z < −0.3, three-point rule per facet) is 2.9e-6 and over all walls
// 1.5e-5, so the first-order bias of the image mean is ≤ k(2.9e-6 + 1.5e-5)/(1 − k(1 − h)) =
// 1.6e-5 of L, and the second-order part (the pointwise 0.5% times the deviation of the facet
// kernel from the sphere's uniform one, ~1e-3) ≤ 5e-6. kPortedSphereBias keeps a factor 10.
inline constexpr double kPortedSphereBias = 2e-4;

struct IntegratingSphereDesc {
    float reflectance = 0.5f;  // k, grey Lambertian wall
    float emission = 0.0f;     // L_e of the wall (sphere B)
    float point_power = 0.0f;  // Φ of a point lamp of radius 0 at the centre (sphere A); 0 = none
    uint32_t rings = 64;       // tessellation
    uint32_t port_rings = 0;   // rings removed around +Z (0 = closed)
    float camera[3] = {0.1f, -0.2f, -0.3f};  // inside, looking down −Z, away from the port
};

// The scene (caller destroys it; nullptr on failure) and the mesh it was built from.
struct IntegratingSphere {
    StratumScene* scene = nullptr;
    PortedSphereMesh sphere;
};

inline IntegratingSphere make_integrating_sphere(const IntegratingSphereDesc& d) {
    IntegratingSphere out;
    out.sphere = make_ported_sphere(d.rings, d.port_rings);
    StratumScene* scene = nullptr;
    if (stratum_scene_create(&scene) != STRATUM_OK) return out;
    const float k = d.reflectance, e = d.emission;
    const StratumMaterialDesc wall{STRATUM_MATERIAL_DIFFUSE, {k, k, k}, 1.0f, 0.0f, 0.0f, 1.5f, {e, e, e},
                                   STRATUM_MICROFACET_GGX};
    const StratumCameraDesc camera = camera_at(d.camera[0], d.camera[1], d.camera[2]);
    const float black[3] = {0.0f, 0.0f, 0.0f};  // the port opens onto nothing
    uint32_t mat = 0;
    bool ok = stratum_scene_add_material(scene, &wall, &mat) == STRATUM_OK &&
              add_mesh_instance(scene, out.sphere.mesh, mat) &&
              stratum_scene_set_camera(scene, &camera) == STRATUM_OK &&
              stratum_scene_set_background(scene, black) == STRATUM_OK;
    if (ok && d.point_power > 0.0f) {
        StratumLightDesc lamp{};
        lamp.type = STRATUM_LIGHT_POINT;
        lamp.color[0] = lamp.color[1] = lamp.color[2] = 1.0f;
        lamp.strength = d.point_power;
        std::copy(kIdentity, kIdentity + 16, lamp.transform);
        ok = stratum_scene_add_light(scene, &lamp) == STRATUM_OK;
    }
    if (!ok) {
        stratum_scene_destroy(scene);
        return out;
    }
    out.scene = scene;
    return out;
}

// A closed sphere (no port, no lamp) of wall reflectance k and emission L_e, seen from the
// default camera.
inline IntegratingSphere make_closed_sphere(float k, float emission, uint32_t rings = 12) {
    IntegratingSphereDesc d;
    d.reflectance = k;
    d.emission = emission;
    d.rings = rings;
    return make_integrating_sphere(d);
}

// Sphere B (research/textbook.md §2.1 test B): wall emission L_e, reflectance k, port fraction
// h. Every wall point sees the port with form factor h and the wall with 1 − h, so a uniform L
// solves L = L_e + k(1 − h)L. With Cycles' bounce cap (vertices 0..max_bounces scatter and the
// ray leaving the last still collects emission) a path carries at most max_bounces + 1
// reflections: L = L_e Σ_{m=0}^{max_bounces+1} (k(1 − h))^m.
inline double sphere_b_radiance(double emission, double k, double h, uint32_t max_bounces) {
    const double q = k * (1.0 - h);
    return emission * (1.0 - std::pow(q, max_bounces + 2.0)) / (1.0 - q);
}

// Sphere A (textbook 3.17): a point source of flux Φ at the centre gives every wall point the
// irradiance Φ/A_s, so the first reflection has radiance kΦ/(πA_s) and each further one a
// factor q = k(1 − h): L = kΦ/(πA_s) Σ_{m=0}^{n−1} q^m = kΦ/(πA_s(1 − q))·(1 − qⁿ), with
// n = max_bounces + 1 reflections (common bounce-cap rule: NEE at vertices 0..max_bounces).
inline double sphere_a_radiance(double flux, double area, double k, double h, uint32_t max_bounces) {
    const double q = k * (1.0 - h);
    return k * flux / (3.14159265358979323846 * area * (1.0 - q)) * (1.0 - std::pow(q, max_bounces + 1.0));
}

// The mean of channel 0 over a render and its standard error. seeds = 1: one render with the
// seed in `settings`, the standard error from the pixel spread (pixel_stats; estimators whose
// pixels are independent). seeds = R > 1: R renders with seeds 0..R−1 (overriding any seed in
// `settings`; seed_stats, valid for any estimator and sampler).
struct Measurement {
    double mean = 0, standard_error = 0;
    std::string notices, error;
};

inline Measurement measure(StratumScene* scene, Settings settings, uint32_t seeds = 1) {
    Measurement m;
    std::vector<PixelStats> images;
    if (seeds > 1) settings.emplace_back("seed", 0u);
    for (uint32_t seed = 0; seed < seeds; ++seed) {
        if (seeds > 1) settings.back() = Setting("seed", seed);
        const RenderOutput out = render(scene, settings);
        if (!out.error.empty() || out.rgba.empty()) {
            m.error = out.error.empty() ? "no pixels" : out.error;
            return m;
        }
        m.notices = out.notices;
        images.push_back(pixel_stats(out.rgba));
    }
    if (seeds == 1) {
        m.mean = images[0].mean;
        m.standard_error = images[0].standard_error;
    } else {
        const SeedStats st = seed_stats(images);
        m.mean = st.mean;
        m.standard_error = st.standard_error;
    }
    return m;
}

}  // namespace stratum_test
