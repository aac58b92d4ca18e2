#include "accel/embree_scene.h"

#include <embree3/rtcore.h>

#include <cstring>
#include <limits>
#include <mutex>

namespace stratum {

struct EmbreeScene::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::mutex error_mutex;
    std::string error;
};

namespace {

void record_error(void* user, RTCError code, const char* message) {
    auto* impl = static_cast<EmbreeScene::Impl*>(user);
    std::lock_guard lock(impl->error_mutex);
    if (impl->error.empty())
        impl->error =
            "Embree error " + std::to_string(static_cast<int>(code)) + ": " + (message ? message : "");
}

}  // namespace

EmbreeScene::EmbreeScene() : impl_(new Impl) {}

EmbreeScene::~EmbreeScene() {
    if (impl_->scene) rtcReleaseScene(impl_->scene);
    if (impl_->device) rtcReleaseDevice(impl_->device);
    delete impl_;
}

std::string EmbreeScene::build(std::span<const TriangleGeometry> geometries) {
    impl_->device = rtcNewDevice(nullptr);
    if (!impl_->device)
        return "Embree: cannot create a device (error " +
               std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) + ")";
    rtcSetDeviceErrorFunction(impl_->device, &record_error, impl_);
    impl_->scene = rtcNewScene(impl_->device);
    // Robust traversal: watertight triangle tests, so rays do not leak through shared edges.
    rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
    for (size_t i = 0; i < geometries.size(); ++i) {
        const TriangleGeometry& g = geometries[i];
        RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
            geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), g.positions.size()));
        auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
            geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), g.triangles.size()));
        if (!vertices || !indices) {
            rtcReleaseGeometry(geom);
            break;
        }
        for (size_t v = 0; v < g.positions.size(); ++v) {
            vertices[3 * v] = g.positions[v].x;
            vertices[3 * v + 1] = g.positions[v].y;
            vertices[3 * v + 2] = g.positions[v].z;
        }
        std::memcpy(indices, g.triangles.data(), g.triangles.size() * sizeof(g.triangles[0]));
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(impl_->scene, geom, static_cast<unsigned>(i));
        rtcReleaseGeometry(geom);
    }
    rtcCommitScene(impl_->scene);
    std::lock_guard lock(impl_->error_mutex);
    return impl_->error;
}

bool EmbreeScene::intersect(Vec3 origin, Vec3 direction, float t_min, float t_max, RayHit* hit) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray.org_x = origin.x;
    rh.ray.org_y = origin.y;
    rh.ray.org_z = origin.z;
    rh.ray.dir_x = direction.x;
    rh.ray.dir_y = direction.y;
    rh.ray.dir_z = direction.z;
    rh.ray.tnear = t_min;
    rh.ray.tfar = t_max;
    rh.ray.mask = std::numeric_limits<unsigned>::max();
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->scene, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    *hit = {rh.ray.tfar, rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v};
    return true;
}

bool EmbreeScene::occluded(Vec3 origin, Vec3 direction, float t_min, float t_max) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray{};
    ray.org_x = origin.x;
    ray.org_y = origin.y;
    ray.org_z = origin.z;
    ray.dir_x = direction.x;
    ray.dir_y = direction.y;
    ray.dir_z = direction.z;
    ray.tnear = t_min;
    ray.tfar = t_max;
    ray.mask = std::numeric_limits<unsigned>::max();
    rtcOccluded1(impl_->scene, &context, &ray);
    return ray.tfar < 0.0f;
}

}  // namespace stratum
