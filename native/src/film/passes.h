// The passes (AOVs) a film can hold: the one list, named as Cycles names them so Blender's
// compositor and multilayer EXR read them unchanged. `Combined` (RGBA) is always there; the
// others exist in a render when the `passes` setting names them.
//
// | kind     | per pixel                                                                    |
// |----------|------------------------------------------------------------------------------|
// | Radiance | mean of the camera samples' values, plus light-path splats / sample indices  |
// | Average  | mean of the camera samples' values (data passes: normals, albedo, ...)        |
//
// Adding a pass: a line here, the integrator line that writes it (PassValues::write), a test.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

namespace stratum {

enum class PassKind : uint8_t { Radiance, Average };

struct PassInfo {
    const char* name;
    uint32_t channels;
    PassKind kind;
    const char* description;
};

// Index into kPasses.
enum class Pass : uint32_t { Combined, Normal };

inline constexpr std::array kPasses = {
    PassInfo{"Combined", 4, PassKind::Radiance, "The rendered image: radiance (RGB) and alpha"},
    PassInfo{"Normal", 3, PassKind::Average,
             "World-space shading normal of the first surface a camera ray meets (0 where it meets none)"},
};

inline constexpr const PassInfo& pass_info(Pass pass) { return kPasses[static_cast<uint32_t>(pass)]; }
// The pass of this name, or false.
inline bool find_pass(std::string_view name, Pass* out) {
    for (uint32_t i = 0; i < kPasses.size(); ++i) {
        if (name == kPasses[i].name) {
            *out = static_cast<Pass>(i);
            return true;
        }
    }
    return false;
}

}  // namespace stratum
