// Binary glTF 2.0 export (one mesh per batch, instances baked, COLOR_0), with the scene's
// materials and their textures: base colour factor, alpha mode and cutoff, double-sidedness,
// the texture as a PNG in the binary chunk with its sampler and TEXCOORD_0 — what gltf_read.cpp
// reads, so an exported leafy forest loads back with its leaves' holes. Only what the file draws
// is written: the textures its materials use (not the billboard clouds', which a loader bakes
// again) and the vertices its triangles use (bake()).
#include "scene_formats.h"

#include "shadowkit/scene/file_write.h"
#include "shadowkit/scene/image.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <span>
#include <sstream>
#include <string>

namespace shadowkit::scene::formats {

namespace fs = std::filesystem;

// `target` 0 for a view no accessor reads (an image). Each view starts on 4 bytes, so that every
// accessor's components are aligned after an image of any length (glTF 2.0 §3.6.2.4).
template <class T>
int appendBufferView(tinygltf::Model& model, std::span<const T> data, int target) {
    auto& bytes = model.buffers[0].data;
    const size_t offset = (bytes.size() + 3) / 4 * 4;
    bytes.resize(offset + data.size_bytes());
    std::memcpy(bytes.data() + offset, data.data(), data.size_bytes());
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = offset;
    view.byteLength = data.size_bytes();
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

int gltfWrap(TextureWrap wrap) {
    return wrap == TextureWrap::ClampToEdge      ? TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE
           : wrap == TextureWrap::MirroredRepeat ? TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT
                                                 : TINYGLTF_TEXTURE_WRAP_REPEAT;
}

// The scene's textures that its materials use, as PNG images in the buffer with one sampler
// each, and Scene::materials in order, their texture indices into the textures written.
core::Status addMaterials(const Scene& scene, tinygltf::Model& model) {
    std::vector<int> written(scene.textures.size(), -1);
    for (const Material& m : scene.materials) {
        if (m.baseColorTexture < 0 || size_t(m.baseColorTexture) >= scene.textures.size()) continue;
        int& index = written[size_t(m.baseColorTexture)];
        if (index >= 0) continue;
        const Texture& t = scene.textures[size_t(m.baseColorTexture)];
        const core::Result<std::string> png =
            encodePng(t.image, "texture " + std::to_string(m.baseColorTexture) + " of material '" + m.name + "'");
        if (!png) return png.errorInfo();
        tinygltf::Image image;
        image.mimeType = "image/png";
        image.bufferView = appendBufferView(model, std::span<const char>(*png), 0);
        model.images.push_back(std::move(image));
        tinygltf::Sampler sampler;
        sampler.wrapS = gltfWrap(t.wrapS), sampler.wrapT = gltfWrap(t.wrapT);
        sampler.magFilter = t.nearest ? TINYGLTF_TEXTURE_FILTER_NEAREST : TINYGLTF_TEXTURE_FILTER_LINEAR;
        sampler.minFilter = t.mipmaps ? TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR : TINYGLTF_TEXTURE_FILTER_LINEAR;
        model.samplers.push_back(sampler);
        tinygltf::Texture texture;
        texture.source = texture.sampler = int(model.images.size() - 1);
        model.textures.push_back(texture);
        index = int(model.textures.size() - 1);
    }
    for (const Material& m : scene.materials) {
        tinygltf::Material out;
        out.name = m.name;
        out.pbrMetallicRoughness.baseColorFactor = {m.baseColorFactor.r, m.baseColorFactor.g, m.baseColorFactor.b,
                                                    m.baseColorFactor.a};
        out.pbrMetallicRoughness.baseColorTexture.index =
            m.baseColorTexture >= 0 && size_t(m.baseColorTexture) < written.size() ? written[size_t(m.baseColorTexture)]
                                                                                   : -1;
        out.pbrMetallicRoughness.baseColorTexture.texCoord = 0;
        out.alphaMode = m.alphaMode == AlphaMode::Mask ? "MASK" : m.alphaMode == AlphaMode::Blend ? "BLEND" : "OPAQUE";
        out.alphaCutoff = m.alphaCutoff;
        out.doubleSided = m.doubleSided;
        model.materials.push_back(std::move(out));
    }
    return core::Ok{};
}

// A binary glTF's header and chunk headers hold their lengths in 32 bits (glTF 2.0 §4.4.3), so
// a file holds at most 2^32 − 1 bytes; tinygltf would truncate the lengths and write a file no
// reader can open. The geometry's bytes, counted before anything is built (the 10,000-tree leafy
// forest would need 5.5 GB), then the encoded file's.
constexpr uint64_t kGlbMaxBytes = (uint64_t(1) << 32) - 1;

uint64_t geometryBytes(const Scene& scene) {
    uint64_t bytes = 0;
    for (const MeshBatch& batch : scene.batches) {
        const Mesh& mesh = scene.meshes[batch.mesh];
        std::vector<bool> used(mesh.vertices.size(), false);
        for (uint32_t i : mesh.indices) used[i] = true;
        const auto vertices = uint64_t(std::count(used.begin(), used.end(), true));
        const Material* material = scene.materialOf(mesh);
        const uint64_t perVertex =
            3 * sizeof(glm::vec3) + (material && material->baseColorTexture >= 0 ? sizeof(glm::vec2) : 0);
        bytes += batch.worldFromObject.size() * (vertices * perVertex + mesh.indices.size() * sizeof(uint32_t));
    }
    return bytes;
}

core::Error tooLarge(const fs::path& file, uint64_t bytes) {
    char size[32];
    std::snprintf(size, sizeof size, "%.2f GB", double(bytes) * 1e-9);
    return core::makeError(
        file.string() + ": the scene needs " + size +
        ", more than the 4.29 GB (2^32 bytes) a binary glTF can hold: export it as .obj, or fewer trees");
}

core::Status exportGlb(const Scene& scene, const fs::path& file) {
    if (const uint64_t bytes = geometryBytes(scene); bytes > kGlbMaxBytes) return tooLarge(file, bytes);
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "shadowkit export";
    model.buffers.emplace_back();
    model.scenes.emplace_back();
    model.defaultScene = 0;
    if (core::Status s = addMaterials(scene, model); !s) return core::makeError(file.string() + ": " + s.error());
    for (size_t b = 0; b < scene.batches.size(); ++b) {
        const BakedBatch baked = bake(scene, scene.batches[b]);
        std::vector<glm::vec3> positions, normals, colors;
        core::Aabb bounds;
        // The reader multiplies COLOR_0 by the material's factor: the factor comes out here.
        const Material* material = scene.materialOf(scene.meshes[scene.batches[b].mesh]);
        const glm::vec3 factor = material ? glm::vec3(material->baseColorFactor) : glm::vec3(1.0f);
        for (const Vertex& v : baked.vertices) {
            positions.push_back(v.position);
            normals.push_back(v.normal);
            colors.push_back(glm::vec3(factor.r > 0.0f ? v.albedo.r / factor.r : v.albedo.r,
                                       factor.g > 0.0f ? v.albedo.g / factor.g : v.albedo.g,
                                       factor.b > 0.0f ? v.albedo.b / factor.b : v.albedo.b));
            bounds.extend(core::Vec3(v.position));
        }
        tinygltf::Primitive prim;
        prim.mode = TINYGLTF_MODE_TRIANGLES;
        prim.attributes["POSITION"] = appendAccessor(
            model, appendBufferView(model, std::span<const glm::vec3>(positions), TINYGLTF_TARGET_ARRAY_BUFFER),
            TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, positions.size(),
            {bounds.min.x, bounds.min.y, bounds.min.z}, {bounds.max.x, bounds.max.y, bounds.max.z});
        prim.attributes["NORMAL"] = appendAccessor(
            model, appendBufferView(model, std::span<const glm::vec3>(normals), TINYGLTF_TARGET_ARRAY_BUFFER),
            TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, normals.size());
        prim.attributes["COLOR_0"] = appendAccessor(
            model, appendBufferView(model, std::span<const glm::vec3>(colors), TINYGLTF_TARGET_ARRAY_BUFFER),
            TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, colors.size());
        if (material) {
            prim.material = scene.meshes[scene.batches[b].mesh].material;
            if (material->baseColorTexture >= 0) {
                std::vector<glm::vec2> uvs;
                for (const Vertex& v : baked.vertices) uvs.push_back(v.uv);
                prim.attributes["TEXCOORD_0"] = appendAccessor(
                    model, appendBufferView(model, std::span<const glm::vec2>(uvs), TINYGLTF_TARGET_ARRAY_BUFFER),
                    TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, uvs.size());
            }
        }
        prim.indices = appendAccessor(
            model,
            appendBufferView(model, std::span<const uint32_t>(baked.indices), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
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
    std::ostringstream glb;
    if (!writer.WriteGltfSceneToStream(&model, glb, false, true))
        return core::makeError(file.string() + ": cannot encode glTF");
    if (glb.view().size() > kGlbMaxBytes) return tooLarge(file, glb.view().size());
    return writeFile(file, glb.view());
}

} // namespace shadowkit::scene::formats
