// Wavefront OBJ export, with per-vertex colours as `v x y z r g b`.
#include "scene_formats.h"

#include "shadowkit/scene/file_write.h"

#include <sstream>

namespace shadowkit::scene::formats {

namespace fs = std::filesystem;

core::Status exportObj(const Scene& scene, const fs::path& file) {
    std::ostringstream out;
    out << "# shadowkit export: " << scene.triangleCount() << " triangles, instances baked into world space\n";
    size_t base = 1;
    char buf[160];
    for (size_t b = 0; b < scene.batches.size(); ++b) {
        const BakedBatch baked = bake(scene, scene.batches[b]);
        out << "o " << scene.meshes[scene.batches[b].mesh].name << "_" << b << "\n";
        for (const Vertex& v : baked.vertices) {
            // "v x y z r g b": the widely read vertex-colour extension of OBJ.
            std::snprintf(buf, sizeof buf, "v %.4f %.4f %.4f %.3f %.3f %.3f\n", v.position.x, v.position.y,
                          v.position.z, v.albedo.r, v.albedo.g, v.albedo.b);
            out << buf;
        }
        for (const Vertex& v : baked.vertices) {
            std::snprintf(buf, sizeof buf, "vn %.4f %.4f %.4f\n", v.normal.x, v.normal.y, v.normal.z);
            out << buf;
        }
        for (size_t i = 0; i < baked.indices.size(); i += 3) {
            const size_t a = base + baked.indices[i], c = base + baked.indices[i + 1], d = base + baked.indices[i + 2];
            out << "f " << a << "//" << a << ' ' << c << "//" << c << ' ' << d << "//" << d << '\n';
        }
        base += baked.vertices.size();
    }
    return writeFile(file, out.view());
}

} // namespace shadowkit::scene::formats
