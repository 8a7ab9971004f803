#include "shadowkit/scene/scene_io.h"

#include "scene_formats.h"

#include "shadowkit/core/camera.h"
#include "shadowkit/scene/foliage_levels.h"
#include "shadowkit/scene/sky_enclosure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <span>

namespace shadowkit::scene {
namespace formats {

namespace fs = std::filesystem;

std::string printable(std::string text) {
    for (char& c : text)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) c = '?';
    return text;
}

std::string lowerExtension(const fs::path& file) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

void computeNormals(Mesh& mesh) {
    for (Vertex& v : mesh.vertices) v.normal = glm::vec3(0.0f);
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        Vertex& a = mesh.vertices[mesh.indices[i]];
        Vertex& b = mesh.vertices[mesh.indices[i + 1]];
        Vertex& c = mesh.vertices[mesh.indices[i + 2]];
        const glm::vec3 n = glm::cross(b.position - a.position, c.position - a.position);
        a.normal += n;
        b.normal += n;
        c.normal += n;
    }
    for (Vertex& v : mesh.vertices) {
        const float len = glm::length(v.normal);
        v.normal = len > 0.0f ? v.normal / len : glm::vec3(0, 1, 0);
    }
}

BakedBatch fullMesh(const Mesh& mesh) {
    // Only the vertices the full mesh's triangles use, in their order: a mesh's vertex list also
    // holds its coarser levels' (AuthoredLod), which a file carrying the full mesh alone would
    // leave unreferenced — the leafy trees' card levels, 46–48 % of their vertices.
    constexpr uint32_t kUnused = ~uint32_t(0);
    std::vector<uint32_t> compactOf(mesh.vertices.size(), kUnused);
    for (uint32_t i : mesh.indices) compactOf[i] = 0;
    BakedBatch out;
    for (uint32_t v = 0; v < compactOf.size(); ++v)
        if (compactOf[v] != kUnused) {
            compactOf[v] = static_cast<uint32_t>(out.vertices.size());
            out.vertices.push_back(mesh.vertices[v]);
        }
    out.indices.reserve(mesh.indices.size());
    for (uint32_t i : mesh.indices) out.indices.push_back(compactOf[i]);
    return out;
}

BakedBatch placed(const BakedBatch& object, std::span<const glm::mat4> worldFromObject) {
    BakedBatch out;
    out.vertices.reserve(object.vertices.size() * worldFromObject.size());
    out.indices.reserve(object.indices.size() * worldFromObject.size());
    for (const glm::mat4& m : worldFromObject) {
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(m)));
        const auto base = static_cast<uint32_t>(out.vertices.size());
        for (const Vertex& in : object.vertices)
            out.vertices.push_back({glm::vec3(m * glm::vec4(in.position, 1.0f)),
                                    glm::normalize(normalMatrix * in.normal), in.albedo, in.uv});
        for (uint32_t i : object.indices) out.indices.push_back(base + i);
    }
    return out;
}

// Whether any placed triangle has an area: one whose every triangle is a point or a line (the
// glTF Validator's files whose accessors have no buffer view, all zeros; nodes scaled to 0)
// casts and receives nothing, and a view framing it would frame a point.
bool anyPlacedArea(const Scene& scene) {
    for (const MeshBatch& batch : scene.batches) {
        const bool placedWithSize = std::any_of(batch.worldFromObject.begin(), batch.worldFromObject.end(),
                                                [](const glm::mat4& m) { return glm::length(glm::vec3(m[0])) > 0.0f; });
        if (!placedWithSize) continue;
        const Mesh& mesh = scene.meshes[batch.mesh];
        for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
            const glm::dvec3 a(mesh.vertices[mesh.indices[i]].position);
            const glm::dvec3 b(mesh.vertices[mesh.indices[i + 1]].position);
            const glm::dvec3 c(mesh.vertices[mesh.indices[i + 2]].position);
            if (glm::length(glm::cross(b - a, c - a)) > 0.0) return true;
        }
    }
    return false;
}

} // namespace formats

namespace fs = std::filesystem;
using namespace formats;

core::Result<Scene> loadScene(const fs::path& file, const LoadOptions& options) {
    std::error_code ec;
    if (!fs::exists(file, ec)) return core::makeError(file.string() + ": scene file does not exist");
    if (fs::is_directory(file, ec)) return core::makeError(file.string() + ": is a directory, not a scene file");
    if (!std::isfinite(options.poseSeconds))
        return core::makeError(file.string() + ": the time to pose its animations at is not finite");
    const std::string ext = lowerExtension(file);
    if (ext != ".gltf" && ext != ".glb" && ext != ".obj")
        return core::makeError(file.string() + ": unknown scene format (use .gltf, .glb or .obj)");
    core::Result<Scene> scene = ext == ".obj" ? loadObj(file) : loadGltf(file, options.poseSeconds);
    if (scene && options.up == UpAxis::Z) turnZUpToYUp(*scene);
    // glTF is y-up by its specification, and its sample cards face +z: only an OBJ, which says
    // nothing, is suspected of z-up.
    if (scene && options.up == UpAxis::Y && ext == ".obj")
        if (auto why = zUpWarning(*scene)) scene->warnings.push_back(file.string() + ": " + *why);
    // Finite positions placed (or scaled by a node) past the world's end: a view framing them
    // would put its eye there, and Embree aborts on such a ray origin.
    if (scene) {
        const core::Aabb bounds = scene->wsBounds();
        const double reach = std::max(glm::length(bounds.min), glm::length(bounds.max));
        if (!(reach <= core::kMaxWorldMetres)) {
            char metres[32];
            std::snprintf(metres, sizeof metres, "%.3g", reach);
            return core::makeError(file.string() + ": its geometry reaches " + metres +
                                   " m from the origin; at most 1e13 m");
        }
        if (!anyPlacedArea(*scene))
            return core::makeError(file.string() + ": every triangle it places has no area (a point or a line, or " +
                                   "scaled to nothing): nothing to cast or receive a shadow");
    }
    if (scene && !options.keepSky)
        for (const SkyEnclosure& sky : leaveOutSkyEnclosures(*scene)) {
            char metres[96];
            std::snprintf(metres, sizeof metres, "%.3g m across against the rest's %.3g m", sky.skyMetres,
                          sky.restMetres);
            const std::string mesh = sky.meshName.empty() ? "a mesh" : "mesh '" + printable(sky.meshName) + "'";
            scene->warnings.push_back(file.string() + ": " + mesh + " encloses the rest of the scene (" + metres +
                                      ") and hides the whole sky from it, as a sky sphere or box does: left out, or " +
                                      "no sun would reach the model (LoadOptions::keepSky, --keep-sky, keeps it)");
        }
    if (scene && options.mergeSmallMeshes) mergeSmallMeshes(*scene);
    // Foliage that brings no levels of its own gets billboard clouds, as the leafy forest's trees.
    if (scene) addFoliageClouds(*scene);
    return scene;
}

core::Status checkExportName(const fs::path& file) {
    if (const std::string ext = lowerExtension(file); ext != ".glb" && ext != ".obj")
        return core::makeError(file.string() + ": unknown export format (use .glb or .obj)");
    return core::Ok{};
}

core::Status exportScene(const Scene& scene, const fs::path& file) {
    if (auto s = checkExportName(file); !s) return s;
    return lowerExtension(file) == ".glb" ? exportGlb(scene, file) : exportObj(scene, file);
}

} // namespace shadowkit::scene
