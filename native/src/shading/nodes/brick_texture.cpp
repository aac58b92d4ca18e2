// Brick Texture (Blender's ShaderNodeTexBrick), as Cycles' svm/brick.h.
//
// | node  | modes                                       | inputs                               | outputs   |
// |-------|---------------------------------------------|--------------------------------------|-----------|
// | brick | 0 offset frequency (0..255), 1 squash       | 0 vector (3), 1 color1 (3), 2 color2 | 0 color   |
// |       | frequency (0..255), 2 smoothing (0: Cycles  | (3), 3 mortar (3), 4 scale, 5 mortar | (3),      |
// |       | 3.4, 1: 3.5 and later)                      | size, 6 mortar smooth, 7 bias, 8     | 1 fac     |
// |       |                                             | brick width, 9 row height            |           |
//
// Data (2 values): the node's offset amount and squash amount (properties, not sockets).
//
// On p = vector x scale: row = floor(p.y / row height); when both frequencies are non-zero, rows
// with row % squash frequency == 0 have their width times the squash amount and rows with row %
// offset frequency == 0 are shifted by width x offset amount; brick = floor((p.x + shift) / width).
// The tint is saturate(noise(row << 16 + (brick & 0xFFFF)) + bias) with the integer noise below
// (not lookup3). The distance to the brick's nearest edge m gives the mortar: 0 at or beyond the
// mortar size, 1 with no smoothing, else smoothstep((1 - m / size) / smooth). 3.4's smoothstep was
// not clamped and was used only while 1 - m / size < smooth (else 1); 3.5 clamps it to [0, 1]:
// the two differ only for a negative smoothing. Color is mix(color1, color2, tint) (color1 alone
// where fac = 1) blended to the mortar colour by fac; fac is the mortar.
#include <cmath>
#include <cstdint>

#include "shading/node_registry.h"
#include "shading/pattern_math.h"

namespace stratum {

namespace {

enum Smoothing : int32_t { Cycles34, Cycles35, SmoothingCount };

// Cycles' "fast integer noise" of the brick texture, in [0, 1).
float brick_noise(uint32_t n) {
    n = (n + 1013u) & 0x7fffffffu;
    n = (n >> 13) ^ n;
    const uint32_t nn = (n * (n * n * 60493u + 19990303u) + 1376312589u) & 0x7fffffffu;
    return 0.5f * (static_cast<float>(nn) / 1073741824.0f);
}

struct BrickParams {
    float mortar_size, mortar_smooth, bias, width, row_height, offset_amount, squash_amount;
    int32_t offset_frequency, squash_frequency, smoothing;
};

// (tint, mortar) at p.
std::pair<float, float> brick(Vec3 p, const BrickParams& b) {
    using pattern_math::floor_to_int;
    const int32_t row = floor_to_int(p.y / b.row_height);
    float width = b.width, offset = 0.0f;
    if (b.offset_frequency != 0 && b.squash_frequency != 0) {
        // % of INT_MIN by a positive int is defined; row stays an int as in Cycles.
        width *= (row % b.squash_frequency) != 0 ? 1.0f : b.squash_amount;
        offset = (row % b.offset_frequency) != 0 ? 0.0f : width * b.offset_amount;
    }
    const int32_t column = floor_to_int((p.x + offset) / width);
    const float x = (p.x + offset) - width * static_cast<float>(column);
    const float y = p.y - b.row_height * static_cast<float>(row);
    // row << 16 wraps as Cycles' int shift does on its targets; done unsigned to stay defined.
    const uint32_t key = (static_cast<uint32_t>(row) << 16) + (static_cast<uint32_t>(column) & 0xFFFFu);
    const float tint = pattern_math::saturate(brick_noise(key) + b.bias);
    const float a = x < y ? x : y;
    const float c = (width - x) < (b.row_height - y) ? (width - x) : (b.row_height - y);
    float min_dist = a < c ? a : c;
    float mortar;
    if (min_dist >= b.mortar_size) {
        mortar = 0.0f;
    } else if (b.mortar_smooth == 0.0f) {
        mortar = 1.0f;
    } else {
        min_dist = 1.0f - min_dist / b.mortar_size;
        if (b.smoothing == Cycles34) {
            mortar = min_dist < b.mortar_smooth
                         ? pattern_math::smoothstep_unclamped(min_dist / b.mortar_smooth)
                         : 1.0f;
        } else {
            mortar = pattern_math::smoothstep_clamped(min_dist / b.mortar_smooth);
        }
    }
    return {tint, mortar};
}

std::string check_brick(const ShaderNode& n, const ShaderProgram&) {
    std::string e = check_mode(n, 0, "offset frequency", 256);
    if (e.empty()) e = check_mode(n, 1, "squash frequency", 256);
    if (e.empty()) e = check_mode(n, 2, "smoothing", SmoothingCount);
    if (e.empty() && n.data_count != 2)
        e = "data_count is " + std::to_string(n.data_count) + "; 2 (offset amount, squash amount)";
    return e;
}

void evaluate_brick(const ShaderNode& n, const ShaderEvalContext& context, ShaderRegisters& r) {
    const float* data = context.data(n);
    const BrickParams params{r[n.inputs[5]], r[n.inputs[6]], r[n.inputs[7]], r[n.inputs[8]], r[n.inputs[9]],
                             data[0],        data[1],        n.modes[0],     n.modes[1],     n.modes[2]};
    const auto [tint, fac] = brick(r.vec3(n.inputs[0]) * r[n.inputs[4]], params);
    Rgb color1 = r.rgb(n.inputs[1]);
    if (fac != 1.0f) color1 = (1.0f - tint) * color1 + tint * r.rgb(n.inputs[2]);
    r.set(n.outputs[0], color1 * (1.0f - fac) + r.rgb(n.inputs[3]) * fac);
    r[n.outputs[1]] = fac;
}

}  // namespace

const NodeRegistration kBrickNode{{.value = 23,
                                   .name = "brick",
                                   .input_widths = {3, 3, 3, 3, 1, 1, 1, 1, 1, 1},
                                   .output_widths = {3, 1},
                                   .check = check_brick,
                                   .evaluate = evaluate_brick}};

}  // namespace stratum
