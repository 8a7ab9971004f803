// A glTF file's own cameras and punctual lights (gltf_viewpoints.cpp). Internal to libs/scene.
#pragma once

#include "shadowkit/scene/scene.h"

#include <tiny_gltf.h>

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace shadowkit::scene::formats {

/// Adds the camera and the KHR_lights_punctual light of node `nodeIndex`, placed by
/// `fileFromNode` (its global transform, the file's coordinates in double), to `scene.cameras`
/// and `scene.lights`. Shadows need none of them, so a camera or light that cannot be used —
/// orthographic, a bad field, a degenerate placement — is one line in `scene.warnings`, never an
/// error. Positions stay in the file's coordinates until placeViewpoints. A hidden node
/// (`visible` false: KHR_node_visibility, which hides lights but not cameras) adds its camera only.
void readNodeViewpoints(const tinygltf::Model& model, int nodeIndex, const glm::dmat4& fileFromNode,
                        const std::string& file, bool visible, Scene& scene);

/// Moves the cameras' and lights' positions from the file's coordinates to the scene's, once
/// placeNearOrigin has set scene.wsOrigin.
void placeViewpoints(Scene& scene);

/// Writes the scene's cameras and lights into `model` (its `cameras`, its KHR_lights_punctual
/// `lights`), each under a node of its own placed in the scene's coordinates; returns those nodes
/// for the caller to hang where the batches hang (exportGlb: under the scene's origin).
std::vector<int> writeViewpoints(const Scene& scene, tinygltf::Model& model);

} // namespace shadowkit::scene::formats
