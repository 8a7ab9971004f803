// Reading and writing scenes: glTF 2.0 (.gltf, .glb) and Wavefront OBJ.
#pragma once

#include "shadowkit/core/result.h"
#include "shadowkit/scene/scene.h"

#include <filesystem>

namespace shadowkit::scene {

// Loads triangles from glTF (a mesh referenced by several nodes becomes one batch with
// several instances) or OBJ (one mesh, one instance). The format follows the extension.
// World coordinates are the file's; a file whose geometry lies far from its origin (survey
// metres) stands at Scene::wsOrigin with everything relative to it, read in double first.
// Errors name the file and what is wrong: missing, unreadable, no triangles.
core::Result<Scene> loadScene(const std::filesystem::path& file);

// Writes the scene in world coordinates (Scene::wsOrigin added in double) with per-vertex
// colours: .glb (binary glTF, COLOR_0: each batch's mesh once and a node per instance, under a
// node at wsOrigin when it is not 0) or .obj (every instance baked). The format follows the
// extension.
core::Status exportScene(const Scene& scene, const std::filesystem::path& file);

} // namespace shadowkit::scene
