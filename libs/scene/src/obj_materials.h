// The materials of a Wavefront OBJ that change a shadow: those whose `map_d` (the MTL's
// dissolve texture) cuts their faces, as an alpha-cut leaf card's does, and those whose dissolve
// (`d`, or `Tr`) lets most of the light through, as glass does (obj_materials.cpp). Internal to
// libs/scene.
#pragma once

#include "shadowkit/scene/scene.h"

#include <tiny_obj_loader.h>

#include <filesystem>
#include <span>
#include <vector>

namespace shadowkit::scene::formats {

/// For each of the file's materials, the Scene::materials entry its faces wear (appended to
/// `scene`, with their textures) or −1: opaque, its diffuse colour in the vertices as before.
/// `facesWearing[m]`: how many of the file's faces wear material m (whether every face would
/// dissolve). A material whose map_d cannot be read is opaque, with one line in
/// scene.warnings; nothing here refuses a file.
std::vector<int32_t> readObjMaterials(const std::vector<tinyobj::material_t>& materials,
                                      std::span<const size_t> facesWearing, const std::filesystem::path& file,
                                      Scene& scene);

/// A texture coordinate as the OBJ writes it (v up, the image's last row at v = 0), with the
/// material's map_d options (-o, -s) applied, in the image's orientation the renderer and the
/// ray tracer sample (material.h: glTF's, v down from the first row).
glm::vec2 objTextureUv(const tinyobj::texture_option_t& options, glm::vec2 vt);

} // namespace shadowkit::scene::formats
