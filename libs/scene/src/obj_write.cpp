// Wavefront OBJ export, with per-vertex colours as `v x y z r g b`. Written in pieces as the
// instances are baked, a few at a time: the 10,000-tree leafy forest is some 11 GB of OBJ text,
// which no export should hold in memory whole.
#include "scene_formats.h"

#include "shadowkit/scene/file_write.h"

#include <algorithm>
#include <cstdio>
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

} // namespace

core::Status exportObj(const Scene& scene, const fs::path& file) {
    return writeFileInPieces(file, [&scene](const ByteSink& write) {
        std::string text = "# shadowkit export: " + std::to_string(scene.triangleCount()) +
                           " triangles, instances baked into world space\n";
        size_t base = 1;
        for (size_t b = 0; b < scene.batches.size(); ++b) {
            const MeshBatch& batch = scene.batches[b];
            text += "o " + scene.meshes[batch.mesh].name + "_" + std::to_string(b) + "\n";
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
                for (size_t i = 0; i + 2 < baked.indices.size(); i += 3) {
                    const size_t a = base + baked.indices[i], c = base + baked.indices[i + 1],
                                 d = base + baked.indices[i + 2];
                    appendf(text, "f %zu//%zu %zu//%zu %zu//%zu\n", a, a, c, c, d, d);
                }
                base += baked.vertices.size();
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
