#include "shading/node_registry.h"

#include <vector>

#include "shading/nodes/node_families.h"

namespace stratum {

namespace {

std::vector<NodeEntry> build_table() {
    std::vector<NodeEntry> table(node_type::kTypeCount, NodeEntry{});
    const auto put = [&](int32_t type, NodeEntry entry) { table[type] = entry; };
    put(node_type::kMath, math_node_entry());
    put(node_type::kCopy, copy_node_entry());
    put(node_type::kBump, bump_node_entry());
    put(node_type::kNormalMap, normal_map_node_entry());
    put(node_type::kMix, mix_node_entry());
    put(node_type::kInvert, invert_node_entry());
    put(node_type::kGamma, gamma_node_entry());
    put(node_type::kBrightContrast, bright_contrast_node_entry());
    put(node_type::kHsv, hsv_node_entry());
    put(node_type::kRgbToBw, rgb_to_bw_node_entry());
    put(node_type::kSeparateColor, separate_color_node_entry());
    put(node_type::kCombineColor, combine_color_node_entry());
    put(node_type::kColorRamp, color_ramp_node_entry());
    put(node_type::kCurves, curves_node_entry());
    put(node_type::kNoise, noise_node_entry());
    put(node_type::kMusgrave, musgrave_node_entry());
    put(node_type::kVoronoi, voronoi_node_entry());
    put(node_type::kWhiteNoise, white_noise_node_entry());
    put(node_type::kVectorMath, vector_math_node_entry());
    put(node_type::kMapRange, map_range_node_entry());
    put(node_type::kClamp, clamp_node_entry());
    put(node_type::kMapping, mapping_node_entry());
    put(node_type::kVectorRotate, vector_rotate_node_entry());
    put(node_type::kVectorTransform, vector_transform_node_entry());
    put(node_type::kFresnel, fresnel_node_entry());
    put(node_type::kLayerWeight, layer_weight_node_entry());
    put(node_type::kNormal, normal_node_entry());
    put(node_type::kBlackbody, blackbody_node_entry());
    put(node_type::kWavelength, wavelength_node_entry());
    put(node_type::kChecker, checker_node_entry());
    put(node_type::kGradient, gradient_node_entry());
    put(node_type::kBrick, brick_node_entry());
    put(node_type::kMagic, magic_node_entry());
    put(node_type::kImage, image_node_entry());
    put(node_type::kWave, wave_node_entry());
    put(node_type::kSky, sky_node_entry());
    return table;
}

}  // namespace

const NodeEntry* node_entry(int32_t type) {
    static const std::vector<NodeEntry> table = build_table();
    if (type < 0 || type >= static_cast<int32_t>(table.size()) || table[type].evaluate == nullptr)
        return nullptr;
    return &table[type];
}

std::string check_mode(const ShaderNode& node, int index, const char* what, int32_t count) {
    const int32_t v = node.modes[index];
    if (v >= 0 && v < count) return "";
    return "mode " + std::to_string(index) + " (" + what + ") is " + std::to_string(v) + "; 0.." +
           std::to_string(count - 1);
}

}  // namespace stratum
