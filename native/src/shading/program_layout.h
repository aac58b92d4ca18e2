// The register layout of the renderer's inputs to shader programs: the values of
// stratum/shader_nodes.h's StratumShaderInput for the layers below the API, which do not include
// the public header; api/shader_program_api.cpp checks at compile time that they agree. (Node
// types are not listed here: each node files its own value, shading/node_registry.h.)
#pragma once

#include <cstdint>

namespace stratum {

namespace shader_input {
inline constexpr uint32_t kPosition = 0;
inline constexpr uint32_t kNormal = 3;
inline constexpr uint32_t kTrueNormal = 6;
inline constexpr uint32_t kIncoming = 9;
inline constexpr uint32_t kUv = 12;
inline constexpr uint32_t kGenerated = 15;
inline constexpr uint32_t kObject = 18;
inline constexpr uint32_t kCamera = 21;
inline constexpr uint32_t kWindow = 24;
inline constexpr uint32_t kObjectLocation = 27;
inline constexpr uint32_t kBackfacing = 30;
inline constexpr uint32_t kObjectRandom = 31;
inline constexpr uint32_t kRayLength = 32;
inline constexpr uint32_t kObjectIndex = 33;
inline constexpr uint32_t kMaterialIndex = 34;
inline constexpr uint32_t kObjectColor = 35;
inline constexpr uint32_t kObjectAlpha = 38;
inline constexpr uint32_t kTangent = 39;
inline constexpr uint32_t kParametric = 42;
inline constexpr uint32_t kObjectNormal = 45;
inline constexpr uint32_t kDpdx = 48;
inline constexpr uint32_t kDpdy = 51;
inline constexpr uint32_t kDgeneratedDx = 54;
inline constexpr uint32_t kDgeneratedDy = 57;
inline constexpr uint32_t kDobjectDx = 60;
inline constexpr uint32_t kDobjectDy = 63;
inline constexpr uint32_t kDuvDx = 66;
inline constexpr uint32_t kDuvDy = 69;
inline constexpr uint32_t kReflection = 72;
inline constexpr uint32_t kUvTangent = 75;
inline constexpr uint32_t kPixelFootprint = 78;
inline constexpr uint32_t kAttribute0 = 80;
inline constexpr uint32_t kAttribute1 = 85;
inline constexpr uint32_t kAttribute2 = 90;
inline constexpr uint32_t kAttribute3 = 95;
inline constexpr uint32_t kTriangle = 100;
inline constexpr uint32_t kMikktspaceTangent = 109;
inline constexpr uint32_t kNormalTransform = 112;
// Cycles' Light Path node (shading/light_path_state.h): eight 0/1 ray kinds, then the depths.
inline constexpr uint32_t kIsCameraRay = 121;
inline constexpr uint32_t kIsShadowRay = 122;
inline constexpr uint32_t kIsDiffuseRay = 123;
inline constexpr uint32_t kIsGlossyRay = 124;
inline constexpr uint32_t kIsSingularRay = 125;
inline constexpr uint32_t kIsReflectionRay = 126;
inline constexpr uint32_t kIsTransmissionRay = 127;
inline constexpr uint32_t kIsVolumeScatterRay = 128;
inline constexpr uint32_t kRayDepth = 129;
inline constexpr uint32_t kDiffuseDepth = 130;
inline constexpr uint32_t kGlossyDepth = 131;
inline constexpr uint32_t kTransparentDepth = 132;
inline constexpr uint32_t kTransmissionDepth = 133;
inline constexpr uint32_t kPortalDepth = 134;
inline constexpr uint32_t kAttributeSlots = 4;
inline constexpr uint32_t kAttributeWidth = 5;
inline constexpr uint32_t kCount = 144;
}  // namespace shader_input

}  // namespace stratum
