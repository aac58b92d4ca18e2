// How large a scene may be, and why: the numbers that keep every ray Embree sees valid.
//
// Embree 3.13 (Debian builds it with assertions on) aborts the process on a ray that fails
// RayK::valid() (kernels/common/ray.h): every component of the origin and of the direction at
// most FLT_LARGE = 1.844e18 in magnitude, tnear and tfar not NaN; and on tnear < 0 or, in a
// motion-blur BVH, a time outside [0, 1] (kernels/bvh/bvh_intersector1.cpp). An instance's
// rays are checked again after Embree maps them into the instance's object space with the
// inverse transform, so a valid world ray can become an invalid one there: a mesh placed with
// scale 1e-18 multiplies the ray's coordinates by 1e18.
//
// The guarantee has three parts:
// * At the ABI (api/validation.cpp), coordinates are bounded: a vertex, a translation, the
//   world-space extent of a placed mesh, a camera or light position at most kMaxCoordinate from
//   the origin; a transform's linear part at most kMaxLinear per element; lens, sensor, ortho
//   scale, aperture and focus distance within the ranges below. 1e12 m is seven times the
//   distance to the Sun: a city in millimetres or a planet in metres fits with a factor 1e5 to
//   spare, while float32 already spaces representable coordinates 1e5 apart there.
// * When the render scene is built (scene/placement_conditioning.h), a placement whose inverse
//   transform could map a ray origin of this scene (within ray_origin_limit(), a multiple of
//   the scene's own extent) beyond kMaxObjectRayCoordinate is skipped with a notice: a
//   zero-scale or nearly zero-scale linked duplicate.
// * Every ray is checked before Embree sees it (accel/embree_scene.cpp): a ray that would fail
//   the checks above is a miss (an occlusion query: occluded), counted and reported once.
#pragma once

namespace stratum {

inline constexpr float kMaxCoordinate = 1e12f;
inline constexpr float kMaxLinear = 1e12f;
// Object-space ray coordinates stay below this, FLT_LARGE (1.844e18) with a margin for the
// rounding of Embree's own transform.
inline constexpr double kMaxObjectRayCoordinate = 1e18;

// Camera ranges (Blender: lens >= 1 mm, sensor 1..100 mm): a view-plane point at unit depth is
// at most sensor / lens = 1e7 from the axis, so the direction's squared length stays far from
// overflow however wide the image.
inline constexpr float kMinLensMm = 1e-3f, kMaxLensMm = 1e6f;
inline constexpr float kMinSensorMm = 1e-3f, kMaxSensorMm = 1e4f;

}  // namespace stratum
