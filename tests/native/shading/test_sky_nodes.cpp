// The Sky Texture node (shading/nodes/sky_texture.cpp) through the C ABI: Preetham at the zenith
// against the model's closed form, values Cycles 3.4, 4.5 and 5.0 rendered
// (scripts/cycles_reference/sky.py), the Nishita table's mirror symmetry and ground fade, the sun
// disc's limb darkening and its radiance against the disc's solid angle, and the checks.
#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "api/shader_program_validation.h"
#include "node_types.h"
#include "render_scene/world_baking.h"
#include "scene_handle.h"

namespace {

using stratum_test::node_type;

constexpr double kPi = 3.14159265358979323846;

struct SkyProgram : stratum_test::SceneHandle {
    uint32_t id = 0;
    // A program of one sky node reading POSITION, its colour at register 80. `matrix`: the XYZ
    // matrix of the colour configuration (0 Blender 3.x, 1 4.0-4.5, 2 5.0 and later).
    StratumStatus add(int32_t model, int32_t disc, const std::vector<float>& data, int32_t matrix = 0) {
        StratumShaderNode node{};
        node.type = node_type("sky");
        node.modes[0] = model;
        node.modes[1] = disc;
        node.modes[2] = matrix;
        node.inputs[0] = STRATUM_INPUT_POSITION;
        node.outputs[0] = STRATUM_SHADER_INPUT_REGISTERS;
        node.data_offset = 0;
        node.data_count = static_cast<uint32_t>(data.size());
        std::vector<float> registers(STRATUM_SHADER_INPUT_REGISTERS + 3, 0.0f);
        StratumShaderProgramDesc desc{&node,
                                      1,
                                      registers.data(),
                                      static_cast<uint32_t>(registers.size()),
                                      data.data(),
                                      static_cast<uint32_t>(data.size())};
        return stratum_scene_add_shader_program(scene, &desc, &id);
    }
    std::array<float, 3> at(double x, double y, double z) const {
        std::array<float, STRATUM_SHADER_INPUT_REGISTERS> in{};
        in[0] = static_cast<float>(x);
        in[1] = static_cast<float>(y);
        in[2] = static_cast<float>(z);
        std::array<float, 3> out{};
        EXPECT_EQ(stratum_scene_evaluate_program(scene, id, in.data(), STRATUM_SHADER_INPUT_REGISTERS, 3,
                                                 out.data()),
                  STRATUM_OK);
        return out;
    }
};

double perez(const double* k, double theta, double gamma) {
    return (1 + k[0] * std::exp(k[1] / std::cos(theta))) *
           (1 + k[2] * std::exp(k[3] * gamma) + k[4] * std::cos(gamma) * std::cos(gamma));
}

// Preetham's data as Cycles packs it, for a sun at zenith angle `ts` (phi 0) and turbidity T.
std::vector<float> preetham_data(double ts, double T, double zenith[3]) {
    const double t2 = ts * ts, t3 = t2 * ts;
    const double chi = (4.0 / 9.0 - T / 120.0) * (kPi - 2 * ts);
    zenith[0] = ((4.0453 * T - 4.9710) * std::tan(chi) - 0.2155 * T + 2.4192) * 0.06;
    zenith[1] = (0.00166 * t3 - 0.00375 * t2 + 0.00209 * ts) * T * T +
                (-0.02903 * t3 + 0.06377 * t2 - 0.03202 * ts + 0.00394) * T +
                (0.11693 * t3 - 0.21196 * t2 + 0.06052 * ts + 0.25886);
    zenith[2] = (0.00275 * t3 - 0.00610 * t2 + 0.00317 * ts) * T * T +
                (-0.04214 * t3 + 0.08970 * t2 - 0.04153 * ts + 0.00516) * T +
                (0.15346 * t3 - 0.26756 * t2 + 0.06670 * ts + 0.26688);
    const double k[3][5] = {{0.1787 * T - 1.4630, -0.3554 * T + 0.4275, -0.0227 * T + 5.3251,
                             0.1206 * T - 2.5771, -0.0670 * T + 0.3703},
                            {-0.0193 * T - 0.2592, -0.0665 * T + 0.0008, -0.0004 * T + 0.2125,
                             -0.0641 * T - 0.8989, -0.0033 * T + 0.0452},
                            {-0.0167 * T - 0.2608, -0.0950 * T + 0.0092, -0.0079 * T + 0.2102,
                             -0.0441 * T - 1.6537, -0.0109 * T + 0.0529}};
    std::vector<float> d = {0.0f, static_cast<float>(ts)};
    for (int c = 0; c < 3; ++c) d.push_back(static_cast<float>(zenith[c] / perez(k[c], 0.0, ts)));
    for (int c = 0; c < 3; ++c) {
        for (int i = 0; i < 5; ++i) d.push_back(static_cast<float>(k[c][i]));
        for (int i = 0; i < 4; ++i) d.push_back(0.0f);
    }
    return d;
}

std::array<double, 3> xyz_to_rec709(double X, double Y, double Z) {
    return {3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z, -0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z,
            0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z};
}

TEST(SkyNodes, PreethamZenithIsTheZenithLuminanceAndChromaticity) {
    for (double ts : {0.3, 0.9, 1.3}) {
        SkyProgram p;
        double zenith[3];
        ASSERT_EQ(p.add(0, 0, preetham_data(ts, 2.5, zenith)), STRATUM_OK);
        // At the zenith theta = 0 and gamma = the sun's angle: the Perez ratio is 1.
        const double Y = zenith[0], x = zenith[1], y = zenith[2];
        const auto want = xyz_to_rec709(x / y * Y, Y, (1 - x - y) / y * Y);
        const auto got = p.at(0, 0, 1);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(got[c], std::max(want[c], 0.0), 1e-5 * std::fabs(want[c])) << ts;
    }
}

// Sun (0.3, 0.4, 0.6) normalised, turbidity 3: the Preetham data Python computes
// (stratum/shaders/nodes/sky_texture.py).
const std::vector<float> kPreethamSun = {
    0.6435011f, 0.6947383f, 0.4350246f, 0.2990316f, 0.3113828f, -0.9269f, -0.6387f, 5.257f,
    -2.2153f,   0.1693f,    0,          0,          0,          0,        -0.3171f, -0.1987f,
    0.2113f,    -1.0912f,   0.0353f,    0,          0,          0,        0,        -0.3109f,
    -0.2758f,   0.1865f,    -1.786f,    0.0202f,    0,          0,        0,        0};

// Each case: a direction (x, y, z) and Cycles' RGB there, which the program gives within 1e-4
// relative.
template <size_t N>
void expect_sky_pixels(const SkyProgram& p, const double (&cases)[N][6]) {
    for (const auto& c : cases) {
        const auto got = p.at(c[0], c[1], c[2]);
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], c[3 + k], 1e-4 * c[3 + k]);
    }
}

TEST(SkyNodes, PreethamMatchesCycles34) {
    // kPreethamSun, and Cycles 3.4's pixels at those directions.
    SkyProgram p;
    ASSERT_EQ(p.add(0, 0, kPreethamSun), STRATUM_OK);
    const double cases[][6] = {
        {-0.5135234, -0.85666883, 0.0491154194, 0.48978439, 0.469021291, 0.537845731},
        {0.549056292, 0.497587681, -0.671523392, 0.527671874, 0.483850211, 0.554474294},
        {0.913331866, -0.228824258, -0.336844683, 0.532538772, 0.486942261, 0.557364047}};
    expect_sky_pixels(p, cases);
}

TEST(SkyNodes, PreethamMatchesCycles45WithTheColourConfigurationOf4x) {
    // The same sky in Cycles 4.5 (4.2's pixels are the same): its XYZ -> Rec.709 is the 4.0-4.5
    // config's 16-digit matrix (XYZ matrix 1). 5.0's 7-digit matrix (2) is 2.4e-4 off here.
    SkyProgram p;
    ASSERT_EQ(p.add(0, 0, kPreethamSun, 1), STRATUM_OK);
    const double cases[][6] = {
        {-0.5135234, -0.85666883, 0.0491154194, 0.48978141, 0.469022125, 0.537846029},
        {0.549056292, 0.497587681, -0.671523392, 0.527668953, 0.483850986, 0.554474473},
        {0.913331866, -0.228824258, -0.336844683, 0.532535434, 0.486943007, 0.557364225}};
    expect_sky_pixels(p, cases);
}

// Nishita data: elevation, rotation, size, intensity, altitude, air, dust, ozone.
std::vector<float> nishita(float elevation, float rotation, float size, float intensity, float altitude,
                           float air, float dust, float ozone) {
    return {elevation, rotation, size, intensity, altitude, air, dust, ozone};
}

TEST(SkyNodes, NishitaMatchesCycles34) {
    // Cycles 3.4's pixels (altitude 1000 m, sun 30 degrees up, rotation -40 degrees, a 40-degree
    // disc at intensity 0.7): four of the sky and one of the disc. Measured worst difference over
    // all 2048 pixels of three settings: 1e-5 (compare_sky.py, a probe removed in issue 33).
    SkyProgram p;
    ASSERT_EQ(p.add(2, 1, nishita(0.5235988f, -0.6981317f, 0.6981317f, 0.7f, 1000.0f, 1, 1, 1)), STRATUM_OK);
    const double cases[][6] = {{-0.688929379, -0.41288352, 0.595737696, 0.9589324, 1.5480665, 2.72938943},
                               {0.0754529238, 0.50849402, 0.857753277, 0.999887347, 1.54214358, 2.72126937},
                               {0.23565042, -0.0590394139, 0.970042944, 0.560015321, 0.921980262, 1.70723093},
                               {-0.326833487, -0.913300633, 0.243026495, 1.92639804, 3.01294923, 4.60674906},
                               {-0.345204473, 0.576001406, 0.740983248, 199.735474, 164.289703, 128.994507}};
    expect_sky_pixels(p, cases);
}

TEST(SkyNodes, SingleScatteringMatchesCycles50) {
    // Blender 5.0's SINGLE_SCATTERING, the same settings as NishitaMatchesCycles34 (aerosol 1):
    // Cycles 5.0's pixels of the sky, the ground fade (below the horizon, now part of the table)
    // and the disc. Measured worst difference over 2048 pixels of three settings: 6e-6.
    SkyProgram p;
    ASSERT_EQ(p.add(3, 1, nishita(0.5235988f, -0.6981317f, 0.6981317f, 0.7f, 1000.0f, 1, 1, 1), 2),
              STRATUM_OK);
    const double cases[][6] = {
        {-0.688929379, -0.41288352, 0.595737696, 0.961367846, 1.55163121, 2.7341485},
        {0.0754529238, 0.50849402, 0.857753277, 1.00394952, 1.54751039, 2.72900486},
        {0.913331866, -0.228824258, -0.336844683, 0.0196205303, 0.0188774206, 0.0140633993},
        {-0.894191086, 0.422973275, -0.146683037, 3.58560705, 2.76677537, 1.64253449},
        {-0.539353549, 0.595142245, 0.595737696, 321.634247, 254.848053, 185.904633}};
    expect_sky_pixels(p, cases);
}

TEST(SkyNodes, MultipleScatteringMatchesCycles50) {
    // Blender 5.0's MULTIPLE_SCATTERING (its default), the same settings: Cycles 5.0's pixels of
    // the sky, below the horizon and the disc. Measured worst difference over 2048 pixels of three
    // settings: 6.3e-6.
    SkyProgram p;
    ASSERT_EQ(p.add(4, 1, nishita(0.5235988f, -0.6981317f, 0.6981317f, 0.7f, 1000.0f, 1, 1, 1), 2),
              STRATUM_OK);
    const double cases[][6] = {{-0.688929379, -0.41288352, 0.595737696, 1.17866731, 2.48518729, 5.14511442},
                               {0.913331866, -0.228824258, -0.336844683, 0.53450048, 0.93976295, 1.74664295},
                               {-0.539353549, 0.595142245, 0.595737696, 330.998413, 273.566345, 204.485947}};
    expect_sky_pixels(p, cases);
}

TEST(SkyNodes, NishitaIsMirroredAboutTheSunAndFadesBelowTheHorizon) {
    const float rotation = 0.7f;
    SkyProgram p;
    ASSERT_EQ(p.add(2, 0, nishita(0.4f, rotation, 0.01f, 1, 0, 1, 1, 1)), STRATUM_OK);
    // The table is mirrored about the direction with atan2(x, y) = rotation.
    for (double delta : {0.3, 1.1, 2.5}) {
        for (double z : {0.05, 0.4, 0.8}) {
            const double s = std::sqrt(1 - z * z);
            const auto a = p.at(s * std::sin(rotation + delta), s * std::cos(rotation + delta), z);
            const auto b = p.at(s * std::sin(rotation - delta), s * std::cos(rotation - delta), z);
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], 1e-4 * std::fabs(a[k]) + 1e-7);
        }
    }
    // Below the horizon: the horizon row times (1 + 2.5 z)^3, black below z = -0.4.
    const double phi = 2.0;
    const auto horizon = p.at(std::sin(phi), std::cos(phi), -1e-6);
    EXPECT_GT(horizon[1], 0.0f);
    for (double z : {-0.05, -0.2, -0.35}) {
        const double s = std::sqrt(1 - z * z);
        const auto g = p.at(s * std::sin(phi), s * std::cos(phi), z);
        const double f = std::pow(1 + 2.5 * z, 3);
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(g[k], horizon[k] * f, 2e-3 * horizon[k]) << z;
    }
    const auto deep = p.at(0, std::sqrt(1 - 0.25), -0.5);
    EXPECT_EQ(deep[0] + deep[1] + deep[2], 0.0f);
}

TEST(SkyNodes, SunDiscLimbDarkeningAndSolidAngle) {
    // No atmosphere: the sky is black and the disc is the sun's irradiance over its solid angle.
    const float elevation = 0.5f;
    const auto sun_at = [&](double dphi) {            // same elevation as the sun, azimuth offset dphi
        const double lon = 2 * kPi + kPi / 2 + dphi;  // rotation 0: 2 pi - 0, plus pi / 2
        return std::array<double, 3>{std::cos(elevation) * std::cos(lon), std::cos(elevation) * std::sin(lon),
                                     std::sin(elevation)};
    };
    const float sizes[2] = {0.02f, 0.05f};
    double centre[2];
    for (int i = 0; i < 2; ++i) {
        SkyProgram p;
        ASSERT_EQ(p.add(2, 1, nishita(elevation, 0.0f, sizes[i], 1, 0, 0, 0, 0)), STRATUM_OK);
        const auto zenith = p.at(0, 0, 1);
        EXPECT_EQ(zenith[0] + zenith[1] + zenith[2], 0.0f);
        const auto c = sun_at(0.0);
        centre[i] = p.at(c[0], c[1], c[2])[1];
        EXPECT_GT(centre[i], 0.0);
        // Half way to the rim along the same elevation: 1 - 0.6 (1 - sqrt(1 - r^2)).
        const double dphi = 2 * std::asin(std::sin(sizes[i] / 8.0) / std::cos(elevation));
        const auto h = sun_at(dphi);
        const double r = 0.5;
        const double darkening = 1 - 0.6 * (1 - std::sqrt(1 - r * r));
        EXPECT_NEAR(p.at(h[0], h[1], h[2])[1] / centre[i], darkening, 1e-3);
    }
    // Radiance is the irradiance over the solid angle 2 pi (1 - cos(size / 2)).
    const double want = (1 - std::cos(sizes[1] / 2.0)) / (1 - std::cos(sizes[0] / 2.0));
    EXPECT_NEAR(centre[0] / centre[1], want, 1e-3 * want);
}

TEST(SkyNodes, ChecksRejectBadModesAndData) {
    SkyProgram p;
    EXPECT_NE(p.add(5, 0, std::vector<float>(32, 0.0f)), STRATUM_OK);
    EXPECT_NE(p.add(4, 0, std::vector<float>(32, 0.0f)), STRATUM_OK);
    EXPECT_NE(p.add(3, 0, std::vector<float>(32, 0.0f)), STRATUM_OK);
    EXPECT_NE(p.add(0, 2, std::vector<float>(32, 0.0f)), STRATUM_OK);
    EXPECT_NE(p.add(0, 0, std::vector<float>(31, 0.0f)), STRATUM_OK);
    EXPECT_NE(p.add(2, 0, std::vector<float>(32, 0.0f)), STRATUM_OK);
    EXPECT_NE(p.add(2, 1, nishita(0.2f, 0, 0.01f, 1, 0, -1, 1, 1)), STRATUM_OK);
    EXPECT_NE(p.add(2, 1, nishita(NAN, 0, 0.01f, 1, 0, 1, 1, 1)), STRATUM_OK);
    std::vector<float> bad(32, 0.0f);
    bad[7] = INFINITY;
    EXPECT_NE(p.add(1, 0, bad), STRATUM_OK);
    EXPECT_NE(p.add(1, 0, std::vector<float>(8, 0.0f)), STRATUM_OK);
    const char* message = stratum_last_error();
    ASSERT_NE(message, nullptr);
    EXPECT_NE(std::string(message).find("(sky): data_count is 8"), std::string::npos) << message;
}

TEST(SkyNodes, BakedWorldKeepsTheSunDiscsIrradiance) {
    // No atmosphere: a black sky and the default disc (0.545 degrees, about 1.5 texels of a
    // 1024 x 512 map). The disc's irradiance on a horizontal plane, integrated over the baked
    // map, against the disc's own: centre radiance x cos(zenith angle) x the limb-darkened cap.
    const float elevation = 0.5f, rotation = 0.3f, size = 0.009512f;
    const std::vector<float> data = nishita(elevation, rotation, size, 1, 0, 0, 0, 0);
    StratumShaderNode node{};
    node.type = node_type("sky");
    node.modes[0] = 2;
    node.modes[1] = 1;
    node.inputs[0] = STRATUM_INPUT_POSITION;
    node.outputs[0] = STRATUM_SHADER_INPUT_REGISTERS;
    node.data_count = static_cast<uint32_t>(data.size());
    std::vector<float> registers(STRATUM_SHADER_INPUT_REGISTERS + 3, 0.0f);
    const StratumShaderProgramDesc desc{&node,
                                        1,
                                        registers.data(),
                                        static_cast<uint32_t>(registers.size()),
                                        data.data(),
                                        static_cast<uint32_t>(data.size())};
    const auto program = stratum::validate_shader_program(desc, 0);
    const uint32_t w = 1024, h = 512;
    const stratum::Environment e =
        stratum::bake_environment(*program, {}, STRATUM_SHADER_INPUT_REGISTERS, w, h);
    double baked = 0.0;
    for (uint32_t row = 0; row < h; ++row) {
        const double t0 = kPi * row / h, t1 = kPi * (row + 1) / h;
        const double d_omega = 2 * kPi / w * (std::cos(t0) - std::cos(t1));
        for (uint32_t col = 0; col < w; ++col)
            baked += e.rgb[(static_cast<size_t>(row) * w + col) * 3 + 1] * std::cos(kPi * (row + 0.5) / h) *
                     d_omega;
    }
    const double lon = 2 * kPi - rotation + kPi / 2;
    stratum::ShaderRegisters r(*program);
    std::copy(program->registers.begin(), program->registers.end(), r.data());
    stratum::write_world_inputs(
        stratum::Vec3(static_cast<float>(std::cos(elevation) * std::cos(lon)),
                      static_cast<float>(std::cos(elevation) * std::sin(lon)), std::sin(elevation)),
        r.data());
    stratum::evaluate(*program, stratum::ShaderEvalContext{program.get(), nullptr}, r);
    const double centre = r[STRATUM_SHADER_INPUT_REGISTERS + 1];
    const double a = size / 2.0;
    double cap = 0.0;  // integral of the limb darkening over the cap, by the midpoint rule
    const int n = 2000;
    for (int i = 0; i < n; ++i) {
        const double t = a * (i + 0.5) / n;
        cap += 2 * kPi * (1 - 0.6 * (1 - std::sqrt(1 - (t / a) * (t / a)))) * std::sin(t) * (a / n);
    }
    const double reference = centre * std::sin(elevation) * cap;
    EXPECT_NEAR(baked / reference, 1.0, 0.01);
}

}  // namespace
