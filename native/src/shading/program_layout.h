// The register layout of the renderer's inputs and the node type numbers of shader programs:
// the values of stratum/shader_nodes.h (StratumShaderInput, StratumShaderNodeType) for the layers
// below the API, which do not include the public header; api/shader_program_api.cpp checks that
// they agree.
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
inline constexpr uint32_t kAttribute0 = 80;
inline constexpr uint32_t kAttribute1 = 85;
inline constexpr uint32_t kAttribute2 = 90;
inline constexpr uint32_t kAttribute3 = 95;
inline constexpr uint32_t kAttributeSlots = 4;
inline constexpr uint32_t kAttributeWidth = 5;
inline constexpr uint32_t kCount = 100;
}  // namespace shader_input

namespace node_type {
inline constexpr int32_t kMath = 0;
inline constexpr int32_t kVectorMath = 1;
inline constexpr int32_t kMix = 2;
inline constexpr int32_t kMapRange = 3;
inline constexpr int32_t kClamp = 4;
inline constexpr int32_t kInvert = 5;
inline constexpr int32_t kGamma = 6;
inline constexpr int32_t kBrightContrast = 7;
inline constexpr int32_t kHsv = 8;
inline constexpr int32_t kSeparateColor = 9;
inline constexpr int32_t kCombineColor = 10;
inline constexpr int32_t kRgbToBw = 11;
inline constexpr int32_t kColorRamp = 12;
inline constexpr int32_t kCurves = 13;
inline constexpr int32_t kMapping = 14;
inline constexpr int32_t kVectorRotate = 15;
inline constexpr int32_t kFresnel = 16;
inline constexpr int32_t kLayerWeight = 17;
inline constexpr int32_t kImage = 18;
inline constexpr int32_t kNoise = 19;
inline constexpr int32_t kVoronoi = 20;
inline constexpr int32_t kWave = 21;
inline constexpr int32_t kChecker = 22;
inline constexpr int32_t kBrick = 23;
inline constexpr int32_t kGradient = 24;
inline constexpr int32_t kMagic = 25;
inline constexpr int32_t kWhiteNoise = 26;
inline constexpr int32_t kMusgrave = 27;
inline constexpr int32_t kSky = 28;
inline constexpr int32_t kBump = 29;
inline constexpr int32_t kNormalMap = 30;
inline constexpr int32_t kBlackbody = 31;
inline constexpr int32_t kWavelength = 32;
inline constexpr int32_t kVectorTransform = 33;
inline constexpr int32_t kNormal = 34;
inline constexpr int32_t kCopy = 35;
inline constexpr int32_t kTypeCount = 36;
}  // namespace node_type

}  // namespace stratum
