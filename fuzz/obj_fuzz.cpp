// OBJ through the project's reader (tinyobjloader and libs/scene/src/obj_read.cpp): any bytes
// give a scene or a one-line error. Beside the input lies a material library whose material
// `leaf` is cut by a mask (map_d, obj_materials.cpp), so that a mutated `usemtl leaf` and its
// texture coordinates reach the cut faces' reader too (seed: corpus/obj/leaf_card), whose
// `glass` and `pane` dissolve below half (d, Tr: seed corpus/obj/glass_pane), and whose `bark of
// the trunk` is named with spaces and a comment after it (seed: corpus/obj/material_names).
#include "fuzz_support.h"

#include "shadowkit/scene/image.h"
#include "shadowkit/scene/scene_io.h"

#include <cstdlib>
#include <fstream>

namespace {

void writeLeafMaterial(const std::filesystem::path& folder) {
    shadowkit::scene::Image mask(4, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) mask.pixel(x, y)[3] = (x + y) % 2 == 0 ? 255 : 0;
    if (!shadowkit::scene::writePng(mask, folder / "shadowkit_fuzz_leaf.png")) std::abort();
    std::ofstream(folder / "shadowkit_fuzz_leaf.mtl")
        << "newmtl leaf\nKd 0.2 0.6 0.1\nmap_d -clamp on shadowkit_fuzz_leaf.png\n"
           "newmtl grey\nmap_d -imfchan l shadowkit_fuzz_leaf.png\n"
           "newmtl glass\nd 0.1\nnewmtl pane\nTr 0.8\nmap_d shadowkit_fuzz_leaf.png\n"
           "newmtl bark  of the trunk # named with spaces\nKd 0.4 0.3 0.2\n";
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const auto file = shadowkit::fuzz::writeInput(data, size, ".obj");
    static const bool materials = (writeLeafMaterial(file.parent_path()), true);
    (void)materials;
    const auto scene = shadowkit::scene::loadScene(file);
    if (!scene && scene.error().find('\n') != std::string::npos) std::abort();
    return 0;
}
