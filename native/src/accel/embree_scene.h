// Ray queries against world-space triangle meshes. The only file set that includes Embree;
// the rest of the core sees plain hits (geometry index, triangle index, barycentrics).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/math.h"

namespace stratum {

struct TriangleGeometry {
    std::span<const Vec3> positions;
    std::span<const std::array<uint32_t, 3>> triangles;
};

struct RayHit {
    float t;
    uint32_t geometry;  // index into the geometries given to build()
    uint32_t triangle;
    float b1, b2;  // barycentrics of vertices 1 and 2
};

class EmbreeScene {
public:
    EmbreeScene();
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    // Builds the BVH. Returns an empty string on success, otherwise Embree's error message.
    std::string build(std::span<const TriangleGeometry> geometries);
    // Closest hit with t in (t_min, t_max); false if none.
    bool intersect(Vec3 origin, Vec3 direction, float t_min, float t_max, RayHit* hit) const;
    // True if anything lies on the ray with t in (t_min, t_max).
    bool occluded(Vec3 origin, Vec3 direction, float t_min, float t_max) const;

    struct Impl;  // Embree handles; public so Embree's C error callback can reach it

private:
    Impl* impl_;
};

}  // namespace stratum
