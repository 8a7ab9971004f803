// Wavefront OBJ import: one mesh, one instance.
#include "scene_formats.h"

#include <fstream>
#include <sstream>

namespace shadowkit::scene::formats {

namespace fs = std::filesystem;

core::Result<Scene> loadObj(const fs::path& file) {
    std::ifstream in(file);
    if (!in) return core::makeError(file.string() + ": cannot open scene file");
    Mesh mesh;
    mesh.name = file.stem().string();
    std::vector<glm::vec3> positions;
    std::string line;
    size_t lineNo = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        std::istringstream ss(line);
        std::string tag;
        ss >> tag;
        if (tag == "v") {
            glm::vec3 p;
            if (!(ss >> p.x >> p.y >> p.z)) return core::makeError(file.string() + ":" + std::to_string(lineNo) + ": malformed vertex");
            positions.push_back(p);
        } else if (tag == "f") {
            std::vector<uint32_t> face;
            std::string corner;
            while (ss >> corner) {
                long idx = std::strtol(corner.c_str(), nullptr, 10); // "i", "i/t", "i//n", "i/t/n"
                if (idx < 0) idx += long(positions.size()) + 1;      // relative indices
                if (idx < 1 || size_t(idx) > positions.size())
                    return core::makeError(file.string() + ":" + std::to_string(lineNo) + ": face index out of range");
                face.push_back(uint32_t(idx - 1));
            }
            for (size_t i = 1; i + 1 < face.size(); ++i) mesh.indices.insert(mesh.indices.end(), {face[0], face[i], face[i + 1]});
        }
    }
    if (mesh.indices.empty()) return core::makeError(file.string() + ": OBJ file holds no faces");
    for (const glm::vec3& p : positions) mesh.vertices.push_back({p, glm::vec3(0, 1, 0), glm::vec3(0.7f)});
    computeNormals(mesh);
    mesh.computeBounds();
    Scene scene;
    scene.meshes.push_back(std::move(mesh));
    scene.batches.push_back({0, {glm::mat4(1.0f)}, false});
    return scene;
}

} // namespace shadowkit::scene::formats
