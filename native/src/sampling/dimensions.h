// The named sample-dimension layout shared by every integrator (DESIGN.md "Dimensions").
// Camera dimensions come first; each bounce then owns a fixed block of kBounceStride
// dimensions, so switching a feature off never shifts the dimensions later bounces use and
// samplers are compared on equal terms. 2D quantities occupy two consecutive dimensions, the
// first of them even, so samplers that pad 2D pairs (Sobol) see them as one pair.
#pragma once

#include <cstdint>

namespace stratum {

enum CameraDimension : uint32_t {
    kDimFilter = 0,  // 2D: pixel filter offset
    kDimLens = 2,    // 2D: aperture position
    kDimTime = 4,    // 1D: shutter time
};

enum BounceDimension : uint32_t {
    kDimLightChoice = 0,      // 1D: which light NEE samples
    kDimRussianRoulette = 1,  // 1D: path termination
    kDimLightPoint = 2,       // 2D: point on the chosen light
    kDimBsdfDirection = 4,    // 2D: scattered direction
    kDimBsdfLobe = 6,         // 1D: lobe of a layered BSDF
    kDimGuideChoice = 7,      // 1D: path guiding: closures or guide (integrators/guided_direction.h)
};

// A light-tracing particle (x, y, i) draws from PixelSample{x, y, i} in the same layout: its
// emission takes the camera block (time stays at kDimTime, so motion blur samples the shutter
// as camera rays do), and surface vertex k owns bounce block k, where the lens point of the
// camera connection takes the slot NEE's light point has in a camera path.
enum ParticleDimension : uint32_t {
    kDimEmissionPoint = 0,      // 2D: point on the light (or its beam disk)
    kDimEmissionDirection = 2,  // 2D: direction of emission
    kDimEmissionLight = 5,      // 1D: which light emits
};
inline constexpr BounceDimension kDimConnectionLens = kDimLightPoint;  // 2D: lens point

inline constexpr uint32_t kCameraDimensions = 6;
inline constexpr uint32_t kBounceStride = 8;

constexpr uint32_t bounce_dimension(uint32_t bounce, BounceDimension d) {
    return kCameraDimensions + bounce * kBounceStride + d;
}

}  // namespace stratum
