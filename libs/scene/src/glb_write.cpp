// Binary glTF 2.0 export (one mesh per batch, instances baked, COLOR_0).
#include "scene_formats.h"

#include <tiny_gltf.h>

namespace shadowkit::scene::formats {

namespace fs = std::filesystem;

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
        prim.attributes["POSITION"] =
            appendAccessor(model, appendBufferView(model, positions, TINYGLTF_TARGET_ARRAY_BUFFER),
                           TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, positions.size(),
                           {bounds.min.x, bounds.min.y, bounds.min.z}, {bounds.max.x, bounds.max.y, bounds.max.z});
        prim.attributes["NORMAL"] =
            appendAccessor(model, appendBufferView(model, normals, TINYGLTF_TARGET_ARRAY_BUFFER),
                           TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, normals.size());
        prim.attributes["COLOR_0"] =
            appendAccessor(model, appendBufferView(model, colors, TINYGLTF_TARGET_ARRAY_BUFFER),
                           TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, colors.size());
        prim.indices =
            appendAccessor(model, appendBufferView(model, baked.indices, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
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

} // namespace shadowkit::scene::formats
