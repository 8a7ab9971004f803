// glTF 2.0 import (.gltf, .glb) through tinygltf: nodes become instances of their mesh.
//
// tinygltf parses the file; everything it leaves to the caller is read here with the rules of
// the glTF 2.0 specification (§3.6 accessors, §3.7.2.1 primitive modes), checked against the
// buffers so that no file can make us read outside them:
//   - component types of every size, normalized signed integers as max(c / (2^(n−1) − 1), −1)
//     and unsigned as c / (2^n − 1) (KHR_mesh_quantization's positions, normals and colours);
//   - sparse accessors: the base values (zeros without a buffer view), then the listed ones;
//   - triangle lists, strips and fans (strips and fans unrolled into lists);
//   - the materials a placed primitive uses (§3.9, gltf_materials.cpp): base colour factor and
//     texture with its TEXCOORD set and sampler, KHR_texture_transform applied to the uvs,
//     alpha mode and cutoff, double-sidedness;
//   - images (§3.8.4, gltf_materials.cpp): PNG, JPEG and WebP (EXT_texture_webp), embedded
//     (buffer view or data URI) or external (tinygltf decodes percent-encoded URIs), decoded by
//     scene::decodeImage within its limits; a buffer view's bytes are checked against its
//     buffer before they are read (tinygltf does not check them). A texture's sources are tried
//     in order — the WebP extension's, the core PNG/JPEG fallback, KHR_texture_basisu's (KTX2,
//     which no Debian library decodes, so it fails with its name);
//   - a texture that cannot be read (missing, corrupt, KTX2 only) matters only where the
//     material's alpha does: on an OPAQUE material it is dropped with one warning in
//     Scene::warnings (shadows never read an opaque colour), on MASK and BLEND it is an error;
//   - the default scene's nodes (scene 0's where the file names none), each placed once (a
//     listed node that is a child stands as a root, with a warning); a file with no scene at
//     all places every root node, with a warning (sceneRoots, gltf_nodes.cpp, after
//     checkNodeTrees has checked that the nodes form trees);
//   - nodes' transforms composed in double, and the scene stood where float keeps its
//     precision (near_origin.cpp): a model in survey metres keeps its millimetres;
//   - nodes instancing their mesh (EXT_mesh_gpu_instancing, gltfpack -mi): one instance each;
//   - morph targets at their weights, then skinned meshes posed by their joints (gltf_pose.cpp,
//     deformation.h), as the file's animations pose them at LoadOptions::poseSeconds (the rest
//     pose where none moves them);
//   - animations (§3.11, gltf_animation.cpp): an instance below a node that an animation's
//     translation, rotation or scale moves (a skin's joint among them) is a Scene::tracks entry
//     of a dynamic batch, and a mesh whose skin's joints or morph weights they move a
//     Scene::deformations entry; scene::animate plays both; the scene as loaded stands at
//     LoadOptions::poseSeconds;
//   - meshopt-compressed buffer views (EXT_meshopt_compression, gltfpack -c) decoded before any
//     accessor reads them (gltf_meshopt.cpp);
//   - what cannot be read is named: glTF 1.0, Draco-compressed meshes, non-finite positions;
//   - the file and every file it names are read through scene::readFile (regular files only,
//     within its limit): a URI naming a directory or a pipe is refused in one line.
#include "gltf_accessor.h"
#include "gltf_animation.h"
#include "gltf_instancing.h"
#include "gltf_materials.h"
#include "gltf_meshopt.h"
#include "gltf_nodes.h"
#include "gltf_pose.h"
#include "gltf_transmission.h"
#include "gltf_viewpoints.h"
#include "scene_formats.h"

#include "shadowkit/scene/animation.h"
#include "shadowkit/scene/file_read.h"

#include <tiny_gltf.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <optional>
#include <string_view>
#include <system_error>
#include <tuple>
#include <unordered_map>
#include <utility>

namespace shadowkit::scene::formats {

namespace fs = std::filesystem;

namespace {

// Draco-compressed geometry, refused by name: Debian 12 ships a decoder (libdraco 1.5.5), but it is not
// among the project's dependencies (DESIGN.md), and no issue has named it.
constexpr const char* kDraco = "KHR_draco_mesh_compression";
core::Error dracoCompressed(const std::string& subject) {
    return core::makeError(subject + " (" + kDraco + "), which shadowkit cannot read: export it uncompressed");
}

// Whether shadows can ignore a required extension shadowkit does not read: those that only shade
// (materials, lights, shader techniques) and those read elsewhere (textures: gltf_materials.cpp;
// meshopt: gltf_meshopt.cpp; node visibility: gltf_nodes.cpp; Draco: refused by name). glTF 2.0 (§3.12) lets a loader
// refuse a file whose required extension it lacks; shadowkit loads what it can and names the rest in a warning, since
// the shapes such an extension describes may be missing.
bool knownOrShadingOnly(const std::string& extension) {
    for (const char* prefix : {"KHR_materials_", "KHR_texture_", "EXT_texture_", "KHR_lights_", "KHR_technique"})
        if (extension.starts_with(prefix)) return true;
    for (const char* known : {"KHR_mesh_quantization", "EXT_meshopt_compression", "KHR_meshopt_compression",
                              kInstancing, kDraco, kNodeVisibility})
        if (extension == known) return true;
    return false;
}

// The triangle list of a primitive's vertex sequence (indices or 0, 1, 2, ...) in its mode.
std::vector<uint32_t> triangleList(int mode, const std::vector<uint32_t>& sequence) {
    if (mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        std::vector<uint32_t> list = sequence;
        list.resize(list.size() / 3 * 3);
        return list;
    }
    std::vector<uint32_t> list;
    for (size_t i = 0; i + 2 < sequence.size(); ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_FAN)
            list.insert(list.end(), {sequence[i + 1], sequence[i + 2], sequence[0]});
        else if (i % 2 == 0)
            list.insert(list.end(), {sequence[i], sequence[i + 1], sequence[i + 2]});
        else
            list.insert(list.end(), {sequence[i], sequence[i + 2], sequence[i + 1]}); // keeps the winding
    }
    return list;
}

// A primitive this much of whose triangles wind against their normals is said to be inside out.
constexpr double kWoundInsideOut = 0.9;

// The share of a mesh's triangles with area whose winding turns against the normals the file
// gives their corners: glTF's front faces wind counter-clockwise about their outward side.
double shareWoundAgainstNormals(const Mesh& mesh) {
    size_t counted = 0, against = 0;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const Vertex &a = mesh.vertices[mesh.indices[t]], &b = mesh.vertices[mesh.indices[t + 1]],
                     &c = mesh.vertices[mesh.indices[t + 2]];
        const glm::vec3 wound = glm::cross(b.position - a.position, c.position - a.position);
        const float agreement = glm::dot(wound, a.normal + b.normal + c.normal);
        if (agreement == 0.0f) continue; // no area, or normals across it
        ++counted;
        against += agreement < 0.0f;
    }
    return counted == 0 ? 0.0 : double(against) / double(counted);
}

// Converts one primitive: an empty mesh for primitives that are not triangles (points,
// lines) or have no positions, an error for what is wrong or cannot be read. Texture
// coordinates an OPAQUE material reads but the primitive lacks are a warning (its texture
// colours, it never cuts holes), as an unreadable texture is.
core::Result<Mesh> convertPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                    const std::string& where, std::vector<std::string>& warnings) {
    Mesh mesh;
    if (prim.extensions.count(kDraco)) return dracoCompressed(where + " is Draco-compressed");
    const int mode = prim.mode == -1 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN)
        return mesh;
    const auto pos = prim.attributes.find("POSITION");
    if (pos == prim.attributes.end()) return mesh;
    auto positions = AccessorReader::open(model, pos->second, where + " POSITION");
    if (!positions) return positions.errorInfo();
    glm::vec3 albedo(0.7f);
    const tinygltf::Material* material = nullptr;
    if (prim.material >= 0 && size_t(prim.material) < model.materials.size()) {
        material = &model.materials[size_t(prim.material)];
        mesh.material = prim.material;
        const auto& f = material->pbrMetallicRoughness.baseColorFactor;
        if (f.size() >= 3) albedo = glm::vec3(float(f[0]), float(f[1]), float(f[2]));
    }
    mesh.vertices.resize(positions->count());
    for (size_t i = 0; i < positions->count(); ++i) {
        const glm::vec3 p(positions->read(i));
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return core::makeError(where + ": position " + std::to_string(i) + " is not finite");
        mesh.vertices[i] = {p, glm::vec3(0, 1, 0), albedo};
    }
    if (const auto c = prim.attributes.find("COLOR_0"); c != prim.attributes.end()) {
        auto colors = AccessorReader::open(model, c->second, where + " COLOR_0");
        if (!colors) return colors.errorInfo();
        float leastAlpha = 1.0f;
        for (size_t i = 0; i < std::min(colors->count(), mesh.vertices.size()); ++i) {
            const glm::vec4 colour = colors->read(i, glm::vec4(1.0f));
            mesh.vertices[i].albedo = albedo * glm::vec3(colour);
            leastAlpha = std::min(leastAlpha, colour.a);
        }
        // glTF's alpha is factor × texture × COLOR_0's (§3.9.2); the vertices keep no alpha, so
        // a mask that the vertex colours cut would cast whole where they cut it: say so.
        if (material && (material->alphaMode == "MASK" || material->alphaMode == "BLEND") &&
            leastAlpha < float(material->alphaCutoff)) {
            char figures[80];
            std::snprintf(figures, sizeof figures, "falls to %.3g, under its material's cutoff %.3g", leastAlpha,
                          material->alphaCutoff);
            warnings.push_back(where + ": its COLOR_0 alpha " + figures +
                               ", which shadowkit does not read: it is cut by its texture and factor alone");
        }
    }
    if (const std::optional<TextureUse> cut = material ? cuttingTexture(model, *material) : std::nullopt) {
        // The texture's coordinates, with KHR_texture_transform applied once here.
        const tinygltf::TextureInfo& info = cut->info;
        const std::string set = "TEXCOORD_" + std::to_string(info.texCoord);
        const auto t = prim.attributes.find(set);
        const std::string missing =
            where + ": its material's " + cut->label + " reads " + set + ", which the primitive does not have";
        const bool opaque = material->alphaMode != "MASK" && material->alphaMode != "BLEND";
        if (t == prim.attributes.end() && !opaque) return core::makeError(missing);
        if (t == prim.attributes.end()) {
            warnings.push_back(missing + "; its texture's first texel is read all over it");
        } else {
            auto uvs = AccessorReader::open(model, t->second, where + " " + set);
            if (!uvs) return uvs.errorInfo();
            const std::optional<glm::mat3> transform = textureTransform(info);
            for (size_t i = 0; i < std::min(uvs->count(), mesh.vertices.size()); ++i) {
                glm::vec2 uv(uvs->read(i));
                if (transform) uv = glm::vec2(*transform * glm::vec3(uv, 1.0f));
                mesh.vertices[i].uv = std::isfinite(uv.x) && std::isfinite(uv.y) ? uv : glm::vec2(0.0f);
            }
        }
    }
    std::vector<uint32_t> sequence;
    if (prim.indices >= 0) {
        auto indices = AccessorReader::open(model, prim.indices, where + " indices");
        if (!indices) return indices.errorInfo();
        sequence.resize(indices->count());
        for (size_t i = 0; i < indices->count(); ++i) {
            const double index = indices->get(i, 0);
            if (!(index >= 0.0 && index < double(mesh.vertices.size())))
                return core::makeError(where + ": index " + std::to_string(i) + " names no vertex");
            sequence[i] = uint32_t(index);
        }
    } else {
        sequence.resize(mesh.vertices.size());
        for (size_t i = 0; i < sequence.size(); ++i) sequence[i] = uint32_t(i);
    }
    mesh.indices = triangleList(mode, sequence);
    if (const auto n = prim.attributes.find("NORMAL"); n != prim.attributes.end()) {
        auto normals = AccessorReader::open(model, n->second, where + " NORMAL");
        if (!normals) return normals.errorInfo();
        for (size_t i = 0; i < std::min(normals->count(), mesh.vertices.size()); ++i) {
            const glm::vec3 normal(normals->read(i));
            const float length = glm::length(normal);
            mesh.vertices[i].normal = length > 0.0f && std::isfinite(length) ? normal / length : glm::vec3(0, 1, 0);
        }
        // Single-sided and wound inside out (a Blender test file, every triangle): it is drawn
        // from inside, as any glTF viewer draws it, while the truth's rays meet its outside, so
        // eval compares almost none of its pixels — worth a word at load.
        if (!(material && material->doubleSided))
            if (const double against = shareWoundAgainstNormals(mesh); against >= kWoundInsideOut)
                warnings.push_back(where + ": " + std::to_string(int(std::lround(100.0 * against))) +
                                   " % of its triangles wind clockwise about the normals it gives them (glTF's "
                                   "front faces wind counter-clockwise): single-sided, it is drawn inside out");
    } else {
        computeNormals(mesh);
    }
    mesh.computeBounds();
    return mesh;
}

// The next character after `key` and its colon that is not white space, or 0.
char valueStart(const std::string& text, size_t key) {
    const size_t colon = text.find(':', key);
    const size_t value = colon == std::string::npos ? colon : text.find_first_not_of(" \t\r\n", colon + 1);
    return value == std::string::npos ? '\0' : text[value];
}

// Whether a file is glTF 1.0, checked before tinygltf (which takes a 1.0 file for a 2.0 one with
// nothing in it): the glb header's version; in JSON, asset.version "1..." or, since 1.0 made the
// asset optional, "meshes" as an object (2.0 has arrays). Looks at the first MiB of JSON at most.
bool isGltf1(std::string_view bytes, bool binary) {
    if (binary) {
        uint32_t version = 0;
        if (bytes.size() >= 8) std::memcpy(&version, bytes.data() + 4, 4);
        return bytes.size() >= 8 && bytes.substr(0, 4) == "glTF" && version == 1;
    }
    const std::string text(bytes.substr(0, size_t(1) << 20));
    if (const size_t meshes = text.find("\"meshes\""); meshes != std::string::npos && valueStart(text, meshes) == '{')
        return true;
    const size_t asset = text.find("\"asset\"");
    const size_t version = asset == std::string::npos ? asset : text.find("\"version\"", asset);
    if (version == std::string::npos || valueStart(text, version) != '"') return false;
    const size_t quote = text.find('"', text.find(':', version));
    return text.compare(quote + 1, 1, "1") == 0;
}

// The file system tinygltf reads a file's external buffers and images through: readFile's
// (file_read.h), not tinygltf's own, which asks a directory for 2^63 bytes and waits on a pipe
// (a URI of "textures/" names a directory beside the file). The reason a file is refused goes
// into tinygltf's message ("File read error : PATH : REASON") and into `images`' refusedFiles.
tinygltf::FsCallbacks guardedFileSystem(ImageContext& images) {
    tinygltf::FsCallbacks callbacks{};
    callbacks.FileExists = [](const std::string& path, void*) {
        std::error_code ec;
        return fs::exists(path, ec); // a directory or pipe too, so that the read says what it is
    };
    callbacks.ExpandFilePath = &tinygltf::ExpandFilePath; // tinygltf 2.7's: the path as written
    callbacks.ReadWholeFile = [](std::vector<unsigned char>* out, std::string* err, const std::string& path,
                                 void* context) {
        auto bytes = readFile(path);
        if (!bytes) {
            const std::string& message = bytes.error(); // "PATH: WHY"
            static_cast<ImageContext*>(context)->refusedFiles[path] =
                message.starts_with(path + ": ") ? message.substr(path.size() + 2) : message;
            if (err) *err += message;
            return false;
        }
        out->assign(bytes->begin(), bytes->end());
        return true;
    };
    callbacks.WriteWholeFile = &tinygltf::WriteWholeFile; // never called: the loader writes nothing
    callbacks.user_data = &images;
    return callbacks;
}

} // namespace

core::Result<const unsigned char*> bytesOf(const tinygltf::Model& model, int viewIndex, size_t offset, size_t count,
                                           size_t elementSize, size_t stride, const std::string& what) {
    if (viewIndex < 0 || size_t(viewIndex) >= model.bufferViews.size())
        return core::makeError(what + ": no such buffer view");
    const tinygltf::BufferView& view = model.bufferViews[size_t(viewIndex)];
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
        return core::makeError(what + ": no such buffer");
    const std::vector<unsigned char>& buffer = model.buffers[size_t(view.buffer)].data;
    const size_t span = count == 0 ? 0 : (count - 1) * stride + elementSize;
    if (offset > view.byteLength || span > view.byteLength - offset || view.byteOffset > buffer.size() ||
        view.byteLength > buffer.size() - view.byteOffset)
        return core::makeError(what + ": reaches past its buffer");
    return buffer.data() + view.byteOffset + offset;
}

// How deep the placed hierarchy may go: a chain of nodes as long as the file is walked no
// deeper (checkNodeTrees has already refused loops and second parents).
constexpr int kMaxNodeDepth = 512;

core::Result<Scene> loadGltf(const fs::path& file, double poseSeconds) {
    const bool binary = lowerExtension(file) == ".glb";
    auto bytes = readFile(file);
    if (!bytes) return bytes.errorInfo();
    if (bytes->empty()) return core::makeError(file.string() + ": an empty file, not glTF");
    if (isGltf1(*bytes, binary)) return core::makeError(file.string() + ": glTF 1.0 is not supported; glTF 2.0 is");
    tinygltf::TinyGLTF loader;
    ImageContext images{file.string(), {}, {}};
    loader.SetFsCallbacks(guardedFileSystem(images));
    loader.SetImageLoader(loadImage, &images);
    tinygltf::Model model;
    std::string err, warn;
    // tinygltf's own base directory rule (GetBaseDir): the file's name up to its last slash.
    const std::string baseDir = file.parent_path().string();
    // A file with meshopt-compressed views is parsed with its placeholder buffers given a byte of data.
    std::optional<MeshoptFile> meshopt = prepareMeshopt(*bytes, binary);
    const std::string_view parsed = meshopt ? std::string_view(meshopt->bytes) : std::string_view(*bytes);
    const auto length = static_cast<unsigned int>(parsed.size()); // within readFile's 32-bit limit
    const bool ok =
        binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(parsed.data()),
                                             length, baseDir)
               : loader.LoadASCIIFromString(&model, &err, &warn, parsed.data(), length, baseDir);
    // tinygltf refuses a Draco file's accessors without buffer views before any primitive is
    // seen; the extension lists it parsed first say why. (A Draco primitive in a file that loads
    // is named by convertPrimitive.)
    const auto lists = [&](const std::vector<std::string>& names) {
        return std::find(names.begin(), names.end(), kDraco) != names.end();
    };
    if (!ok && (lists(model.extensionsRequired) || lists(model.extensionsUsed)))
        return dracoCompressed(file.string() + ": its meshes are Draco-compressed");
    if (!ok) {
        std::replace(err.begin(), err.end(), '\n', ' ');
        while (!err.empty() && err.back() == ' ') err.pop_back();
        // tinygltf refuses some objects missing a required property (a skin without `joints`)
        // without a word: say at least where to look.
        if (err.empty()) err = "an object lacks a property glTF requires; the glTF Validator names it";
        return core::makeError(file.string() + ": not a readable glTF file (" + err + ")");
    }
    // tinygltf holds its own copy of every buffer: the file's bytes go before the meshes are
    // built (an 81 MB .glb of 4.5 M triangles peaked at 370 MB held, 291 MB without them).
    std::string().swap(*bytes);
    if (meshopt) std::string().swap(meshopt->bytes);
    auto trees = checkNodeTrees(model, file);
    if (!trees) return trees.errorInfo();
    if (auto transforms = checkNodeTransforms(model, file); !transforms) return transforms.errorInfo();
    if (meshopt)
        if (auto s = decodeMeshoptViews(model, meshopt->placeholders, file.string()); !s) return s.errorInfo();
    Scene scene;
    for (const std::string& extension : model.extensionsRequired)
        if (!knownOrShadingOnly(extension))
            scene.warnings.push_back(file.string() + ": it requires " + printable(extension) +
                                     ", which shadowkit does not read: what it describes is left out");
    warnOfNodeRotations(model, file, scene.warnings);
    const std::vector<int> roots = sceneRoots(model, *trees, file, scene.warnings);
    if (auto s = readMaterials(model, file, images, materialsPlaced(model, roots), scene); !s) return s.errorInfo();
    // (mesh, primitive) -> batch index: a mesh placed by many nodes becomes one instanced batch.
    // A batch per mesh primitive and handedness: glTF reverses the winding of a node whose
    // transform has a negative determinant (a mirror), so its instances get the primitive with
    // each triangle reversed, and every instance transform of a batch keeps the winding's sense.
    // Skinned meshes are posed per skin: a batch per mesh primitive, handedness and skin (-1: none).
    // A node with morph weights of its own gets batches of its own too (the last: its index, else -1).
    // An instance that an animation moves (its node or one above it) gets batches of its own, dynamic.
    std::map<std::tuple<int, size_t, bool, int, int, bool>, size_t> batchOf;
    const FileAnimations animations = readAnimations(model, *trees, file.string(), scene.warnings);
    poseNodes(model, animations.posed, poseSeconds); // joints and weights, before anything reads the nodes
    // Every node an animation moves: a rigid instance below a skin's joint follows it too.
    AnimatedNodes animated = animations.played;
    animated.insert(animations.posed.joints.begin(), animations.posed.joints.end());
    std::vector<int> path;              // the nodes from the root down to the one visited
    std::map<int, SkinJoints> jointsOf; // each skin's, read when a mesh first needs them
    std::optional<core::Error> failure;
    size_t instancesPlaced = 0; // by EXT_mesh_gpu_instancing
    // Each batch's placements in the file's coordinates, in double until placeNearOrigin; a
    // skinned batch is placed at its posed vertices' anchor (applySkin), every other at its nodes.
    std::vector<std::vector<glm::dmat4>> placements;
    std::map<size_t, glm::dvec3> skinnedAt;
    size_t meshNodesVisited = 0;                 // nodes of the scene that place a mesh, drawable or not
    size_t hiddenNodes = 0, hiddenMeshNodes = 0; // KHR_node_visibility: hidden here, and the mesh nodes at or below
    auto visit = [&](auto&& self, int nodeIndex, const glm::dmat4& parent, int depth, bool visible) -> void {
        if (failure || nodeIndex < 0 || size_t(nodeIndex) >= model.nodes.size()) return; // a bad root is skipped
        if (depth > kMaxNodeDepth) {
            failure = core::makeError(file.string() + ": the node hierarchy is deeper than " +
                                      std::to_string(kMaxNodeDepth) + " levels");
            return;
        }
        const tinygltf::Node& node = model.nodes[size_t(nodeIndex)];
        const glm::dmat4 world = parent * nodeLocalMatrix(node);
        path.push_back(nodeIndex);
        if (!core::isFinite(glm::dmat4(glm::mat4(world)))) { // as float too: the renderer's
            failure = core::makeError(file.string() + ": node " + std::to_string(nodeIndex) + " '" +
                                      printable(node.name) + "' has a non-finite transform");
            return;
        }
        if (visible && hiddenByItself(node)) visible = false, ++hiddenNodes;
        readNodeViewpoints(model, nodeIndex, world, file.string(), visible, scene);
        if (!visible && node.mesh >= 0) ++hiddenMeshNodes; // nothing to draw or cast, as the file means
        if (visible && node.mesh >= 0 && size_t(node.mesh) < model.meshes.size()) {
            ++meshNodesVisited;
            const tinygltf::Mesh& gltfMesh = model.meshes[size_t(node.mesh)];
            const std::string nodeName = file.string() + ": node " + std::to_string(nodeIndex) +
                                         (node.name.empty() ? "" : " '" + printable(node.name) + "'");
            // A skinned mesh is placed by its joints alone: its node's transform is ignored (deformation.h).
            const int skin = node.skin >= 0 && size_t(node.skin) < model.skins.size() ? node.skin : -1;
            const auto weightKeys = animations.posed.weights.find(nodeIndex);
            const bool deformedOverTime =
                animations.posed.skins.count(skin) > 0 || weightKeys != animations.posed.weights.end();
            if (skin >= 0 && !jointsOf.count(skin)) {
                auto joints = readSkinJoints(model, *trees, skin, animated, poseSeconds, file.string());
                if (!joints) {
                    failure = joints.errorInfo();
                    return;
                }
                jointsOf.emplace(skin, std::move(*joints));
            }
            // A moving instance's placement is its motion at rest times what lies below its node
            // (a GPU-instancing transform): the motion replaces the first factor at every t.
            const std::optional<NodeMotion> motion = skin >= 0 ? std::nullopt : motionAlong(model, path, animated);
            const auto transforms = skin >= 0 ? std::vector<glm::dmat4>{glm::dmat4(1.0)}
                                              : instanceTransforms(model, node, motion ? glm::dmat4(1.0) : world,
                                                                   nodeName, instancesPlaced);
            if (!transforms) {
                failure = transforms.errorInfo();
                return;
            }
            for (const glm::dmat4& below : *transforms) {
                const glm::dmat4 transform = motion ? world * below : below;
                const bool mirrored = glm::determinant(glm::dmat3(transform)) < 0.0;
                for (size_t p = 0; p < gltfMesh.primitives.size(); ++p) {
                    auto [it, inserted] = batchOf.try_emplace(
                        {node.mesh, p, mirrored, skin, node.weights.empty() ? -1 : nodeIndex, motion.has_value()},
                        scene.batches.size());
                    if (inserted) {
                        const std::string named = gltfMesh.name.empty() ? "" : " '" + printable(gltfMesh.name) + "'";
                        const std::string where = file.string() + ": mesh " + std::to_string(node.mesh) + named +
                                                  " primitive " + std::to_string(p);
                        core::Result<Mesh> mesh =
                            convertPrimitive(model, gltfMesh.primitives[p], where, scene.warnings);
                        if (!mesh) {
                            failure = mesh.errorInfo();
                            return;
                        }
                        if (mesh->indices.empty()) { // not triangles: nothing to draw or cast
                            batchOf.erase(it);
                            continue;
                        }
                        const std::vector<double>& weights = node.weights.empty() ? gltfMesh.weights : node.weights;
                        const bool morphed =
                            std::any_of(weights.begin(), weights.end(), [](double w) { return w != 0.0; });
                        std::optional<MeshDeformation> deformation;
                        if (skin >= 0 || morphed || deformedOverTime) {
                            auto read = readDeformation(model, gltfMesh.primitives[p], *mesh, weights,
                                                        weightKeys == animations.posed.weights.end()
                                                            ? decltype(weightKeys->second){}
                                                            : weightKeys->second,
                                                        skin >= 0 ? &jointsOf.at(skin) : nullptr, where);
                            if (!read) {
                                failure = read.errorInfo();
                                return;
                            }
                            glm::dvec3 anchor(0.0);
                            if (auto posed = poseAtLoad(*read, poseSeconds, *mesh, anchor, where); !posed) {
                                failure = posed.errorInfo();
                                return;
                            }
                            if (skin >= 0) skinnedAt[it->second] = anchor;
                            if (deformedOverTime) deformation = std::move(*read);
                        }
                        if (mirrored) // counter-clockwise again once the mirror has turned it
                            for (size_t t = 0; t + 2 < mesh->indices.size(); t += 3)
                                std::swap(mesh->indices[t + 1], mesh->indices[t + 2]);
                        mesh->name = gltfMesh.name;
                        scene.meshes.push_back(std::move(*mesh));
                        scene.batches.push_back(
                            {uint32_t(scene.meshes.size() - 1), {}, motion.has_value() || deformation.has_value()});
                        if (deformation) {
                            deformation->batch = uint32_t(scene.batches.size() - 1);
                            scene.deformations.push_back(std::move(*deformation));
                        }
                        placements.emplace_back();
                    }
                    const auto skinned = skinnedAt.find(it->second);
                    placements[it->second].push_back(
                        skinned == skinnedAt.end() ? transform : glm::translate(glm::dmat4(1.0), skinned->second));
                    if (motion) {
                        Track track;
                        track.batch = uint32_t(it->second);
                        track.instance = uint32_t(placements[it->second].size() - 1);
                        track.keyframed = motion;
                        track.keyframed->nodeFromObject = below;
                        scene.tracks.push_back(std::move(track));
                    }
                }
            }
        }
        for (int child : node.children) self(self, child, world, depth + 1, visible);
        path.pop_back();
    };
    for (int root : roots) visit(visit, root, glm::dmat4(1.0), 0, true);
    if (failure) return *failure;
    if (hiddenNodes > 0)
        scene.warnings.push_back(
            file.string() + ": " + std::to_string(hiddenNodes) + (hiddenNodes == 1 ? " node is" : " nodes are") +
            " hidden (KHR_node_visibility), with everything below: " + std::to_string(hiddenMeshNodes) +
            (hiddenMeshNodes == 1 ? " mesh" : " meshes") + " left out, neither drawn nor casting");
    placeNearOrigin(scene, placements);
    placeViewpoints(scene);
    animate(scene, poseSeconds); // a moving instance stands where its keys put it then, a deformed mesh as posed
    if (scene.triangleCount() == 0) {
        // Say which it is: meshes the scene hides or never places, or none that are triangles.
        if (meshNodesVisited == 0 && hiddenMeshNodes > 0)
            return core::makeError(file.string() + ": every mesh it places is hidden (KHR_node_visibility)");
        if (meshNodesVisited == 0 && !model.meshes.empty()) {
            const std::string ofScene = model.scenes.empty() ? "" : " of its scene";
            return core::makeError(file.string() + ": " +
                                   (model.meshes.size() == 1 ? "its mesh is placed by no node" + ofScene
                                                             : "none of its " + std::to_string(model.meshes.size()) +
                                                                   " meshes is placed by a node" + ofScene));
        }
        // An animation library (a character's clips exported one to a file, as PlayCanvas's
        // and Mixamo's are): its nodes are another file's skeleton.
        if (model.meshes.empty())
            return core::makeError(
                file.string() + ": it holds no mesh" +
                (model.animations.empty()
                     ? std::string()
                     : ", only " +
                           (model.animations.size() == 1 ? std::string("an animation")
                                                         : std::to_string(model.animations.size()) + " animations") +
                           " (clips for another file's model; shadowkit plays a file's animations on its own meshes)"));
        return core::makeError(file.string() + ": glTF file holds no triangle meshes");
    }
    return scene;
}

} // namespace shadowkit::scene::formats
