// Ray queries against instanced triangle meshes: a two-level Embree BVH. The only file set that
// includes Embree; the rest of the core sees plain hits (instance index, triangle index,
// barycentrics).
//
// A mesh placed several times, or moving, gets one object-space BVH (an Embree scene holding one
// triangle geometry) and each placement is an RTC_GEOMETRY_TYPE_INSTANCE of it in the top-level
// scene, so N placements of one mesh cost one mesh of memory plus N small instance records. A
// mesh placed once and static is flattened into the top level in world space instead (what
// Cycles does with single-user objects): its rays skip the instance indirection.
//
// | placement field | Embree |
// |-----------------|--------|
// | start, end      | instance transform at time 0 and 1 (2 time steps when `motion`); the
// |                 | steps are given as RTC_FORMAT_QUATERNION_DECOMPOSITION so rotation is
// |                 | interpolated by slerp and scale/skew/translation linearly (Embree >= 3.6) |
// | mask            | rtcSetGeometryMask: a ray of mask m sees the instance iff (m & mask) != 0;
// |                 | Debian's Embree 3.13 is built with EMBREE_RAY_MASK (checked at build) |
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/math.h"

namespace stratum {

// A mesh's arrays. Embree reads `triangles` in place: it must outlive the EmbreeScene built
// from it (RenderScene's meshes live in the Scene it was built from, which outlives it).
struct TriangleGeometry {
    std::span<const Vec3> positions;
    std::span<const std::array<uint32_t, 3>> triangles;
};

struct InstancePlacement {
    uint32_t prototype = 0;  // index into the prototypes given to build()
    Transform start;         // object-to-world (always, when not moving)
    Transform end;           // object-to-world at time 1; read when `motion`
    bool motion = false;
    uint32_t mask = 0xffffffffu;
};

struct RayHit {
    float t;
    uint32_t instance;  // index into the placements given to build()
    uint32_t triangle;
    float b1, b2;  // barycentrics of vertices 1 and 2
};

class EmbreeScene {
public:
    EmbreeScene();
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    // Builds the BVHs. Returns an empty string on success, otherwise Embree's error message.
    // ray_origin_limit: the largest |coordinate| a ray origin may have (scene/scene_limits.h);
    // placements must be traceable for it (scene/placement_conditioning.h). The build stops
    // early, returning kBuildCancelled, once *cancel becomes true (cancel may be null).
    // `flatten`: a mesh placed once and static goes into the top level in world space (fastest
    // to trace); false instances every mesh, so that moving any object is a top-level
    // recommit (Cycles' dynamic viewport BVH).
    std::string build(std::span<const TriangleGeometry> prototypes,
                      std::span<const InstancePlacement> placements, float ray_origin_limit,
                      const std::atomic<bool>* cancel = nullptr, bool flatten = true);
    static constexpr const char* kBuildCancelled = "BVH build cancelled";
    // Re-places the placements listed in `changed` (indices into `placements`, which are those
    // given to build() with new transforms and masks; prototypes and motion as built) and
    // recommits the top level: for an instanced mesh only its instance record changes, a
    // flattened one has its world-space vertices mapped anew. The result is what build() gives
    // for these placements. Returns an empty string or Embree's error.
    std::string update(std::span<const InstancePlacement> placements, std::span<const uint32_t> changed,
                       float ray_origin_limit);
    // Closest hit with t in (t_min, t_max) at shutter time `time` in [0,1], among instances whose
    // mask shares a bit with `mask`; false if none.
    bool intersect(Vec3 origin, Vec3 direction, float t_min, float t_max, float time, uint32_t mask,
                   RayHit* hit) const;
    // True if anything visible to `mask` lies on the ray with t in (t_min, t_max) at `time`.
    bool occluded(Vec3 origin, Vec3 direction, float t_min, float t_max, float time, uint32_t mask) const;
    // Object-to-world transform of a moving placement at `time`, interpolated by Embree exactly
    // as the traversal interpolates it.
    Transform motion_transform(uint32_t instance, float time) const;
    // Rays refused so far because Embree would have rejected them (an origin beyond the
    // limit, a direction that is not finite or not at most unit length, t_min < 0 or not
    // finite, t_max NaN, a time outside [0, 1]): a refused intersect() misses, a refused
    // occluded() is occluded. A bug or an extreme input upstream; counted to be reported.
    uint64_t refused_rays() const;

    struct Impl;  // Embree handles; public so Embree's C error callback can reach it

private:
    Impl* impl_;
};

// Splits the linear part A of `m` into A = R·S, R a rotation (unit quaternion r, i, j, k) and S
// upper triangular (scale on the diagonal, skew above it; Embree's layout), by Gram–Schmidt on
// A's columns. A mirroring A (det < 0) gets a negative scale_z so that R stays a rotation.
struct MotionDecomposition {
    float scale[3];
    float skew_xy, skew_xz, skew_yz;
    float quaternion[4];  // r, i, j, k
    Vec3 translation;
};
MotionDecomposition decompose_transform(const Transform& m);

}  // namespace stratum
