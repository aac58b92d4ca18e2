// The ceiling for `make bench`: how many rays per second Embree alone traces through a scene
// with the same ray mix as the path tracer, without sampling, shading, lights or film.
//
// | parameter     | meaning |
// |---------------|---------|
// | width, height | camera rays through the pixel centres, `samples` per pixel |
// | max_bounces   | each path continues with a cosine-distributed bounce ray at every vertex up to
// max_bounces, as a path does | | shadow rays   | one occlusion ray per vertex (a second cosine direction, up
// to the scene size), like NEE's one shadow ray | | threads       | TBB workers, 0 = all cores |
//
// Stratum's rays/s divided by this is the fraction of the raw tracing speed the renderer keeps.
#pragma once

#include <cstdint>

#include "scene/scene.h"

namespace stratum {

struct RayThroughput {
    double rays = 0;
    double seconds = 0;  // tracing only, without the BVH build
};

// Throws std::runtime_error when the scene has no camera or Embree fails.
RayThroughput measure_ray_throughput(const Scene& scene, uint32_t width, uint32_t height, uint32_t samples,
                                     uint32_t max_bounces, uint32_t threads);

}  // namespace stratum
