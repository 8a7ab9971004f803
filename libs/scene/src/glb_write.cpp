// Binary glTF 2.0 export: each batch's full mesh once (COLOR_0) and a node placing it per
// instance, as engines draw instances, with the scene's materials and their textures: base
// colour factor, alpha mode and cutoff, double-sidedness, the texture as a PNG in the binary
// chunk with its sampler and TEXCOORD_0 — what gltf_read.cpp reads, so an exported leafy forest
// loads back with its leaves' holes and its trees as instances. Only what the file draws is
// written: the textures its materials use (not the billboard clouds', which a loader bakes
// again) and the vertices the full meshes' triangles use (fullMesh()). A file's animations are
// written back with the instances they move (gltf_animation.cpp's AnimationWriter), a forest's
// circling movers as keys round their circles (circleAsKeys), and a mesh
// they deform with its skin, morph targets and keys (appendDeformedBatch).
#include "gltf_animation.h"
#include "gltf_viewpoints.h"
#include "scene_formats.h"

#include "shadowkit/scene/animation.h"
#include "shadowkit/scene/file_write.h"
#include "shadowkit/scene/image.h"

#include <tiny_gltf.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <map>
#include <optional>
#include <span>
#include <sstream>
#include <string>

namespace shadowkit::scene::formats {

namespace fs = std::filesystem;

namespace {

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

// Whether a node can carry this placement: glTF's node matrices must decompose into
// translation, rotation and scale (glTF 2.0 §3.5.3), which a loaded file's node hierarchy can
// break (a non-uniform scale under a rotation shears); such instances are baked instead.
bool isTrs(const glm::mat4& m) {
    if (m[0][3] != 0.0f || m[1][3] != 0.0f || m[2][3] != 0.0f || m[3][3] != 1.0f) return false;
    const glm::vec3 x(m[0]), y(m[1]), z(m[2]);
    const float lx = glm::length(x), ly = glm::length(y), lz = glm::length(z);
    if (!(lx > 0.0f && ly > 0.0f && lz > 0.0f)) return false;
    constexpr float kOrthogonal = 1e-4f; // cosine of the angle between two axes
    return std::abs(glm::dot(x, y)) <= kOrthogonal * lx * ly && std::abs(glm::dot(y, z)) <= kOrthogonal * ly * lz &&
           std::abs(glm::dot(z, x)) <= kOrthogonal * lz * lx;
}

// A batch's instances as the file holds them: the full mesh once for the nodes that place it,
// with its triangles' winding as the file states it for mirrored ones (a glTF reader turns a
// mirrored node's winding itself, and Scene keeps a mirrored batch's triangles already turned:
// gltf_read.cpp), and baked into world space for placements no node can carry.
struct BatchPlan {
    std::vector<size_t> placed, mirrored, baked; // instance indices
};
BatchPlan planOf(const MeshBatch& batch) {
    BatchPlan plan;
    for (size_t i = 0; i < batch.worldFromObject.size(); ++i) {
        const glm::mat4& m = batch.worldFromObject[i];
        if (!isTrs(m))
            plan.baked.push_back(i);
        else if (glm::determinant(glm::mat3(m)) < 0.0f)
            plan.mirrored.push_back(i);
        else
            plan.placed.push_back(i);
    }
    return plan;
}

// A binary glTF's header and chunk headers hold their lengths in 32 bits (glTF 2.0 §4.4.3), so
// a file holds at most 2^32 − 1 bytes; tinygltf would truncate the lengths and write a file no
// reader can open. The geometry's bytes, counted before anything is built, then the encoded file's.
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
        const uint64_t meshBytes = vertices * perVertex + mesh.indices.size() * sizeof(uint32_t);
        const BatchPlan plan = planOf(batch);
        bytes += (plan.placed.empty() && plan.mirrored.empty() ? 0 : meshBytes) +
                 (plan.mirrored.empty() || plan.placed.empty() ? 0 : mesh.indices.size() * sizeof(uint32_t)) +
                 plan.baked.size() * meshBytes;
    }
    return bytes;
}

core::Error tooLarge(const fs::path& file, uint64_t bytes) {
    char size[32];
    std::snprintf(size, sizeof size, "%.2f GB", double(bytes) * 1e-9);
    return core::makeError(file.string() + ": the scene needs " + size +
                           ", more than the 4.29 GB (2^32 bytes) a binary glTF can hold: export it as .obj");
}

// POSITION, NORMAL, COLOR_0 and, for a textured material, TEXCOORD_0 of `geometry`'s vertices.
std::map<std::string, int> appendAttributes(tinygltf::Model& model, const BakedBatch& geometry,
                                            const Material* material) {
    std::vector<glm::vec3> positions, normals, colors;
    core::Aabb bounds;
    // The reader multiplies COLOR_0 by the material's factor: the factor comes out here.
    const glm::vec3 factor = material ? glm::vec3(material->baseColorFactor) : glm::vec3(1.0f);
    for (const Vertex& v : geometry.vertices) {
        positions.push_back(v.position);
        normals.push_back(v.normal);
        colors.push_back(glm::vec3(factor.r > 0.0f ? v.albedo.r / factor.r : v.albedo.r,
                                   factor.g > 0.0f ? v.albedo.g / factor.g : v.albedo.g,
                                   factor.b > 0.0f ? v.albedo.b / factor.b : v.albedo.b));
        bounds.extend(core::Vec3(v.position));
    }
    const auto vec3s = [&model](const std::vector<glm::vec3>& data, std::vector<double> lo = {},
                                std::vector<double> hi = {}) {
        return appendAccessor(
            model, appendBufferView(model, std::span<const glm::vec3>(data), TINYGLTF_TARGET_ARRAY_BUFFER),
            TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, data.size(), std::move(lo), std::move(hi));
    };
    std::map<std::string, int> attributes;
    attributes["POSITION"] =
        vec3s(positions, {bounds.min.x, bounds.min.y, bounds.min.z}, {bounds.max.x, bounds.max.y, bounds.max.z});
    attributes["NORMAL"] = vec3s(normals);
    attributes["COLOR_0"] = vec3s(colors);
    if (material && material->baseColorTexture >= 0) {
        std::vector<glm::vec2> uvs;
        for (const Vertex& v : geometry.vertices) uvs.push_back(v.uv);
        attributes["TEXCOORD_0"] = appendAccessor(
            model, appendBufferView(model, std::span<const glm::vec2>(uvs), TINYGLTF_TARGET_ARRAY_BUFFER),
            TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, uvs.size());
    }
    return attributes;
}

// A mesh of one primitive over `attributes`, drawing `indices`; returns its index.
int appendMesh(tinygltf::Model& model, const std::string& name, const std::map<std::string, int>& attributes,
               const std::vector<uint32_t>& indices, int material) {
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.attributes = attributes;
    prim.material = material;
    prim.indices = appendAccessor(
        model, appendBufferView(model, std::span<const uint32_t>(indices), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
        TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, indices.size());
    tinygltf::Mesh mesh;
    mesh.name = name;
    mesh.primitives.push_back(std::move(prim));
    model.meshes.push_back(std::move(mesh));
    return int(model.meshes.size() - 1);
}

// A node drawing `mesh` (or grouping `children`), placed by `worldFromObject` unless it is the
// identity; returns its index.
int appendNode(tinygltf::Model& model, int mesh, const std::string& name, const glm::mat4& worldFromObject,
               std::vector<int> children = {}) {
    tinygltf::Node node;
    node.mesh = mesh;
    node.name = name;
    node.children = std::move(children);
    if (worldFromObject != glm::mat4(1.0f))
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) node.matrix.push_back(worldFromObject[c][r]); // column-major, as glTF
    model.nodes.push_back(std::move(node));
    return int(model.nodes.size() - 1);
}

// One batch: a group node named after its mesh, holding a node per instance over the full mesh
// (its mirrored instances over the same vertices with the winding the file states), and one
// mesh of the instances baked into world space where a node cannot place them.
// An instance a file's animation moves (`moving`, by instance index) is placed by its motion's
// nodes instead, its channels written by `animations`.
void appendBatch(tinygltf::Model& model, const Scene& scene, const MeshBatch& batch,
                 const std::map<size_t, const NodeMotion*>& moving, AnimationWriter& animations) {
    const Mesh& mesh = scene.meshes[batch.mesh];
    const Material* material = scene.materialOf(mesh);
    const int materialIndex = material ? mesh.material : -1;
    const BatchPlan plan = planOf(batch);
    const BakedBatch object = fullMesh(mesh);
    std::vector<int> children;
    if (!plan.placed.empty() || !plan.mirrored.empty()) {
        const std::map<std::string, int> attributes = appendAttributes(model, object, material);
        const auto placeAll = [&](const std::vector<size_t>& instances, int meshIndex) {
            for (size_t i : instances) {
                const auto motion = moving.find(i);
                children.push_back(motion != moving.end() ? animations.appendMotion(*motion->second, meshIndex)
                                                          : appendNode(model, meshIndex, "", batch.worldFromObject[i]));
            }
        };
        if (!plan.placed.empty())
            placeAll(plan.placed, appendMesh(model, mesh.name, attributes, object.indices, materialIndex));
        if (!plan.mirrored.empty()) {
            std::vector<uint32_t> turned = object.indices;
            for (size_t t = 0; t + 2 < turned.size(); t += 3) std::swap(turned[t + 1], turned[t + 2]);
            placeAll(plan.mirrored, appendMesh(model, mesh.name + " (mirrored)", attributes, turned, materialIndex));
        }
    }
    if (!plan.baked.empty()) {
        std::vector<glm::mat4> worldFromObject;
        for (size_t i : plan.baked) worldFromObject.push_back(batch.worldFromObject[i]);
        const BakedBatch baked = placed(object, worldFromObject);
        const int meshIndex = appendMesh(model, mesh.name + " (baked)", appendAttributes(model, baked, material),
                                         baked.indices, materialIndex);
        children.push_back(appendNode(model, meshIndex, "", glm::mat4(1.0f)));
    }
    model.scenes[0].nodes.push_back(appendNode(model, -1, mesh.name, glm::mat4(1.0f), std::move(children)));
}

// A batch whose mesh the file's animations deform, written so that it plays again: its bind
// vertices with its morph targets and their weights' keys, and a skin whose joints are placed
// by their chains of nodes and keys (AnimationWriter::appendMotion), one per instance. What a
// reader poses from it is what `deformation` poses in the scene (deformation.h): the vertices
// are written relative to their bind box's centre B, the inverse bind matrices taking B back
// (IBM · T(B)), so a skin bound far out keeps its precision in float accessors; each joint's
// global is the instance's placement times the mesh's move from posed coordinates (E) times
// the joint's own, G' = E · G, so Σ w · G'(t) · IBM · T(B) · (p − B) = E · p'(t).
void appendDeformedBatch(tinygltf::Model& model, const Scene& scene, const MeshBatch& batch,
                         const MeshDeformation& deformation, AnimationWriter& animations) {
    const Mesh& mesh = scene.meshes[batch.mesh];
    const Material* material = scene.materialOf(mesh);
    core::Aabb bindBox;
    for (const glm::vec3& p : deformation.bindPositions) bindBox.extend(core::Vec3(p));
    const glm::dvec3 centre = deformation.skinned() ? glm::dvec3(bindBox.center()) : glm::dvec3(0.0);
    BakedBatch bind{mesh.vertices, mesh.indices};
    // The loader turned the triangles a mirroring pose (at t = 0, export's) or a mirroring node
    // mirrors; a reader turns them again: written as bound.
    std::vector<glm::dvec3> normals;
    std::vector<bool> mirrored;
    deformation.posedPositions(0.0, normals, &mirrored);
    const bool nodeMirrors =
        !deformation.skinned() && !batch.worldFromObject.empty() &&
        glm::determinant(glm::dmat3(glm::dmat4(batch.worldFromObject[0]) * deformation.meshFromPosed)) < 0.0;
    for (size_t i = 0; i + 2 < bind.indices.size(); i += 3) {
        const auto flips = [&](uint32_t v) { return v < mirrored.size() && mirrored[v] ? 1 : 0; };
        const bool poseMirrors = flips(bind.indices[i]) + flips(bind.indices[i + 1]) + flips(bind.indices[i + 2]) >= 2;
        if (poseMirrors != nodeMirrors) std::swap(bind.indices[i + 1], bind.indices[i + 2]);
    }
    for (size_t v = 0; v < bind.vertices.size() && v < deformation.bindPositions.size(); ++v) {
        bind.vertices[v].position = glm::vec3(glm::dvec3(deformation.bindPositions[v]) - centre);
        bind.vertices[v].normal = deformation.bindNormals[v];
    }
    std::map<std::string, int> attributes = appendAttributes(model, bind, material);
    const size_t n = bind.vertices.size();
    const auto floats = [&model](const std::vector<float>& data, int type, size_t count) {
        return appendAccessor(model,
                              appendBufferView(model, std::span<const float>(data), TINYGLTF_TARGET_ARRAY_BUFFER),
                              TINYGLTF_COMPONENT_TYPE_FLOAT, type, count);
    };
    std::vector<std::map<std::string, int>> targets;
    for (const MorphTarget& t : deformation.targets) {
        std::map<std::string, int> target;
        for (const auto& [name, moves] : {std::pair{"POSITION", &t.positions}, std::pair{"NORMAL", &t.normals}}) {
            if (moves->empty()) continue;
            std::vector<float> data(3 * n, 0.0f);
            for (size_t v = 0; v < std::min(n, moves->size()); ++v)
                for (int c = 0; c < 3; ++c) data[3 * v + size_t(c)] = (*moves)[v][c];
            target[name] = floats(data, TINYGLTF_TYPE_VEC3, n);
        }
        targets.push_back(std::move(target));
    }
    if (deformation.skinned()) {
        // Four influences a set, as many sets as the most-influenced vertex needs.
        size_t most = 0;
        for (size_t v = 0; v + 1 < deformation.firstInfluence.size(); ++v)
            most = std::max<size_t>(most, deformation.firstInfluence[v + 1] - deformation.firstInfluence[v]);
        for (size_t set = 0; set * 4 < most; ++set) {
            std::vector<uint16_t> joints(4 * n, 0);
            std::vector<float> weights(4 * n, 0.0f);
            for (size_t v = 0; v < n && v + 1 < deformation.firstInfluence.size(); ++v)
                for (uint32_t i = deformation.firstInfluence[v] + uint32_t(4 * set), k = 0;
                     i < deformation.firstInfluence[v + 1] && k < 4; ++i, ++k) {
                    joints[4 * v + k] = uint16_t(deformation.influences[i].joint);
                    weights[4 * v + k] = float(deformation.influences[i].weight);
                }
            attributes["JOINTS_" + std::to_string(set)] = appendAccessor(
                model, appendBufferView(model, std::span<const uint16_t>(joints), TINYGLTF_TARGET_ARRAY_BUFFER),
                TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC4, n);
            attributes["WEIGHTS_" + std::to_string(set)] = floats(weights, TINYGLTF_TYPE_VEC4, n);
        }
    }
    const int meshIndex = appendMesh(model, mesh.name, attributes, bind.indices, material ? mesh.material : -1);
    tinygltf::Mesh& written = model.meshes[size_t(meshIndex)];
    written.primitives[0].targets = std::move(targets);
    for (size_t k = 0; k < deformation.targets.size(); ++k)
        written.weights.push_back(k < deformation.weights.size() ? deformation.weights[k] : 0.0);
    std::vector<int> children;
    for (const glm::mat4& placed : batch.worldFromObject) {
        const glm::dmat4 e = glm::dmat4(placed) * deformation.meshFromPosed;
        tinygltf::Node node;
        node.mesh = meshIndex;
        if (deformation.skinned()) {
            tinygltf::Skin skin;
            std::vector<float> inverseBind;
            for (size_t j = 0; j < deformation.joints.size(); ++j) {
                NodeMotion joint = deformation.joints[j];
                joint.sceneFromRoot = e * joint.sceneFromRoot;
                const int jointNode = int(model.nodes.size()); // appendMotion's first node: the joint's own
                children.push_back(animations.appendMotion(joint, -1));
                model.nodes[size_t(jointNode)].name = "joint " + std::to_string(j); // named: never an empty node
                skin.joints.push_back(jointNode);
                const glm::dmat4 ibm = deformation.inverseBind[j] * glm::translate(glm::dmat4(1.0), centre);
                for (int c = 0; c < 16; ++c) inverseBind.push_back(float(ibm[c / 4][c % 4])); // column-major
            }
            skin.inverseBindMatrices = floats(inverseBind, TINYGLTF_TYPE_MAT4, deformation.joints.size());
            model.skins.push_back(std::move(skin));
            node.skin = int(model.skins.size() - 1);
        } else if (e != glm::dmat4(1.0)) {
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) node.matrix.push_back(e[c][r]); // column-major, as glTF
        }
        model.nodes.push_back(std::move(node));
        children.push_back(int(model.nodes.size() - 1));
        animations.appendWeights(children.back(), deformation.weightKeys);
    }
    model.scenes[0].nodes.push_back(appendNode(model, -1, mesh.name, glm::mat4(1.0f), std::move(children)));
}

} // namespace

core::Status exportGlb(const Scene& scene, const fs::path& file) {
    if (const uint64_t bytes = geometryBytes(scene); bytes > kGlbMaxBytes) return tooLarge(file, bytes);
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "shadowkit export";
    model.buffers.emplace_back();
    model.scenes.emplace_back();
    model.defaultScene = 0;
    if (core::Status s = addMaterials(scene, model); !s) return core::makeError(file.string() + ": " + s.error());
    // A file's animations go back with the instances they move, and a forest's circling movers
    // as keys sampled round their circles (circleAsKeys), one animation each.
    std::vector<std::map<size_t, const NodeMotion*>> moving(scene.batches.size());
    std::deque<NodeMotion> circles; // fixed addresses for `moving`
    for (const Track& track : scene.tracks) {
        if (track.keyframed) {
            moving[track.batch][track.instance] = &*track.keyframed;
        } else if (std::optional<NodeMotion> keys = circleAsKeys(track, scene)) {
            circles.push_back(std::move(*keys));
            moving[track.batch][track.instance] = &circles.back();
        }
    }
    AnimationWriter animations(model, [&model](const std::vector<float>& data, int type, size_t count,
                                               std::vector<double> min, std::vector<double> max) {
        return appendAccessor(model, appendBufferView(model, std::span<const float>(data), 0),
                              TINYGLTF_COMPONENT_TYPE_FLOAT, type, count, std::move(min), std::move(max));
    });
    std::map<size_t, const MeshDeformation*> deformed; // by batch
    for (const MeshDeformation& deformation : scene.deformations) deformed[deformation.batch] = &deformation;
    for (size_t b = 0; b < scene.batches.size(); ++b) {
        if (const auto d = deformed.find(b); d != deformed.end())
            appendDeformedBatch(model, scene, scene.batches[b], *d->second, animations);
        else
            appendBatch(model, scene, scene.batches[b], moving[b], animations);
    }
    animations.finish();
    for (int node : writeViewpoints(scene, model)) model.scenes[0].nodes.push_back(node);
    if (scene.wsOrigin != core::Vec3(0.0)) { // the batches under a node that stands them where the scene stands
        tinygltf::Node origin;
        origin.name = "scene origin";
        origin.translation = {scene.wsOrigin.x, scene.wsOrigin.y, scene.wsOrigin.z}; // double, as JSON keeps it
        origin.children = std::move(model.scenes[0].nodes);
        model.nodes.push_back(std::move(origin));
        model.scenes[0].nodes = {int(model.nodes.size() - 1)};
    }
    tinygltf::TinyGLTF writer;
    std::ostringstream glb;
    if (!writer.WriteGltfSceneToStream(&model, glb, false, true))
        return core::makeError(file.string() + ": cannot encode glTF");
    if (glb.view().size() > kGlbMaxBytes) return tooLarge(file, glb.view().size());
    return writeFile(file, glb.view());
}

} // namespace shadowkit::scene::formats
