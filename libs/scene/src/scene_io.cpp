#include "shadowkit/scene/scene_io.h"

#include <tiny_gltf.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

namespace shadowkit::scene {
namespace {

namespace fs = std::filesystem;

std::string lowerExtension(const fs::path& file) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

// Smooth normals from triangle areas, for files that carry none.
void computeNormals(Mesh& mesh) {
    for (Vertex& v : mesh.vertices) v.normal = glm::vec3(0.0f);
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        Vertex& a = mesh.vertices[mesh.indices[i]];
        Vertex& b = mesh.vertices[mesh.indices[i + 1]];
        Vertex& c = mesh.vertices[mesh.indices[i + 2]];
        const glm::vec3 n = glm::cross(b.position - a.position, c.position - a.position);
        a.normal += n;
        b.normal += n;
        c.normal += n;
    }
    for (Vertex& v : mesh.vertices) {
        const float len = glm::length(v.normal);
        v.normal = len > 0.0f ? v.normal / len : glm::vec3(0, 1, 0);
    }
}

// ---------------------------------------------------------------- glTF
// Reads accessor element i as up to 4 floats (float, normalized integer or integer data).
class AccessorReader {
public:
    AccessorReader(const tinygltf::Model& model, int index) : m_accessor(model.accessors.at(size_t(index))) {
        const auto& view = model.bufferViews.at(size_t(m_accessor.bufferView));
        m_data = model.buffers.at(size_t(view.buffer)).data.data() + view.byteOffset + m_accessor.byteOffset;
        m_components = tinygltf::GetNumComponentsInType(uint32_t(m_accessor.type));
        m_componentSize = tinygltf::GetComponentSizeInBytes(uint32_t(m_accessor.componentType));
        m_stride = m_accessor.ByteStride(view);
    }
    size_t count() const { return m_accessor.count; }
    glm::vec4 read(size_t i, glm::vec4 fallback = glm::vec4(0, 0, 0, 1)) const {
        glm::vec4 out = fallback;
        const unsigned char* p = m_data + i * size_t(m_stride);
        for (int c = 0; c < std::min(m_components, 4); ++c) out[c] = component(p + c * m_componentSize);
        return out;
    }
    uint32_t readIndex(size_t i) const { return static_cast<uint32_t>(component(m_data + i * size_t(m_stride))); }

private:
    float component(const unsigned char* p) const {
        const bool norm = m_accessor.normalized;
        switch (m_accessor.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p, 4); return f; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return norm ? float(*p) / 255.0f : float(*p);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t v; std::memcpy(&v, p, 2); return norm ? float(v) / 65535.0f : float(v); }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t v; std::memcpy(&v, p, 4); return float(v); }
        default: return 0.0f;
        }
    }
    const tinygltf::Accessor& m_accessor;
    const unsigned char* m_data = nullptr;
    int m_components = 0, m_componentSize = 0, m_stride = 0;
};

glm::mat4 nodeLocalMatrix(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) {
        glm::dmat4 m;
        std::copy(node.matrix.begin(), node.matrix.end(), glm::value_ptr(m));
        return glm::mat4(m);
    }
    glm::dmat4 m(1.0);
    if (node.translation.size() == 3) m = glm::translate(m, glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
    if (node.rotation.size() == 4)
        m *= glm::mat4_cast(glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]));
    if (node.scale.size() == 3) m = glm::scale(m, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
    return glm::mat4(m);
}

// Converts one triangle primitive; returns false if it is not a triangle list with positions.
bool convertPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& prim, Mesh& mesh) {
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) return false;
    const auto pos = prim.attributes.find("POSITION");
    if (pos == prim.attributes.end()) return false;
    const AccessorReader positions(model, pos->second);
    glm::vec3 albedo(0.7f);
    if (prim.material >= 0) {
        const auto& f = model.materials[size_t(prim.material)].pbrMetallicRoughness.baseColorFactor;
        if (f.size() >= 3) albedo = glm::vec3(float(f[0]), float(f[1]), float(f[2]));
    }
    mesh.vertices.resize(positions.count());
    for (size_t i = 0; i < positions.count(); ++i) mesh.vertices[i] = {glm::vec3(positions.read(i)), glm::vec3(0, 1, 0), albedo};
    if (const auto c = prim.attributes.find("COLOR_0"); c != prim.attributes.end()) {
        const AccessorReader colors(model, c->second);
        for (size_t i = 0; i < std::min(colors.count(), mesh.vertices.size()); ++i)
            mesh.vertices[i].albedo = albedo * glm::vec3(colors.read(i, glm::vec4(1.0f)));
    }
    if (prim.indices >= 0) {
        const AccessorReader indices(model, prim.indices);
        for (size_t i = 0; i < indices.count(); ++i) mesh.indices.push_back(indices.readIndex(i));
    } else {
        for (size_t i = 0; i < mesh.vertices.size(); ++i) mesh.indices.push_back(static_cast<uint32_t>(i));
    }
    mesh.indices.resize(mesh.indices.size() / 3 * 3);
    for (uint32_t idx : mesh.indices)
        if (idx >= mesh.vertices.size()) return false;
    if (const auto n = prim.attributes.find("NORMAL"); n != prim.attributes.end()) {
        const AccessorReader normals(model, n->second);
        for (size_t i = 0; i < std::min(normals.count(), mesh.vertices.size()); ++i)
            mesh.vertices[i].normal = glm::normalize(glm::vec3(normals.read(i)));
    } else {
        computeNormals(mesh);
    }
    mesh.computeBounds();
    return !mesh.indices.empty();
}

core::Result<Scene> loadGltf(const fs::path& file) {
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string err, warn;
    const bool ok = lowerExtension(file) == ".glb" ? loader.LoadBinaryFromFile(&model, &err, &warn, file.string())
                                                   : loader.LoadASCIIFromFile(&model, &err, &warn, file.string());
    if (!ok) {
        std::replace(err.begin(), err.end(), '\n', ' ');
        return core::makeError(file.string() + ": not a readable glTF file (" + err + ")");
    }
    Scene scene;
    // (mesh, primitive) -> batch index: a mesh placed by many nodes becomes one instanced batch.
    std::map<std::pair<int, size_t>, size_t> batchOf;
    auto visit = [&](auto&& self, int nodeIndex, const glm::mat4& parent, int depth) -> void {
        if (depth > 64 || nodeIndex < 0 || size_t(nodeIndex) >= model.nodes.size()) return; // cycles / bad refs
        const tinygltf::Node& node = model.nodes[size_t(nodeIndex)];
        const glm::mat4 world = parent * nodeLocalMatrix(node);
        if (node.mesh >= 0 && size_t(node.mesh) < model.meshes.size()) {
            const auto& prims = model.meshes[size_t(node.mesh)].primitives;
            for (size_t p = 0; p < prims.size(); ++p) {
                auto [it, inserted] = batchOf.try_emplace({node.mesh, p}, scene.batches.size());
                if (inserted) {
                    Mesh mesh;
                    mesh.name = model.meshes[size_t(node.mesh)].name;
                    if (!convertPrimitive(model, prims[p], mesh)) { batchOf.erase(it); continue; }
                    scene.meshes.push_back(std::move(mesh));
                    scene.batches.push_back({uint32_t(scene.meshes.size() - 1), {}, false});
                }
                scene.batches[it->second].worldFromObject.push_back(world);
            }
        }
        for (int child : node.children) self(self, child, world, depth + 1);
    };
    const int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (!model.scenes.empty())
        for (int root : model.scenes[size_t(sceneIndex)].nodes) visit(visit, root, glm::mat4(1.0f), 0);
    if (scene.triangleCount() == 0) return core::makeError(file.string() + ": glTF file holds no triangle meshes");
    return scene;
}

// ---------------------------------------------------------------- OBJ
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

// ---------------------------------------------------------------- export
// One batch with every instance transformed into world space.
struct BakedBatch {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
};
BakedBatch bake(const Scene& scene, const MeshBatch& batch) {
    const Mesh& mesh = scene.meshes[batch.mesh];
    BakedBatch out;
    out.vertices.reserve(mesh.vertices.size() * batch.worldFromObject.size());
    out.indices.reserve(mesh.indices.size() * batch.worldFromObject.size());
    for (const glm::mat4& m : batch.worldFromObject) {
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(m)));
        const auto base = static_cast<uint32_t>(out.vertices.size());
        for (const Vertex& v : mesh.vertices)
            out.vertices.push_back({glm::vec3(m * glm::vec4(v.position, 1.0f)), glm::normalize(normalMatrix * v.normal), v.albedo});
        for (uint32_t i : mesh.indices) out.indices.push_back(base + i);
    }
    return out;
}

core::Status exportObj(const Scene& scene, const fs::path& file) {
    std::ofstream out(file);
    if (!out) return core::makeError(file.string() + ": cannot open for writing");
    out << "# shadowkit export: " << scene.triangleCount() << " triangles, instances baked into world space\n";
    size_t base = 1;
    char buf[160];
    for (size_t b = 0; b < scene.batches.size(); ++b) {
        const BakedBatch baked = bake(scene, scene.batches[b]);
        out << "o " << scene.meshes[scene.batches[b].mesh].name << "_" << b << "\n";
        for (const Vertex& v : baked.vertices) {
            // "v x y z r g b": the widely read vertex-colour extension of OBJ.
            std::snprintf(buf, sizeof buf, "v %.4f %.4f %.4f %.3f %.3f %.3f\n", v.position.x, v.position.y, v.position.z,
                          v.albedo.r, v.albedo.g, v.albedo.b);
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
    if (!out) return core::makeError(file.string() + ": write failed (disk full?)");
    return core::Ok{};
}

template <class T>
int appendBufferView(tinygltf::Model& model, const std::vector<T>& data, int target) {
    auto& bytes = model.buffers[0].data;
    const size_t offset = bytes.size();
    bytes.resize(offset + data.size() * sizeof(T));
    std::memcpy(bytes.data() + offset, data.data(), data.size() * sizeof(T));
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = offset;
    view.byteLength = data.size() * sizeof(T);
    view.target = target;
    model.bufferViews.push_back(view);
    return int(model.bufferViews.size() - 1);
}

int appendAccessor(tinygltf::Model& model, int view, int componentType, int type, size_t count,
                   std::vector<double> lo = {}, std::vector<double> hi = {}) {
    tinygltf::Accessor a;
    a.bufferView = view;
    a.componentType = componentType;
    a.type = type;
    a.count = count;
    a.minValues = std::move(lo);
    a.maxValues = std::move(hi);
    model.accessors.push_back(a);
    return int(model.accessors.size() - 1);
}

core::Status exportGlb(const Scene& scene, const fs::path& file) {
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "shadowkit export";
    model.buffers.emplace_back();
    model.scenes.emplace_back();
    model.defaultScene = 0;
    for (size_t b = 0; b < scene.batches.size(); ++b) {
        const BakedBatch baked = bake(scene, scene.batches[b]);
        std::vector<glm::vec3> positions, normals, colors;
        core::Aabb bounds;
        for (const Vertex& v : baked.vertices) {
            positions.push_back(v.position);
            normals.push_back(v.normal);
            colors.push_back(v.albedo);
            bounds.extend(core::Vec3(v.position));
        }
        tinygltf::Primitive prim;
        prim.mode = TINYGLTF_MODE_TRIANGLES;
        prim.attributes["POSITION"] = appendAccessor(model, appendBufferView(model, positions, TINYGLTF_TARGET_ARRAY_BUFFER),
                                                     TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, positions.size(),
                                                     {bounds.min.x, bounds.min.y, bounds.min.z}, {bounds.max.x, bounds.max.y, bounds.max.z});
        prim.attributes["NORMAL"] = appendAccessor(model, appendBufferView(model, normals, TINYGLTF_TARGET_ARRAY_BUFFER),
                                                   TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, normals.size());
        prim.attributes["COLOR_0"] = appendAccessor(model, appendBufferView(model, colors, TINYGLTF_TARGET_ARRAY_BUFFER),
                                                    TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, colors.size());
        prim.indices = appendAccessor(model, appendBufferView(model, baked.indices, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, baked.indices.size());
        tinygltf::Mesh mesh;
        mesh.name = scene.meshes[scene.batches[b].mesh].name;
        mesh.primitives.push_back(prim);
        model.meshes.push_back(mesh);
        tinygltf::Node node;
        node.mesh = int(model.meshes.size() - 1);
        node.name = mesh.name;
        model.nodes.push_back(node);
        model.scenes[0].nodes.push_back(int(model.nodes.size() - 1));
    }
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToFile(&model, file.string(), true, true, false, true))
        return core::makeError(file.string() + ": cannot write glTF file");
    return core::Ok{};
}

} // namespace

core::Result<Scene> loadScene(const fs::path& file) {
    std::error_code ec;
    if (!fs::exists(file, ec)) return core::makeError(file.string() + ": scene file does not exist");
    if (fs::is_directory(file, ec)) return core::makeError(file.string() + ": is a directory, not a scene file");
    const std::string ext = lowerExtension(file);
    if (ext == ".gltf" || ext == ".glb") return loadGltf(file);
    if (ext == ".obj") return loadObj(file);
    return core::makeError(file.string() + ": unknown scene format (use .gltf, .glb or .obj)");
}

core::Status exportScene(const Scene& scene, const fs::path& file) {
    const std::string ext = lowerExtension(file);
    if (ext == ".glb") return exportGlb(scene, file);
    if (ext == ".obj") return exportObj(scene, file);
    return core::makeError(file.string() + ": unknown export format (use .glb or .obj)");
}

} // namespace shadowkit::scene
