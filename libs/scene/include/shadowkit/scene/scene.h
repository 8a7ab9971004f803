// Scene model: meshes drawn many times through instance transforms.
//
// The GPU side draws each MeshBatch as one instanced draw call, so 10,000 trees that
// share a handful of meshes are a handful of draw calls.
#pragma once

#include "shadowkit/core/aabb.h"
#include "shadowkit/scene/deformation.h"
#include "shadowkit/scene/heightfield.h"
#include "shadowkit/scene/keyframes.h"
#include "shadowkit/scene/material.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace shadowkit::scene {

struct Vertex {
    glm::vec3 position; // object space, metres
    glm::vec3 normal;   // object space, unit
    glm::vec3 albedo;   // linear RGB in [0,1]: the material's base colour factor × vertex colour
    glm::vec2 uv{0.0f}; // the base colour texture's coordinates (glTF TEXCOORD_n of its texCoord)
};

// A level drawn as one card turned to each pass's viewer, showing the frame of an octahedral
// impostor (octahedral_impostor.h) whose direction is nearest: the level's four vertices are
// the corners osCentre + osRadius · (±1, ±1, 0), which the vertex stages turn and whose texture
// coordinates they compute (impostor.glsl). framesPerSide 0: not an impostor.
struct ImpostorCard {
    glm::vec3 osCentre{0.0f};
    float osRadius = 0.0f;
    int framesPerSide = 0;  // the frames' grid, framesPerSide² frames over the level's own texture
    int texelsPerFrame = 0; // each frame's texels a side, the outermost ring open
    bool operator==(const ImpostorCard&) const = default;
};

// Which passes draw an authored level: a pass that does not is given the next level it does.
enum class LodPasses : uint8_t { Both, Camera, Shadows };

// A coarser version of a mesh made with it (scene/mesh_lod.h uses it instead of simplifying):
// leaf cards do not simplify like closed surfaces, so a leafy tree brings fewer, larger cards.
struct AuthoredLod {
    std::vector<uint32_t> indices; // over the mesh's vertices (which hold every level's)
    float objectError = 0.0f;      // object-space metres, as scene::LodLevel::objectError
    bool keepsCoverage = false;    // as scene::LodLevel::keepsCoverage
    int32_t texture = -1;          // as scene::LodLevel::texture
    LodPasses passes = LodPasses::Both;
    // An impostor's card (shadow passes only: its card is flat through the tree's centre, and a
    // camera would see the tree's sunlit half and shadowed half as one plane).
    ImpostorCard impostor{};
};

struct Mesh {
    std::string name;
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;         // triangle list, counter-clockwise front faces; the full mesh
    core::Aabb osBounds;                   // object-space bounds, kept by computeBounds()
    int32_t material = -1;                 // index into Scene::materials; -1: opaque, vertex colours only
    std::vector<AuthoredLod> authoredLods; // coarser after coarser; empty: buildLods simplifies

    void computeBounds();
    size_t triangleCount() const { return indices.size() / 3; }
};

// One mesh and every placement of it.
struct MeshBatch {
    uint32_t mesh = 0;                      // index into Scene::meshes
    std::vector<glm::mat4> worldFromObject; // rigid transforms with uniform scale
    bool dynamic = false;                   // moves over time (animated objects)

    // Whether an instance's transform has a negative determinant: it turns the triangles'
    // winding over, so their front faces wind clockwise on screen.
    bool mirrored() const;
};

// A dynamic instance's motion (scene/animation.h): round a circle over the ground at a
// constant speed, `lift` metres above it, turning with the circle. Deterministic in time.
struct Track {
    uint32_t batch = 0, instance = 0;    // the instance it moves: batches[batch].worldFromObject[instance]
    double centreX = 0.0, centreZ = 0.0; // metres
    double radius = 10.0;                // metres, > 0
    double speed = 2.0;                  // metres per second along the circle; negative: anticlockwise seen from above
    double phase = 0.0;                  // compass angle (conventions.h) of the position at t = 0, radians
    double lift = 3.0;                   // metres above the ground
    float scale = 1.0f;                  // uniform
    // Set: the instance follows a file's keyframes (a glTF's animations), not the circle above.
    std::optional<NodeMotion> keyframed;
};

// One instance: batches[batch].worldFromObject[instance].
struct InstanceRef {
    uint32_t batch = 0, instance = 0;
};

// A perspective camera a loaded file brings (glTF 2.0 §5.12 `cameras`, placed by its node), in
// the scene's own coordinates: what `--view file` looks through (views.h, fileView).
struct FileCamera {
    std::string name;                  // the node's, else the camera's; may be empty
    core::Vec3 localEye{0.0};          // scene coordinates
    core::Vec3 localForward{0, 0, -1}; // unit: the node's −z
    core::Vec3 localUp{0, 1, 0};       // unit: the node's +y
    double fovYDegrees = 60.0;         // (0, 180)
    std::optional<double> aspect;      // width / height; unset: the picture's
    double zNear = 0.1;                // metres, > 0 (>= 0 orthographic)
    std::optional<double> zFar;        // metres, > zNear; unset: infinite (glTF's)
    // An orthographic camera's half height in metres (glTF's ymag; `aspect` is xmag / ymag and
    // zFar is set): drawn as a telephoto, a perspective camera from far behind it whose picture
    // matches the orthographic one within 1 % across the scene's depth (file_view.cpp).
    std::optional<double> orthographicHalfHeight;
};

// A punctual light a loaded file brings (KHR_lights_punctual, placed by its node), in the scene's
// own coordinates. Colour and intensity are shading, not shadow: only where it is and which way
// it shines are kept (a light of intensity 0 is left out).
struct FileLight {
    enum class Kind { Sun, Point, Spot }; // glTF's directional, point, spot
    Kind kind = Kind::Sun;
    std::string name;
    core::Vec3 localPosition{0.0};       // point and spot
    core::Vec3 localDirection{0, 0, -1}; // sun and spot: unit, the way the light travels (the node's −z)
    double coneDegrees = 90.0;           // spot: the full opening, twice glTF's outerConeAngle
    std::optional<double> range;         // metres; unset: unlimited (glTF's)
};

// Coordinates: a scene stands at `wsOrigin` in the world, and everything it holds —
// transforms, terrain, tracks, the heights groundHeightAt gives — is in its own coordinates,
// relative to that origin (world point = wsOrigin + scene point). Float keeps its precision
// near the scene wherever the scene is: 1,000 km out a float world coordinate has a 6 cm
// step, a float scene coordinate a few micrometres. Cameras, lights and set-ups are in world
// coordinates (double); the renderer and the ray tracer meet them in the scene's
// (gl::Renderer, eval::RayScene). `worldFromObject` below takes object space to the scene's.
struct Scene {
    core::Vec3 wsOrigin{0.0}; // `--world-offset`; 0: scene and world coordinates agree
    std::vector<Mesh> meshes;
    std::vector<MeshBatch> batches;
    std::optional<Heightfield> terrain; // set for procedural terrain: ground height lookups
    std::vector<Track> tracks;          // animated instances (a batch's `dynamic` instances)
    // Meshes a file's animations deform (skins, morph weights), each the mesh of a dynamic batch:
    // posed at LoadOptions::poseSeconds when loaded, and by animate() at every t after.
    std::vector<MeshDeformation> deformations;
    std::vector<Material> materials; // what Mesh::material names (material.h)
    std::vector<Texture> textures;   // what Material::baseColorTexture names
    // What a loader could not use and did without, one line each (an undecodable texture on an
    // opaque material): the caller shows them; nothing here changes a shadow.
    std::vector<std::string> warnings;
    // The file's own perspective cameras and punctual lights, in the order its node tree lists
    // them (a glTF's; an OBJ has none).
    std::vector<FileCamera> cameras;
    std::vector<FileLight> lights;

    // The material of a mesh, or nullptr for the plain opaque one.
    const Material* materialOf(const Mesh& mesh) const {
        return mesh.material >= 0 && size_t(mesh.material) < materials.size() ? &materials[size_t(mesh.material)]
                                                                              : nullptr;
    }

    // Whether a camera sees only the front of batches[batch]'s triangles, as the camera pass draws
    // them: its material is single-sided (glTF 2.0 §3.9.5: `doubleSided` false, back faces culled;
    // the plain material of a mesh without one is single-sided too) and no instance is mirrored (a
    // batch with one is drawn from both sides, as a mirror turns its winding over). Light meets
    // both sides whatever this says: a single-sided wall still stops the sun.
    bool seenFromFrontOnly(size_t batch) const;

    // Whether anything moves or changes shape over time (tracks or deformations).
    bool animated() const { return !tracks.empty() || !deformations.empty(); }
    // Whether animate() reshapes meshes[mesh] (a deformation's batch draws it).
    bool deforms(uint32_t mesh) const;

    // Puts `kept` in place of the batches, each naming its mesh by its index in `meshes` as they
    // stand (meshes appended for them first included), and drops the meshes none of them draws;
    // the rest keep the order in which `kept` first draws them. `batchAt[b]` is where batch b went,
    // UINT32_MAX where it is gone: tracks and deformations follow their batches, which must stay.
    void replaceBatches(std::vector<MeshBatch> kept, std::span<const uint32_t> batchAt);

    // Bounds of every instance (empty box for an empty scene): in the world, and in the scene's own coordinates.
    core::Aabb wsBounds() const;
    core::Aabb localBounds() const;
    // Each instance's box in the scene's coordinates, batch after batch (the global instance order).
    std::vector<core::Aabb> instanceBounds() const;
    size_t triangleCount() const; // over all instances
    size_t instanceCount() const;
    // Global instance indices count batch after batch (the order of instanceBounds(), of
    // the renderer's surface ids and of the ray tracer's instances).
    uint32_t globalIndex(InstanceRef ref) const;              // precondition: ref exists
    std::optional<InstanceRef> locate(uint32_t global) const; // nullopt beyond the last instance
    // Height of the ground under (x, z), both in the scene's coordinates: the terrain heightfield where there is one,
    // else the highest upward-facing surface of a static batch over that point, else the bottom of the scene bounds (0
    // for an empty scene).
    double groundHeightAt(double x, double z) const;
};

} // namespace shadowkit::scene
