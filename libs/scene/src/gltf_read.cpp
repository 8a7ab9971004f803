// glTF 2.0 import (.gltf, .glb) through tinygltf: nodes become instances of their mesh.
#include "scene_formats.h"

#include <tiny_gltf.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cstring>
#include <map>

namespace shadowkit::scene::formats {

namespace fs = std::filesystem;

namespace {

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

} // namespace

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

} // namespace shadowkit::scene::formats
