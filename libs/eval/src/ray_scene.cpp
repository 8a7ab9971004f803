// Embree 3 scene construction with two-level instancing, and alpha-tested materials as
// Embree filter functions: a hit on a masked surface counts only where its alpha covers it.
// Camera rays pass the back faces the camera pass culls (Faces::AsTheCameraSees) through a
// second, per-query filter (Embree's context filter), which light's queries never set.
#include "shadowkit/eval/ray_scene.h"

#include "shadowkit/scene/alpha_mask.h"

#include <embree3/rtcore.h>

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace shadowkit::eval {

namespace {

// What the filter of an alpha-tested mesh needs, owned here (a RayScene may outlive the
// scene it was built from): each vertex's uv, the triangles, and the material's alpha test.
struct AlphaSurface {
    std::vector<glm::vec2> uvs;
    std::vector<uint32_t> indices;
    // glTF 2.0 §3.9.4 at level 0 of the texture, sampled as GL samples it up close
    // (scene::sampleLevel0). The rasteriser's distant mip levels keep coverage
    // (scene/texture_mips.h); the truth is the full-resolution card.
    scene::AlphaMask mask;

    // At the hit's barycentrics (u, v) on `triangle`.
    bool covers(uint32_t triangle, float u, float v) const {
        const size_t i = size_t(triangle) * 3;
        if (i + 2 >= indices.size()) return true;
        return mask.covers((1.0f - u - v) * uvs[indices[i]] + u * uvs[indices[i + 1]] + v * uvs[indices[i + 2]]);
    }
};

// Embree's intersection and occlusion filter (RTCFilterFunctionN): rejects the hits that
// fall where the material's alpha is below its cutoff, so the ray goes on through the hole.
void alphaFilter(const RTCFilterFunctionNArguments* args) {
    const auto& surface = *static_cast<const AlphaSurface*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0) continue;
        const uint32_t triangle = RTCHitN_primID(args->hit, args->N, i);
        if (!surface.covers(triangle, RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i)))
            args->valid[i] = 0;
    }
}

// A query's context with what its context filter reads: which instances a camera sees from the
// front only (one byte per global instance). Embree hands the filter the context it was given,
// the RTCIntersectContext first.
struct CameraContext {
    RTCIntersectContext context;
    const uint8_t* seenFromFrontOnly = nullptr;
};

// The context filter of camera rays: rejects a hit on the back of a triangle of an instance seen
// from the front only, so the ray goes on to what the camera pass shows behind it. For an
// instanced geometry Embree gives ray and hit in object space, where a counter-clockwise
// triangle's Ng points out of its front face (Embree's convention, glTF's and GL's winding):
// a ray meets the back when it runs along Ng. A batch seen from the front only has no mirrored
// instance, so object-space winding is the winding on screen.
void backFaceFilter(const RTCFilterFunctionNArguments* args) {
    const auto& context = *reinterpret_cast<const CameraContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0) continue;
        const unsigned instance = RTCHitN_instID(args->hit, args->N, i, 0);
        if (instance == RTC_INVALID_GEOMETRY_ID || context.seenFromFrontOnly[instance] == 0) continue;
        const float along = RTCHitN_Ng_x(args->hit, args->N, i) * RTCRayN_dir_x(args->ray, args->N, i) +
                            RTCHitN_Ng_y(args->hit, args->N, i) * RTCRayN_dir_y(args->ray, args->N, i) +
                            RTCHitN_Ng_z(args->hit, args->N, i) * RTCRayN_dir_z(args->ray, args->N, i);
        if (along > 0.0f) args->valid[i] = 0;
    }
}

} // namespace

struct RayScene::Impl {
    RTCDevice device = nullptr;
    RTCScene top = nullptr;
    std::vector<RTCScene> meshes;
    std::vector<float*> meshVertices; // per mesh, Embree's buffer of its positions (null: no triangles)
    std::vector<std::unique_ptr<AlphaSurface>> alphaSurfaces; // user data of the filters: fixed addresses
    std::vector<glm::mat3> normalFromObject; // per global instance: inverse transpose of the linear part
    std::vector<uint8_t> seenFromFrontOnly;  // per global instance: Scene::seenFromFrontOnly of its batch
    std::string lastError;

    // A context for queries meeting `faces`: coherent rays or not; the camera's back-face filter.
    CameraContext contextFor(Faces faces, bool coherent) const {
        CameraContext c;
        rtcInitIntersectContext(&c.context);
        if (coherent) c.context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        if (faces == Faces::AsTheCameraSees) {
            c.context.filter = backFaceFilter;
            c.seenFromFrontOnly = seenFromFrontOnly.data();
        }
        return c;
    }

    ~Impl() {
        if (top) rtcReleaseScene(top);
        for (RTCScene s : meshes)
            if (s) rtcReleaseScene(s);
        if (device) rtcReleaseDevice(device);
    }
};

namespace {

// A ray's single-precision form, relative to the scene's origin: the same conversions for one
// ray and for a packet's lane, so both give the same answer.
struct FloatRay {
    float org[3], dir[3], tnear, tfar;
};
FloatRay toFloat(const core::Vec3& wsOrigin, const core::Vec3& origin, const core::Vec3& direction, double tNear,
                 double tFar) {
    const core::Vec3 local = origin - wsOrigin;
    return {{static_cast<float>(local.x), static_cast<float>(local.y), static_cast<float>(local.z)},
            {static_cast<float>(direction.x), static_cast<float>(direction.y), static_cast<float>(direction.z)},
            static_cast<float>(tNear),
            static_cast<float>(std::min(tFar, double(std::numeric_limits<float>::max())))};
}

constexpr int kPacket = 8; // rtcIntersect8 / rtcOccluded8

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

    for (uint32_t m = 0; m < scene.meshes.size(); ++m) {
        const scene::Mesh& mesh = scene.meshes[m];
        RTCScene meshScene = rtcNewScene(impl.device);
        impl.meshes.push_back(meshScene);
        impl.meshVertices.push_back(nullptr);
        // Spatial splits (Embree's high-quality build): a tree's leaf cards are long thin
        // quads that overlap, whose boxes an object split cannot separate. Built once per mesh,
        // shared by every instance; on the leafy forest they cut the soft truth's time by a
        // tenth for no measurable build time. A mesh the scene deforms is built again in every
        // frame that poses it (moveInstances): Embree's dynamic scene, its BVH refitted.
        const bool deformed = scene.deforms(m);
        rtcSetSceneBuildQuality(meshScene, deformed ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_HIGH);
        // Every scene a camera ray enters lets the query's own filter see its hits (Embree asks
        // for the flag on each instanced scene too).
        rtcSetSceneFlags(meshScene, RTCSceneFlags(RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION |
                                                  (deformed ? RTC_SCENE_FLAG_DYNAMIC : RTC_SCENE_FLAG_NONE)));
        // A mesh whose material the alpha test cuts away whole (clear glass) stops no ray:
        // left out, rather than every hit on it rejected by the alpha filter (scene::coversNothing,
        // the rule the renderer keeps it out of every pass by).
        const scene::Material* material = scene.materialOf(mesh);
        if (mesh.indices.empty() || (material && scene::coversNothing(*material, scene.textures))) {
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
        impl.meshVertices.back() = vertices;
        std::memcpy(indices, mesh.indices.data(), mesh.indices.size() / 3 * 3 * sizeof(uint32_t));
        if (deformed) rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_REFIT);
        if (const scene::Material* material = scene.materialOf(mesh); material && material->alphaTested()) {
            const int32_t t = material->baseColorTexture;
            auto surface = std::make_unique<AlphaSurface>(AlphaSurface{
                .uvs = {},
                .indices = mesh.indices,
                .mask = scene::AlphaMask(t >= 0 && size_t(t) < scene.textures.size() ? scene.textures[size_t(t)]
                                                                                     : scene::Texture{},
                                         material->baseColorFactor.a, material->alphaCutoff)});
            for (const scene::Vertex& v : mesh.vertices) surface->uvs.push_back(v.uv);
            rtcSetGeometryUserData(geom, surface.get());
            rtcSetGeometryIntersectFilterFunction(geom, alphaFilter);
            rtcSetGeometryOccludedFilterFunction(geom, alphaFilter);
            impl.alphaSurfaces.push_back(std::move(surface));
        }
        rtcCommitGeometry(geom);
        rtcAttachGeometry(meshScene, geom);
        rtcReleaseGeometry(geom);
        rtcCommitScene(meshScene);
    }

    impl.top = rtcNewScene(impl.device);
    rtcSetSceneFlags(impl.top, RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
    unsigned instance = 0;
    for (size_t b = 0; b < scene.batches.size(); ++b) {
        const scene::MeshBatch& batch = scene.batches[b];
        const bool frontOnly = scene.seenFromFrontOnly(b);
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
            impl.seenFromFrontOnly.push_back(frontOnly ? 1 : 0);
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
    // A deformed mesh's new shape first: its scene committed before the instances above it.
    std::vector<bool> batchMoved(scene.batches.size(), false);
    for (const uint32_t global : moved) batchMoved[scene.locate(global)->batch] = true;
    for (const scene::MeshDeformation& deformation : scene.deformations) {
        if (deformation.batch >= batchMoved.size() || !batchMoved[deformation.batch]) continue;
        const uint32_t m = scene.batches[deformation.batch].mesh;
        const scene::Mesh& mesh = scene.meshes[m];
        float* vertices = m_impl->meshVertices[m];
        if (!vertices) continue;
        for (size_t i = 0; i < mesh.vertices.size(); ++i) std::memcpy(vertices + 3 * i, &mesh.vertices[i].position, 12);
        RTCGeometry geom = rtcGetGeometry(m_impl->meshes[m], 0);
        rtcUpdateGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0);
        rtcCommitGeometry(geom);
        rtcCommitScene(m_impl->meshes[m]);
    }
    for (const uint32_t global : moved) {
        const scene::InstanceRef ref = *scene.locate(global);
        const glm::mat4& worldFromObject = scene.batches[ref.batch].worldFromObject[ref.instance];
        RTCGeometry geom = rtcGetGeometry(m_impl->top, global);
        rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR, glm::value_ptr(worldFromObject));
        rtcCommitGeometry(geom);
        m_impl->normalFromObject[global] = glm::transpose(glm::inverse(glm::mat3(worldFromObject)));
    }
    // A batch turns mirrored, or back, as a whole (Scene::seenFromFrontOnly).
    for (size_t b = 0; b < scene.batches.size(); ++b) {
        if (!batchMoved[b]) continue;
        const uint8_t frontOnly = scene.seenFromFrontOnly(b) ? 1 : 0;
        const uint32_t first = scene.globalIndex({uint32_t(b), 0});
        std::fill_n(m_impl->seenFromFrontOnly.begin() + first, scene.batches[b].worldFromObject.size(), frontOnly);
    }
    if (!moved.empty()) rtcCommitScene(m_impl->top);
    if (!m_impl->lastError.empty()) return core::makeError("ray tracer: " + m_impl->lastError);
    m_diagonal = scene.wsBounds().diagonal();
    return core::Ok{};
}

namespace {

// Embree reports instanced hits' Ng in object space: to world space, facing against the ray.
RayHit worldHit(const std::vector<glm::mat3>& normalFromObject, float t, unsigned instance, const glm::vec3& osNg,
                const core::Vec3& direction) {
    RayHit hit;
    hit.t = t;
    hit.instance = instance;
    core::Vec3 n = glm::normalize(core::Vec3(normalFromObject[instance] * osNg));
    if (glm::dot(n, direction) > 0.0) n = -n;
    hit.wsGeometricNormal = n;
    return hit;
}

} // namespace

bool RayScene::intersect(const core::Vec3& origin, const core::Vec3& direction, double tNear, double tFar, RayHit& hit,
                         Faces faces) const {
    CameraContext context = m_impl->contextFor(faces, false);
    RTCRayHit rh{};
    const FloatRay f = toFloat(m_wsOrigin, origin, direction, tNear, tFar);
    rh.ray.org_x = f.org[0], rh.ray.org_y = f.org[1], rh.ray.org_z = f.org[2];
    rh.ray.dir_x = f.dir[0], rh.ray.dir_y = f.dir[1], rh.ray.dir_z = f.dir[2];
    rh.ray.tnear = f.tnear;
    rh.ray.tfar = f.tfar;
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(m_impl->top, &context.context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    hit = worldHit(m_impl->normalFromObject, rh.ray.tfar, rh.hit.instID[0],
                   glm::vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z), direction);
    return true;
}

bool RayScene::occluded(const core::Vec3& origin, const core::Vec3& direction, double tNear, double tFar) const {
    CameraContext context = m_impl->contextFor(Faces::Both, false);
    RTCRay ray{};
    const FloatRay f = toFloat(m_wsOrigin, origin, direction, tNear, tFar);
    ray.org_x = f.org[0], ray.org_y = f.org[1], ray.org_z = f.org[2];
    ray.dir_x = f.dir[0], ray.dir_y = f.dir[1], ray.dir_z = f.dir[2];
    ray.tnear = f.tnear;
    ray.tfar = f.tfar;
    ray.mask = ~0u;
    rtcOccluded1(m_impl->top, &context.context, &ray);
    return ray.tfar < 0.0f; // Embree sets tfar to -inf on a hit
}

namespace {

// Lanes [first, first + count) of `rays` into a packet's ray part; the rest invalid.
void fillPacket(RTCRay8& packet, int (&valid)[kPacket], const core::Vec3& wsOrigin, std::span<const Ray> rays,
                size_t first, size_t count) {
    for (size_t lane = 0; lane < size_t(kPacket); ++lane) {
        valid[lane] = lane < count ? -1 : 0;
        if (lane >= count) continue;
        const Ray& r = rays[first + lane];
        const FloatRay f = toFloat(wsOrigin, r.origin, r.direction, r.tNear, r.tFar);
        packet.org_x[lane] = f.org[0], packet.org_y[lane] = f.org[1], packet.org_z[lane] = f.org[2];
        packet.dir_x[lane] = f.dir[0], packet.dir_y[lane] = f.dir[1], packet.dir_z[lane] = f.dir[2];
        packet.tnear[lane] = f.tnear;
        packet.tfar[lane] = f.tfar;
        packet.mask[lane] = ~0u;
        packet.time[lane] = 0.0f;
        packet.flags[lane] = 0;
    }
}

// Calls trace(first, count) for each packet of `rays`.
template <class Trace>
void forEachPacket(size_t rays, Trace trace) {
    for (size_t first = 0; first < rays; first += kPacket) trace(first, std::min(rays - first, size_t(kPacket)));
}

} // namespace

void RayScene::intersect(std::span<const Ray> rays, std::span<uint8_t> hit, std::span<RayHit> hits, Faces faces) const {
    CameraContext context = m_impl->contextFor(faces, true);
    forEachPacket(rays.size(), [&](size_t first, size_t count) {
        RTCRayHit8 packet{};
        alignas(32) int valid[kPacket]; // Embree loads the mask with aligned vector loads
        fillPacket(packet.ray, valid, m_wsOrigin, rays, first, count);
        for (int lane = 0; lane < kPacket; ++lane) {
            packet.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
            packet.hit.instID[0][lane] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect8(valid, m_impl->top, &context.context, &packet);
        for (size_t lane = 0; lane < count; ++lane) {
            hit[first + lane] = packet.hit.geomID[lane] != RTC_INVALID_GEOMETRY_ID;
            if (!hit[first + lane]) continue;
            hits[first + lane] =
                worldHit(m_impl->normalFromObject, packet.ray.tfar[lane], packet.hit.instID[0][lane],
                         glm::vec3(packet.hit.Ng_x[lane], packet.hit.Ng_y[lane], packet.hit.Ng_z[lane]),
                         rays[first + lane].direction);
        }
    });
}

void RayScene::occluded(std::span<const Ray> rays, std::span<uint8_t> occluded) const {
    CameraContext context = m_impl->contextFor(Faces::Both, true);
    forEachPacket(rays.size(), [&](size_t first, size_t count) {
        RTCRay8 packet{};
        alignas(32) int valid[kPacket]; // Embree loads the mask with aligned vector loads
        fillPacket(packet, valid, m_wsOrigin, rays, first, count);
        rtcOccluded8(valid, m_impl->top, &context.context, &packet);
        for (size_t lane = 0; lane < count; ++lane) occluded[first + lane] = packet.tfar[lane] < 0.0f;
    });
}

} // namespace shadowkit::eval
