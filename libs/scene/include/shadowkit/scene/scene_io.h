// Reading and writing scenes: glTF 2.0 (.gltf, .glb) and Wavefront OBJ.
#pragma once

#include "shadowkit/core/result.h"
#include "shadowkit/scene/scene.h"

#include <filesystem>

namespace shadowkit::scene {

// Which of a file's axes points up. glTF's is y (glTF 2.0 §3.4); OBJ has no convention, and
// CAD, GIS and photogrammetry exports often write z up (easting, northing, height).
enum class UpAxis { Y, Z };

struct LoadOptions {
    // Z: the file's (x, y, z) is shadowkit's (x, z, −y) — turned −90° about x, exactly (a
    // permutation with a sign), so the world is still y-up and right-handed.
    UpAxis up = UpAxis::Y;
    // A scene of 1,024 batches or more (a town, every building a mesh placed once): its opaque
    // meshes placed once, under 16,384 triangles each, merged into tiles of neighbours by
    // material — a few dozen draws a pass where there were thousands. A tile, not a building, is
    // then an instance (culled, given levels and told apart by the evaluation as one).
    bool mergeSmallMeshes = true;
    // A glTF's skins and morph weights stand as its animations pose them at this time (seconds;
    // each animation looping over its own length). They deform meshes, which stay fixed once
    // built, so they are posed at load — a still frame's --time — not played; rigid motion plays
    // at any time (scene::animate).
    double poseSeconds = 0.0;
    // A sky sphere, dome or box the file brings round the model (sky_enclosure.h) hides every sun
    // from it: left out, each named in Scene::warnings, unless this keeps it.
    bool keepSky = false;
};

// Loads triangles from glTF (a mesh referenced by several nodes becomes one batch with
// several instances) or OBJ (one mesh, one instance). The format follows the extension.
// World coordinates are the file's (turned y-up, LoadOptions::up); a file whose geometry lies
// far from its origin (survey metres) stands at Scene::wsOrigin with everything relative to it,
// read in double first. An OBJ loaded y-up that looks z-up — its net area facing +z, as a
// ground's does — says so in Scene::warnings (glTF is y-up by its specification). Errors name the file and what is
// wrong: missing, unreadable, no triangles.
core::Result<Scene> loadScene(const std::filesystem::path& file, const LoadOptions& options = {});

// Writes the scene in world coordinates (Scene::wsOrigin added in double) with per-vertex
// colours: .glb (binary glTF, COLOR_0: each batch's mesh once and a node per instance, under a
// node at wsOrigin when it is not 0) or .obj (every instance baked). The format follows the
// extension.
core::Status exportScene(const Scene& scene, const std::filesystem::path& file);
// Whether exportScene knows the format `file` names: for a command to check before it builds the
// scene, not after.
core::Status checkExportName(const std::filesystem::path& file);

} // namespace shadowkit::scene
