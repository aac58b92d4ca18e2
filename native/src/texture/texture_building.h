// A stored image (image_reading.h) to the render-ready float RGBA texels of a Texture
// (texture.h): channels expanded, alpha made straight, colour converted to scene linear, and
// the texels that are not finite replaced.
//
// | step         | rule                                                                    |
// |--------------|-------------------------------------------------------------------------|
// | channels     | 1 grey -> (g, g, g, 1); 2 grey + alpha; 3 RGB -> alpha 1; 4+ RGB + alpha |
// | alpha        | associated (premultiplied) colour divided by alpha where alpha > 0       |
// | colour       | SceneLinearConversion (color_conversion.h); alpha never converted. When  |
// |              | the conversion is the sRGB curve the texels stay sRGB-encoded and the   |
// |              | lookup decodes after interpolating, as Cycles (svm_image_texture,       |
// |              | NODE_IMAGE_COMPRESS_AS_SRGB): interpolating encoded values gives darker |
// |              | edges between texels than interpolating linear ones                     |
// | non-finite   | a texel with any NaN or infinite channel after conversion (e.g. an sRGB  |
// |              | float of 1e19 decodes beyond FLT_MAX, also when the decoding is left to |
// |              | the lookup) becomes (0, 0, 0, 0): Cycles'                               |
// |              | rule, scene/image.cpp "Make sure we don't have buggy values" (Cycles    |
// |              | 3.4-5.0), applied after its colour conversion too. Counted: those and   |
// |              | the texels not finite as stored, which a conversion may have turned    |
// |              | into numbers (OCIO's sRGB gives 0 for NaN) but the user should hear of  |
// | rows         | row 0 of the result is the bottom of the picture                        |
//
// Rows are converted in parallel; each texel depends only on its stored pixel, so the result
// does not depend on the thread count.
#pragma once

#include <cstdint>
#include <vector>

#include "core/uninitialized_allocator.h"
#include "texture/color_conversion.h"
#include "texture/image_reading.h"

namespace stratum {

struct SceneLinearTexels {
    UninitializedVector<float> rgba;  // width*height*4, row 0 at the bottom
    uint64_t replaced_texels = 0;
    bool srgb_encoded = false;  // RGB still sRGB-encoded (Texture::srgb_encoded)
};

SceneLinearTexels scene_linear_texels(const StoredImage& image, const SceneLinearConversion& conversion);

}  // namespace stratum
