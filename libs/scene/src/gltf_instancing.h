// EXT_mesh_gpu_instancing (gltf_instancing.cpp). Internal to libs/scene.
#pragma once

#include "shadowkit/core/result.h"

#include <tiny_gltf.h>

#include <glm/glm.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace shadowkit::scene::formats {

inline constexpr const char* kInstancing = "EXT_mesh_gpu_instancing";
/// The most instances a file may place through the extension, in all.
inline constexpr size_t kMaxInstances = size_t(1) << 24;

/// EXT_mesh_gpu_instancing (gltfpack -mi): a node that places its mesh once per element of its
/// TRANSLATION, ROTATION and SCALE accessors (each optional, all of one count), at
/// nodeWorld × T × R × S (the extension's order, as for a node's own TRS). Quaternions are
/// normalised (normalized 16-bit ones are not quite unit; a zero one is an error). A file may not
/// place more than kMaxInstances instances in all: a sparse accessor of zeros costs no bytes, and
/// many nodes may share it.
/// Returns the node's placements in the world (`world` alone without the extension); `placed`
/// counts the instances placed so far in the file.
core::Result<std::vector<glm::dmat4>> instanceTransforms(const tinygltf::Model& model, const tinygltf::Node& node,
                                                         const glm::dmat4& world, const std::string& where,
                                                         size_t& placed);

} // namespace shadowkit::scene::formats
