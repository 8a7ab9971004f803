// Wavefront OBJ export, with per-vertex colours as `v x y z r g b`. Written in pieces as the
// instances are baked, a few at a time: the 10,000-tree leafy forest is some 11 GB of OBJ text,
// which no export should hold in memory whole.
//
// Meshes whose material cuts them (MASK, BLEND cast as MASK) keep their cut: their texture
// coordinates are written (`vt`, v up as OBJ has it), and a material library beside the file
// names, per such material, a PNG of its mask as map_d (obj_materials.cpp reads it back from its
// alpha). An MTL has no cutoff, so the mask's alpha is remapped to put the material's cutoff c
// at one half — a < c to a/(2c), a ≥ c to ½ + ½ (a − c)/(1 − c), the factor's alpha multiplied
// in first — and quantised on the right side of it: every texel is kept or cut as it was
// (between two texel centres across the cut the bilinear edge may move by a fraction of a
// texel, the remapping bending at the cutoff). Files without such meshes are written as before,
// with no library.
#include "scene_formats.h"

#include "shadowkit/scene/file_write.h"
#include "shadowkit/scene/image.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <span>
#include <string>

namespace shadowkit::scene::formats {

namespace fs = std::filesystem;

namespace {

// Instances baked at a time, and the text gathered before it is handed to the file.
constexpr size_t kInstancesPerPiece = 64;
constexpr size_t kPieceBytes = size_t(8) << 20;

template <class... Args>
void appendf(std::string& out, const char* format, Args... args) {
    char line[160];
    const int n = std::snprintf(line, sizeof line, format, args...);
    out.append(line, size_t(std::min(n, int(sizeof line) - 1)));
}

// A material's mask: white, its alpha the texture's (1 without one) remapped so that its cutoff
// lies at one half (above). White, since an OBJ's colour is its vertices' (shadowkit reads no
// texture colour from an OBJ), and a reader that takes a mask with no alpha below 255 as grey
// levels reads it whole, as its alpha says.
Image cutMask(const Scene& scene, const Material& material) {
    const Texture* texture = material.baseColorTexture >= 0 && size_t(material.baseColorTexture) < scene.textures.size()
                                 ? &scene.textures[size_t(material.baseColorTexture)]
                                 : nullptr;
    Image out = texture ? texture->image : Image(1, 1);
    if (!texture) out.rgba[3] = 255;
    const float c = material.alphaCutoff;
    for (size_t i = 3; i < out.rgba.size(); i += 4) {
        out.rgba[i - 3] = out.rgba[i - 2] = out.rgba[i - 1] = 255; // white: a mask read as luminance is whole
        const float a = material.baseColorFactor.a * float(out.rgba[i]) / 255.0f;
        const bool covered = a >= c;
        const float remapped = covered ? (c < 1.0f ? 0.5f + 0.5f * (a - c) / (1.0f - c) : 1.0f) : 0.5f * a / c;
        const int level = int(std::lround(255.0f * std::clamp(remapped, 0.0f, 1.0f)));
        out.rgba[i] = uint8_t(covered ? std::max(level, 128) : std::min(level, 127)); // 127.5 is the cut
    }
    return out;
}

// The cut materials the placed meshes wear, written as `<stem>.mtl` and `<stem>_cut<k>.png`
// beside `file`; their MTL names by Scene::materials index (empty: none to write).
core::Result<std::map<int32_t, std::string>> writeCutMaterials(const Scene& scene, const fs::path& file) {
    std::map<int32_t, std::string> nameOf;
    for (const MeshBatch& batch : scene.batches) {
        const Mesh& mesh = scene.meshes[batch.mesh];
        if (const Material* m = scene.materialOf(mesh); m && m->alphaTested() && !batch.worldFromObject.empty())
            nameOf.emplace(mesh.material, "shadowkit_cut" + std::to_string(nameOf.size()));
    }
    // A target that is a device or a pipe (/dev/stdout) is written in place (writeFile): files
    // beside it would land in /dev. Its cards are written whole, as an OBJ without a library.
    std::error_code error;
    if (fs::exists(file, error) && !fs::is_regular_file(file, error)) nameOf.clear();
    if (nameOf.empty()) return nameOf;
    const std::string stem = file.stem().string();
    std::string mtl = "# shadowkit export: the alpha-cut materials of " + file.filename().string() +
                      " (each mask's cutoff at alpha 0.5)\nnewmtl shadowkit_plain\nKd 1 1 1\n";
    for (auto& [index, name] : nameOf) {
        const Material& material = scene.materials[size_t(index)];
        const std::string png = stem + "_" + name.substr(std::string("shadowkit_").size()) + ".png";
        if (auto written = writePng(cutMask(scene, material), file.parent_path() / png); !written)
            return written.errorInfo();
        const Texture* texture =
            material.baseColorTexture >= 0 ? &scene.textures[size_t(material.baseColorTexture)] : nullptr;
        const bool clamp =
            texture && (texture->wrapS == TextureWrap::ClampToEdge || texture->wrapT == TextureWrap::ClampToEdge);
        const std::string options = clamp ? "-clamp on " : "";
        mtl += "newmtl " + name + "\nKd 1 1 1\nmap_d " + options + png + "\n";
    }
    if (auto written = writeFile(file.parent_path() / (stem + ".mtl"), mtl); !written) return written.errorInfo();
    return nameOf;
}

} // namespace

core::Status exportObj(const Scene& scene, const fs::path& file) {
    const auto cut = writeCutMaterials(scene, file);
    if (!cut) return cut.errorInfo();
    return writeFileInPieces(file, [&scene, &file, &cut = *cut](const ByteSink& write) {
        std::string text = "# shadowkit export: " + std::to_string(scene.triangleCount()) +
                           " triangles, instances baked into world space\n";
        if (!cut.empty()) text += "mtllib " + file.stem().string() + ".mtl\n";
        size_t base = 1, uvBase = 1; // the next vertex's index, and texture coordinate's (cut meshes only)
        for (size_t b = 0; b < scene.batches.size(); ++b) {
            const MeshBatch& batch = scene.batches[b];
            text += "o " + scene.meshes[batch.mesh].name + "_" + std::to_string(b) + "\n";
            const auto cutBy = cut.find(scene.meshes[batch.mesh].material);
            const bool withUv = cutBy != cut.end();
            if (!cut.empty()) text += "usemtl " + (withUv ? cutBy->second : std::string("shadowkit_plain")) + "\n";
            const BakedBatch object = fullMesh(scene.meshes[batch.mesh]);
            const std::span<const glm::mat4> instances(batch.worldFromObject);
            for (size_t first = 0; first < instances.size(); first += kInstancesPerPiece) {
                const BakedBatch baked =
                    placed(object, instances.subspan(first, std::min(kInstancesPerPiece, instances.size() - first)));
                // "v x y z r g b": the widely read vertex-colour extension of OBJ. World
                // coordinates, the scene's origin added in double (a scene far out keeps its
                // millimetres: near_origin.cpp).
                const core::Vec3& origin = scene.wsOrigin;
                for (const Vertex& v : baked.vertices)
                    appendf(text, "v %.4f %.4f %.4f %.3f %.3f %.3f\n", origin.x + v.position.x, origin.y + v.position.y,
                            origin.z + v.position.z, v.albedo.r, v.albedo.g, v.albedo.b);
                for (const Vertex& v : baked.vertices)
                    appendf(text, "vn %.4f %.4f %.4f\n", v.normal.x, v.normal.y, v.normal.z);
                if (withUv) // v up, as OBJ has it: the image's first row at v = 1
                    for (const Vertex& v : baked.vertices) appendf(text, "vt %.6f %.6f\n", v.uv.x, 1.0f - v.uv.y);
                for (size_t i = 0; i + 2 < baked.indices.size(); i += 3) {
                    const size_t a = base + baked.indices[i], c = base + baked.indices[i + 1],
                                 d = base + baked.indices[i + 2];
                    if (withUv) {
                        const size_t ta = a - base + uvBase, tc = c - base + uvBase, td = d - base + uvBase;
                        appendf(text, "f %zu/%zu/%zu %zu/%zu/%zu %zu/%zu/%zu\n", a, ta, a, c, tc, c, d, td, d);
                    } else {
                        appendf(text, "f %zu//%zu %zu//%zu %zu//%zu\n", a, a, c, c, d, d);
                    }
                }
                base += baked.vertices.size();
                if (withUv) uvBase += baked.vertices.size();
                if (text.size() >= kPieceBytes) {
                    if (!write(text)) return; // the file will not be written: stop baking
                    text.clear();
                }
            }
        }
        write(text);
    });
}

} // namespace shadowkit::scene::formats
