// Helpers for tests that write glTF files by hand, and check what they place.
#pragma once

#include "shadowkit/scene/scene_io.h"

#include "scratch_dir.h"

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>
#include <vector>

namespace shadowkit::scene::testing {

// Little-endian bytes of values of type T, appended to a buffer.
template <class T>
inline void append(std::vector<unsigned char>& buffer, std::initializer_list<T> values) {
    for (T v : values) {
        const size_t at = buffer.size();
        buffer.resize(at + sizeof(T));
        std::memcpy(buffer.data() + at, &v, sizeof(T));
    }
}

// Every triangle placed in the world must wind counter-clockwise about its own normal (the
// normal matrix of its instance applied), or a pass culling back faces would drop the side that
// faces out. Returns how many triangles were placed.
inline size_t expectEveryTriangleFacesOutward(const Scene& scene) {
    size_t triangles = 0;
    for (const MeshBatch& batch : scene.batches) {
        const Mesh& mesh = scene.meshes[batch.mesh];
        for (const glm::mat4& worldFromObject : batch.worldFromObject) {
            const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(worldFromObject)));
            for (size_t t = 0; t < mesh.triangleCount(); ++t, ++triangles) {
                glm::vec3 ws[3], wsNormal(0.0f);
                for (int k = 0; k < 3; ++k) {
                    const Vertex& v = mesh.vertices[mesh.indices[3 * t + size_t(k)]];
                    ws[k] = glm::vec3(worldFromObject * glm::vec4(v.position, 1.0f));
                    wsNormal += normalMatrix * v.normal;
                }
                EXPECT_GT(glm::dot(glm::cross(ws[1] - ws[0], ws[2] - ws[0]), wsNormal), 0.0f)
                    << "the triangle near x = " << ws[0].x;
            }
        }
    }
    return triangles;
}

// RFC 4648 base64, for data: URIs.
inline std::string base64(const std::vector<unsigned char>& data) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < data.size(); i += 3) {
        const uint32_t n = uint32_t(data[i]) << 16 | (i + 1 < data.size() ? uint32_t(data[i + 1]) << 8 : 0) |
                           (i + 2 < data.size() ? uint32_t(data[i + 2]) : 0);
        out += digits[n >> 18 & 63];
        out += digits[n >> 12 & 63];
        out += i + 1 < data.size() ? digits[n >> 6 & 63] : '=';
        out += i + 2 < data.size() ? digits[n & 63] : '=';
    }
    return out;
}

// `text` as the temporary file `name`, loaded (with `options`) and removed; a file that could
// not be written is the test's failure, not the reader's.
inline core::Result<Scene> loadWritten(const std::string& name, const std::string& text,
                                       const LoadOptions& options = {}) {
    const auto file = shadowkit::test_support::scratchDir() / name;
    std::ofstream out(file);
    out << text;
    out.close();
    if (!out) return core::makeError(file.string() + ": the test could not write it");
    auto scene = loadScene(file, options);
    std::filesystem::remove(file);
    return scene;
}

} // namespace shadowkit::scene::testing
