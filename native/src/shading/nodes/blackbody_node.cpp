// Blackbody (Blender's ShaderNodeBlackbody) and Wavelength (ShaderNodeWavelength).
//
// | node       | modes | inputs          | outputs  | data                               |
// |------------|-------|-----------------|----------|------------------------------------|
// | blackbody  | -     | temperature 1   | colour 3 | 9: Rec.709 -> working RGB, by rows |
// | wavelength | -     | wavelength 1 nm | colour 3 | 9: XYZ -> working RGB, by rows     |
//
// Cycles' svm_node_blackbody and svm_node_wavelength (kernel/svm/blackbody.h, wavelength.h) with
// svm_math_blackbody_color_rec709 and svm_math_wavelength_color_xyz (kernel/svm/math_util.h) and
// their tables (kernel/tables.h), the same in 3.4 and 5.0. Blackbody: a fit per temperature band,
// a / t + b t + c for red and green and a cubic for blue, in Rec.709, constant below 800 K and
// from 12000 K; Wavelength: the CIE 1931 colour matching functions at 5 nm steps from 380 nm,
// interpolated linearly, zero outside [380, 780), scaled by 1 / 2.52. Each result is taken to the
// working space by the node's matrix and clamped at zero. The matrices are the host's (Cycles
// derives them from the OpenColorIO config: the compiler passes those of the Blender version).
#include <cmath>

#include "shading/node_registry.h"

namespace stratum {

namespace {

// Blackbody fit coefficients per band (band i starts at kBandStart[i] kelvin).
constexpr float kBandStart[7] = {800.0f, 965.0f, 1167.0f, 1449.0f, 1902.0f, 3315.0f, 6365.0f};
constexpr float kRed[7][3] = {{1.61919106e+03f, -2.05010916e-03f, 5.02995757e+00f},
                              {2.48845471e+03f, -1.11330907e-03f, 3.22621544e+00f},
                              {3.34143193e+03f, -4.86551192e-04f, 1.76486769e+00f},
                              {4.09461742e+03f, -1.27446582e-04f, 7.25731635e-01f},
                              {4.67028036e+03f, 2.91258199e-05f, 1.26703442e-01f},
                              {4.59509185e+03f, 2.87495649e-05f, 1.50345020e-01f},
                              {3.78717450e+03f, 9.35907826e-06f, 3.99075871e-01f}};
constexpr float kGreen[7][3] = {{-4.88999748e+02f, 6.04330754e-04f, -7.55807526e-02f},
                                {-7.55994277e+02f, 3.16730098e-04f, 4.78306139e-01f},
                                {-1.02363977e+03f, 1.20223470e-04f, 9.36662319e-01f},
                                {-1.26571316e+03f, 4.87340896e-06f, 1.27054498e+00f},
                                {-1.42529332e+03f, -4.01150431e-05f, 1.43972784e+00f},
                                {-1.17554822e+03f, -2.16378048e-05f, 1.30408023e+00f},
                                {-5.00799571e+02f, -4.59832026e-06f, 1.09098763e+00f}};
constexpr float kBlue[7][4] = {{5.96945309e-11f, -4.85742887e-08f, -9.70622247e-05f, -4.07936148e-03f},
                               {2.40430366e-11f, 5.55021075e-08f, -1.98503712e-04f, 2.89312858e-02f},
                               {-1.40949732e-11f, 1.89878968e-07f, -3.56632824e-04f, 9.10767778e-02f},
                               {-3.61460868e-11f, 2.84822009e-07f, -4.93211319e-04f, 1.56723440e-01f},
                               {-1.97075738e-11f, 1.75359352e-07f, -2.50542825e-04f, -2.22783266e-02f},
                               {-1.61997957e-13f, -1.64216008e-08f, 3.86216271e-04f, -7.38077418e-01f},
                               {6.72650283e-13f, -2.73078809e-08f, 4.24098264e-04f, -7.52335691e-01f}};

Vec3 blackbody_rec709(float t) {
    if (t >= 12000.0f) return {0.8262954810464208f, 0.9945080501520986f, 1.566307710274283f};
    if (t < 800.0f) return {5.413294490189271f, -0.20319390035873933f, -0.0822535242887164f};
    int band = 6;
    while (band > 0 && !(t >= kBandStart[band])) --band;
    const float* r = kRed[band];
    const float* g = kGreen[band];
    const float* b = kBlue[band];
    const float inv = 1.0f / t;
    return {r[0] * inv + r[1] * t + r[2], g[0] * inv + g[1] * t + g[2],
            ((b[0] * t + b[1]) * t + b[2]) * t + b[3]};
}

// CIE 1931 2-degree colour matching functions (x, y, z), 380 nm to 780 nm in 5 nm steps.
// clang-format off
constexpr float kColorMatch[81][3] = {
    /* 380 nm */ {0.0014f, 0.0000f, 0.0065f}, {0.0022f, 0.0001f, 0.0105f}, {0.0042f, 0.0001f, 0.0201f},
    /* 395 nm */ {0.0076f, 0.0002f, 0.0362f}, {0.0143f, 0.0004f, 0.0679f}, {0.0232f, 0.0006f, 0.1102f},
    /* 410 nm */ {0.0435f, 0.0012f, 0.2074f}, {0.0776f, 0.0022f, 0.3713f}, {0.1344f, 0.0040f, 0.6456f},
    /* 425 nm */ {0.2148f, 0.0073f, 1.0391f}, {0.2839f, 0.0116f, 1.3856f}, {0.3285f, 0.0168f, 1.6230f},
    /* 440 nm */ {0.3483f, 0.0230f, 1.7471f}, {0.3481f, 0.0298f, 1.7826f}, {0.3362f, 0.0380f, 1.7721f},
    /* 455 nm */ {0.3187f, 0.0480f, 1.7441f}, {0.2908f, 0.0600f, 1.6692f}, {0.2511f, 0.0739f, 1.5281f},
    /* 470 nm */ {0.1954f, 0.0910f, 1.2876f}, {0.1421f, 0.1126f, 1.0419f}, {0.0956f, 0.1390f, 0.8130f},
    /* 485 nm */ {0.0580f, 0.1693f, 0.6162f}, {0.0320f, 0.2080f, 0.4652f}, {0.0147f, 0.2586f, 0.3533f},
    /* 500 nm */ {0.0049f, 0.3230f, 0.2720f}, {0.0024f, 0.4073f, 0.2123f}, {0.0093f, 0.5030f, 0.1582f},
    /* 515 nm */ {0.0291f, 0.6082f, 0.1117f}, {0.0633f, 0.7100f, 0.0782f}, {0.1096f, 0.7932f, 0.0573f},
    /* 530 nm */ {0.1655f, 0.8620f, 0.0422f}, {0.2257f, 0.9149f, 0.0298f}, {0.2904f, 0.9540f, 0.0203f},
    /* 545 nm */ {0.3597f, 0.9803f, 0.0134f}, {0.4334f, 0.9950f, 0.0087f}, {0.5121f, 1.0000f, 0.0057f},
    /* 560 nm */ {0.5945f, 0.9950f, 0.0039f}, {0.6784f, 0.9786f, 0.0027f}, {0.7621f, 0.9520f, 0.0021f},
    /* 575 nm */ {0.8425f, 0.9154f, 0.0018f}, {0.9163f, 0.8700f, 0.0017f}, {0.9786f, 0.8163f, 0.0014f},
    /* 590 nm */ {1.0263f, 0.7570f, 0.0011f}, {1.0567f, 0.6949f, 0.0010f}, {1.0622f, 0.6310f, 0.0008f},
    /* 605 nm */ {1.0456f, 0.5668f, 0.0006f}, {1.0026f, 0.5030f, 0.0003f}, {0.9384f, 0.4412f, 0.0002f},
    /* 620 nm */ {0.8544f, 0.3810f, 0.0002f}, {0.7514f, 0.3210f, 0.0001f}, {0.6424f, 0.2650f, 0.0000f},
    /* 635 nm */ {0.5419f, 0.2170f, 0.0000f}, {0.4479f, 0.1750f, 0.0000f}, {0.3608f, 0.1382f, 0.0000f},
    /* 650 nm */ {0.2835f, 0.1070f, 0.0000f}, {0.2187f, 0.0816f, 0.0000f}, {0.1649f, 0.0610f, 0.0000f},
    /* 665 nm */ {0.1212f, 0.0446f, 0.0000f}, {0.0874f, 0.0320f, 0.0000f}, {0.0636f, 0.0232f, 0.0000f},
    /* 680 nm */ {0.0468f, 0.0170f, 0.0000f}, {0.0329f, 0.0119f, 0.0000f}, {0.0227f, 0.0082f, 0.0000f},
    /* 695 nm */ {0.0158f, 0.0057f, 0.0000f}, {0.0114f, 0.0041f, 0.0000f}, {0.0081f, 0.0029f, 0.0000f},
    /* 710 nm */ {0.0058f, 0.0021f, 0.0000f}, {0.0041f, 0.0015f, 0.0000f}, {0.0029f, 0.0010f, 0.0000f},
    /* 725 nm */ {0.0020f, 0.0007f, 0.0000f}, {0.0014f, 0.0005f, 0.0000f}, {0.0010f, 0.0004f, 0.0000f},
    /* 740 nm */ {0.0007f, 0.0002f, 0.0000f}, {0.0005f, 0.0002f, 0.0000f}, {0.0003f, 0.0001f, 0.0000f},
    /* 755 nm */ {0.0002f, 0.0001f, 0.0000f}, {0.0002f, 0.0001f, 0.0000f}, {0.0001f, 0.0000f, 0.0000f},
    /* 770 nm */ {0.0001f, 0.0000f, 0.0000f}, {0.0001f, 0.0000f, 0.0000f}, {0.0000f, 0.0000f, 0.0000f}
};
// clang-format on

Vec3 wavelength_xyz(float nm) {
    float scaled = (nm - 380.0f) * (1.0f / 5.0f);
    // The integer part truncates toward zero (Cycles' float_to_int), so (375, 380) nm reads the
    // first interval; a value beyond int's range or NaN reads nothing.
    if (!(scaled > -1.0f && scaled < 80.0f)) return {};
    const int i = static_cast<int>(scaled);
    scaled -= static_cast<float>(i);
    const float* lo = kColorMatch[i];
    const float* hi = kColorMatch[i + 1];
    return {lo[0] + scaled * (hi[0] - lo[0]), lo[1] + scaled * (hi[1] - lo[1]),
            lo[2] + scaled * (hi[2] - lo[2])};
}

Vec3 to_working(const float* m, Vec3 c) {
    const auto row = [&](int k) {
        return std::fmax(m[3 * k] * c.x + m[3 * k + 1] * c.y + m[3 * k + 2] * c.z, 0.0f);
    };
    return {row(0), row(1), row(2)};
}

std::string check_matrix(const ShaderNode& n, const ShaderProgram&) {
    if (n.data_count != 9) return "data count is " + std::to_string(n.data_count) + "; 9 (a 3x3 matrix)";
    return "";
}

void evaluate_blackbody(const ShaderNode& n, const ShaderEvalContext& context, ShaderRegisters& r) {
    r.set(n.outputs[0], to_working(context.data(n), blackbody_rec709(r[n.inputs[0]])));
}

void evaluate_wavelength(const ShaderNode& n, const ShaderEvalContext& context, ShaderRegisters& r) {
    r.set(n.outputs[0], to_working(context.data(n), wavelength_xyz(r[n.inputs[0]])) * (1.0f / 2.52f));
}

}  // namespace

const NodeRegistration kBlackbodyNode{{.value = 31,
                                       .name = "blackbody",
                                       .input_widths = {1},
                                       .output_widths = {3},
                                       .check = check_matrix,
                                       .evaluate = evaluate_blackbody}};

const NodeRegistration kWavelengthNode{{.value = 32,
                                        .name = "wavelength",
                                        .input_widths = {1},
                                        .output_widths = {3},
                                        .check = check_matrix,
                                        .evaluate = evaluate_wavelength}};

}  // namespace stratum
