// Embree 3 scene construction with two-level instancing.
#include "shadowkit/eval/ray_scene.h"

#include <embree3/rtcore.h>

#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace shadowkit::eval {

struct RayScene::Impl {
    RTCDevice device = nullptr;
    RTCScene top = nullptr;
    std::vector<RTCScene> meshes;
    std::vector<glm::mat3> normalFromObject; // per global instance: inverse transpose of the linear part
    std::string lastError;

    ~Impl() {
        if (top) rtcReleaseScene(top);
        for (RTCScene s : meshes)
            if (s) rtcReleaseScene(s);
        if (device) rtcReleaseDevice(device);
    }
};

namespace {

void onEmbreeError(void* user, RTCError code, const char* message) {
    *static_cast<std::string*>(user) =
        "Embree error " + std::to_string(static_cast<int>(code)) + ": " + (message ? message : "?");
}

} // namespace

RayScene::~RayScene() = default;

core::Result<std::unique_ptr<RayScene>> RayScene::build(const scene::Scene& scene) {
    auto rs = std::unique_ptr<RayScene>(new RayScene);
    rs->m_impl = std::make_unique<Impl>();
    Impl& impl = *rs->m_impl;
    impl.device = rtcNewDevice(nullptr);
    if (!impl.device) return core::makeError("ray tracer: Embree could not create a device (unsupported CPU?)");
    rtcSetDeviceErrorFunction(impl.device, onEmbreeError, &impl.lastError);

    for (const scene::Mesh& mesh : scene.meshes) {
        RTCScene meshScene = rtcNewScene(impl.device);
        impl.meshes.push_back(meshScene);
        if (mesh.indices.empty()) {
            rtcCommitScene(meshScene);
            continue;
        }
        RTCGeometry geom = rtcNewGeometry(impl.device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                     3 * sizeof(float), mesh.vertices.size()));
        auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                       3 * sizeof(uint32_t), mesh.indices.size() / 3));
        if (!vertices || !indices) {
            rtcReleaseGeometry(geom);
            return core::makeError("ray tracer: " + (impl.lastError.empty() ? "out of memory" : impl.lastError));
        }
        for (size_t i = 0; i < mesh.vertices.size(); ++i) std::memcpy(vertices + 3 * i, &mesh.vertices[i].position, 12);
        std::memcpy(indices, mesh.indices.data(), mesh.indices.size() / 3 * 3 * sizeof(uint32_t));
        rtcCommitGeometry(geom);
        rtcAttachGeometry(meshScene, geom);
        rtcReleaseGeometry(geom);
        rtcCommitScene(meshScene);
    }

    impl.top = rtcNewScene(impl.device);
    unsigned instance = 0;
    for (const scene::MeshBatch& batch : scene.batches) {
        for (const glm::mat4& worldFromObject : batch.worldFromObject) {
            RTCGeometry geom = rtcNewGeometry(impl.device, RTC_GEOMETRY_TYPE_INSTANCE);
            rtcSetGeometryInstancedScene(geom, impl.meshes[batch.mesh]);
            rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, glm::value_ptr(worldFromObject));
            rtcCommitGeometry(geom);
            // The geometry ID is the global instance index: the surface identity the
            // rasterizer writes too (gl::GpuScene).
            rtcAttachGeometryByID(impl.top, geom, instance++);
            rtcReleaseGeometry(geom);
            impl.normalFromObject.push_back(glm::transpose(glm::inverse(glm::mat3(worldFromObject))));
        }
    }
    rtcCommitScene(impl.top);
    if (!impl.lastError.empty()) return core::makeError("ray tracer: " + impl.lastError);
    rs->m_diagonal = scene.wsBounds().diagonal();
    rs->m_wsOrigin = scene.wsOrigin;
    return rs;
}

core::Status RayScene::moveInstances(const scene::Scene& scene, std::span<const uint32_t> moved) {
    if (scene.instanceCount() != m_impl->normalFromObject.size())
        return core::makeError("ray tracer: moveInstances() needs the scene it was built from");
    for (const uint32_t global : moved)
        if (!scene.locate(global))
            return core::makeError("ray tracer: moved instance " + std::to_string(global) + " is out of range");
    for (const uint32_t global : moved) {
        const scene::InstanceRef ref = *scene.locate(global);
        const glm::mat4& worldFromObject = scene.batches[ref.batch].worldFromObject[ref.instance];
        RTCGeometry geom = rtcGetGeometry(m_impl->top, global);
        rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, glm::value_ptr(worldFromObject));
        rtcCommitGeometry(geom);
        m_impl->normalFromObject[global] = glm::transpose(glm::inverse(glm::mat3(worldFromObject)));
    }
    if (!moved.empty()) rtcCommitScene(m_impl->top);
    if (!m_impl->lastError.empty()) return core::makeError("ray tracer: " + m_impl->lastError);
    m_diagonal = scene.wsBounds().diagonal();
    return core::Ok{};
}

bool RayScene::intersect(const core::Vec3& origin, const core::Vec3& direction, double tNear, double tFar,
                         RayHit& hit) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    const core::Vec3 local = origin - m_wsOrigin;
    rh.ray.org_x = static_cast<float>(local.x);
    rh.ray.org_y = static_cast<float>(local.y);
    rh.ray.org_z = static_cast<float>(local.z);
    rh.ray.dir_x = static_cast<float>(direction.x);
    rh.ray.dir_y = static_cast<float>(direction.y);
    rh.ray.dir_z = static_cast<float>(direction.z);
    rh.ray.tnear = static_cast<float>(tNear);
    rh.ray.tfar = static_cast<float>(std::min(tFar, double(std::numeric_limits<float>::max())));
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(m_impl->top, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    hit.t = rh.ray.tfar;
    hit.instance = rh.hit.instID[0];
    // Embree reports instanced hits' Ng in object space: bring it to world space.
    const glm::vec3 osNg(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
    core::Vec3 n = glm::normalize(core::Vec3(m_impl->normalFromObject[hit.instance] * osNg));
    if (glm::dot(n, direction) > 0.0) n = -n;
    hit.wsGeometricNormal = n;
    return true;
}

bool RayScene::occluded(const core::Vec3& origin, const core::Vec3& direction, double tNear, double tFar) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray{};
    const core::Vec3 local = origin - m_wsOrigin;
    ray.org_x = static_cast<float>(local.x);
    ray.org_y = static_cast<float>(local.y);
    ray.org_z = static_cast<float>(local.z);
    ray.dir_x = static_cast<float>(direction.x);
    ray.dir_y = static_cast<float>(direction.y);
    ray.dir_z = static_cast<float>(direction.z);
    ray.tnear = static_cast<float>(tNear);
    ray.tfar = static_cast<float>(std::min(tFar, double(std::numeric_limits<float>::max())));
    ray.mask = ~0u;
    rtcOccluded1(m_impl->top, &context, &ray);
    return ray.tfar < 0.0f; // Embree sets tfar to -inf on a hit
}

} // namespace shadowkit::eval
