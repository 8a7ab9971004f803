// EXT_mesh_gpu_instancing (gltfpack -mi): one node placing its mesh many times, read and checked.
#include "gltf_instancing.h"

#include "gltf_accessor.h"

#include "shadowkit/core/conventions.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <optional>

namespace shadowkit::scene::formats {

core::Result<std::vector<glm::dmat4>> instanceTransforms(const tinygltf::Model& model, const tinygltf::Node& node,
                                                         const glm::dmat4& world, const std::string& where,
                                                         size_t& placed) {
    const auto ext = node.extensions.find(kInstancing);
    if (ext == node.extensions.end()) return std::vector<glm::dmat4>{world};
    const std::string what = where + " (" + kInstancing + ")";
    if (!ext->second.IsObject()) return core::makeError(what + ": the extension is not an object");
    const tinygltf::Value& attributes = ext->second.Get("attributes"); // Get() asserts an object
    if (!attributes.IsObject()) return core::makeError(what + ": no attributes");
    std::optional<AccessorReader> readers[3]; // TRANSLATION, ROTATION, SCALE
    const char* names[3] = {"TRANSLATION", "ROTATION", "SCALE"};
    std::optional<size_t> count;
    for (int a = 0; a < 3; ++a) {
        const tinygltf::Value& index = attributes.Get(names[a]);
        if (index.Type() == tinygltf::NULL_TYPE) continue;
        if (!index.IsInt()) return core::makeError(what + ": " + names[a] + " is not an accessor index");
        const int accessor = index.Get<int>();
        auto reader = AccessorReader::open(model, accessor, what + " " + names[a]);
        if (!reader) return reader.errorInfo();
        const int type = model.accessors[size_t(accessor)].type;
        if (type != (a == 1 ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3))
            return core::makeError(what + ": " + names[a] + " must be a " + (a == 1 ? "VEC4" : "VEC3") + " accessor");
        if (count && *count != reader->count())
            return core::makeError(what + ": its attributes have different counts (" + std::to_string(*count) +
                                   " and " + std::to_string(reader->count()) + ")");
        count = reader->count();
        readers[a] = std::move(*reader);
    }
    if (!count) return std::vector<glm::dmat4>{world}; // no attributes: the node as it is
    placed += *count;
    if (placed > kMaxInstances)
        return core::makeError(what + ": more instances than shadowkit places in one scene (2^24)");
    std::vector<glm::dmat4> out(*count);
    for (size_t i = 0; i < *count; ++i) {
        glm::dmat4 m(1.0);
        if (readers[0]) m = glm::translate(m, glm::dvec3(readers[0]->read(i)));
        if (readers[1]) {
            const glm::dvec4 q(readers[1]->read(i));
            const double length = glm::length(q);
            if (!(length > 0.0) || !std::isfinite(length))
                return core::makeError(what + ": instance " + std::to_string(i) + "'s rotation is not a quaternion");
            m *= glm::mat4_cast(glm::dquat(q.w / length, q.x / length, q.y / length, q.z / length));
        }
        if (readers[2]) m = glm::scale(m, glm::dvec3(readers[2]->read(i)));
        out[i] = world * m;
        if (!core::isFinite(glm::dmat4(glm::mat4(out[i])))) // as float too: the renderer's
            return core::makeError(what + ": instance " + std::to_string(i) + " has a non-finite transform");
    }
    return out;
}

} // namespace shadowkit::scene::formats
