// Conversion of image texels to the renderer's scene-linear space with OpenColorIO, from the
// image's colour space (Blender's Image > Color Space) through Blender's own config.
//
// | config          | colour space              | conversion                                 |
// |-----------------|---------------------------|--------------------------------------------|
// | a readable file | data (isdata, Non-Color)  | none                                       |
// |                 | any other name or alias   | OCIO processor: space -> scene_linear role |
// | NULL            | Non-Color, Raw, Linear,   | none                                       |
// |                 | Linear Rec.709            |                                            |
// |                 | sRGB                      | IEC 61966-2-1 piecewise EOTF (built in)    |
// | unreadable      | the NULL names only       | built in, as NULL (see below)              |
//
// Debian 12 ships OpenColorIO 2.1.2, which reads config versions up to 2.1: Blender 3.4's
// config (version 2.0) works, Blender 5.0's (ocio_profile_version 2.4) is refused by the
// library ("minor version 4 is not supported"). For such a config the built-in names are
// converted with the built-in transforms, which equal what Blender 5.0's config defines for
// them (its sRGB is the same piecewise curve, its scene_linear is Linear Rec.709); any other
// name is an error that says why. An OCIO colour space whose conversion is the sRGB curve on
// each channel alone is recognised as Cycles recognises it (ColorSpaceManager::
// is_builtin_colorspace, Cycles 3.4-5.0: the 256 levels v/255 on R, G, B and grey, no crosstalk
// above 1e-5, channels alike, within 1e-4 of the curve). Alpha is never converted. Conversions are cached per
// (config, colour space); the cache is shared by all threads. A config path that is no regular
// file (a directory, a FIFO, a device) is treated as unreadable without being opened: reading a
// FIFO would block forever.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace stratum {

// One colour space's conversion to scene linear, applied to runs of straight-alpha RGBA pixels.
// Stored 8- and 16-bit values are normalised (v / 255, v / 65535) as OpenImageIO does; for them
// the conversion is a lookup table (the built-in sRGB curve) or OCIO's processor optimised for
// that input depth, which turns the per-channel prefix of the transform into a table. Thread-safe.
class SceneLinearConversion {
public:
    struct Impl;
    explicit SceneLinearConversion(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}

    // True when the conversion is the sRGB curve itself (the built-in "sRGB", or an OCIO colour
    // space that Cycles' test finds equal to it: see conversion_to_scene_linear). Cycles keeps
    // such images sRGB-encoded and decodes after interpolation; textures do the same.
    bool is_srgb_curve() const;

    void apply(float* rgba, size_t count) const;  // in place
    void apply(const uint8_t* rgba, float* out, size_t count) const;
    void apply(const uint16_t* rgba, float* out, size_t count) const;

private:
    std::shared_ptr<const Impl> impl_;
};

// The conversion from `color_space` to scene linear. config_path NULL or empty: built-in names
// only. Throws std::invalid_argument naming an unknown colour space (and listing valid names).
SceneLinearConversion conversion_to_scene_linear(const char* config_path, const std::string& color_space);

// The built-in sRGB decoding curve (IEC 61966-2-1): sRGB-encoded value to linear.
float srgb_to_linear(float encoded);

// As Cycles decodes an interpolated sRGB texel (util/color.h color_srgb_to_linear): the same
// curve, negative values to 0.
inline float srgb_texel_to_linear(float encoded) { return encoded < 0.0f ? 0.0f : srgb_to_linear(encoded); }

}  // namespace stratum
