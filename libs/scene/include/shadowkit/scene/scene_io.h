// Reading and writing scenes: glTF 2.0 (.gltf, .glb) and Wavefront OBJ.
#pragma once

#include "shadowkit/core/result.h"
#include "shadowkit/scene/scene.h"

#include <filesystem>

namespace shadowkit::scene {

// Loads triangles from glTF (a mesh referenced by several nodes becomes one batch with
// several instances) or OBJ (one mesh, one instance). The format follows the extension.
// Errors name the file and what is wrong: missing, unreadable, no triangles.
core::Result<Scene> loadScene(const std::filesystem::path& file);

// Writes every instance baked into world space, one mesh per batch, with per-vertex
// colours: .glb (binary glTF, COLOR_0) or .obj. The format follows the extension.
core::Status exportScene(const Scene& scene, const std::filesystem::path& file);

} // namespace shadowkit::scene
