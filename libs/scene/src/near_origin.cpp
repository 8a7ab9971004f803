// A loaded scene kept where float keeps its precision.
//
// Survey, GIS and photogrammetry exports write their metres as they are: UTM eastings near
// 5e5 m, northings up to 1e7 m, national grids alike. A float there steps by 3 cm to 1 m, and
// every float the pipeline makes from such a number — a vertex, an instance matrix, a clip-space
// product on the GPU, a hit point in Embree — errs by that much: a 20 m model 1e6 m out was 48 %
// wrong on `paper` with its raster and ray disagreeing on half its pixels, 1e7 m out 15–40 % on
// every view (reliability.md, "Large worlds"). So a loader carries the file's placements in
// double to the end and stands the scene where it is (Scene::wsOrigin) with everything in it
// relative to there, as a floating origin does; a mesh whose own vertices lie far from its
// origin is moved to it first, the move folded into its placements. Double keeps the file's
// numbers: a float32 vertex minus a whole number of metres is exact in double, and lands in
// float near zero with float's full precision.
#include "scene_formats.h"

#include <glm/gtc/matrix_transform.hpp>

namespace shadowkit::scene::formats {

glm::dvec3 anchorOf(const core::Aabb& bounds) {
    if (bounds.isEmpty()) return glm::dvec3(0.0);
    const glm::dvec3 centre = bounds.center();
    // Within 16 of its own sizes from the origin a float's step is under 2e-6 of the model:
    // a hundredth of a texel of a map 8192 texels across it. Farther, it moves.
    if (!(glm::length(centre) > kFarFromOriginSizes * bounds.diagonal())) return glm::dvec3(0.0);
    return glm::round(centre);
}

void placeNearOrigin(Scene& scene, const std::vector<std::vector<glm::dmat4>>& fileFromObject) {
    std::vector<glm::dvec3> meshAnchor(scene.meshes.size(), glm::dvec3(0.0));
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        Mesh& mesh = scene.meshes[m];
        meshAnchor[m] = anchorOf(mesh.osBounds);
        if (meshAnchor[m] == glm::dvec3(0.0)) continue;
        for (Vertex& v : mesh.vertices) v.position = glm::vec3(glm::dvec3(v.position) - meshAnchor[m]);
        mesh.computeBounds();
    }
    // The placements with the meshes' moves folded in, and the bounds they give, in the file's
    // coordinates (double).
    std::vector<std::vector<glm::dmat4>> placements(scene.batches.size());
    core::Aabb fileBounds;
    for (size_t b = 0; b < scene.batches.size(); ++b) {
        const uint32_t m = scene.batches[b].mesh;
        const glm::dmat4 moved = glm::translate(glm::dmat4(1.0), meshAnchor[m]);
        for (const glm::dmat4& fromObject : fileFromObject[b]) {
            placements[b].push_back(fromObject * moved);
            fileBounds.extend(core::transformBounds(placements[b].back(), scene.meshes[m].osBounds));
        }
    }
    scene.wsOrigin = anchorOf(fileBounds);
    const glm::dmat4 sceneFromFile = glm::translate(glm::dmat4(1.0), -scene.wsOrigin);
    for (size_t b = 0; b < scene.batches.size(); ++b) {
        std::vector<glm::mat4>& out = scene.batches[b].worldFromObject;
        out.clear();
        out.reserve(placements[b].size());
        for (const glm::dmat4& fromObject : placements[b]) out.emplace_back(sceneFromFile * fromObject);
    }
    // A deformed mesh is posed where its vertices were: moved as they were.
    for (MeshDeformation& deformation : scene.deformations)
        deformation.meshFromPosed =
            glm::translate(glm::dmat4(1.0), -meshAnchor[scene.batches[deformation.batch].mesh]) *
            deformation.meshFromPosed;
    // A keyframed instance is placed by its motion: the same origin before it, the same move of
    // its mesh after it.
    for (Track& track : scene.tracks)
        if (track.keyframed) {
            const uint32_t m = scene.batches[track.batch].mesh;
            track.keyframed->sceneFromRoot = sceneFromFile * track.keyframed->sceneFromRoot;
            track.keyframed->nodeFromObject *= glm::translate(glm::dmat4(1.0), meshAnchor[m]);
        }
}

} // namespace shadowkit::scene::formats
