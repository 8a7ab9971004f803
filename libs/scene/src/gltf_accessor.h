// glTF accessors (§3.6) read element by element, checked against their buffers: the component
// types with glTF's normalisation and sparse substitution that the mesh, instance and skin readers
// share (gltf_read.cpp, gltf_pose.cpp). Internal to libs/scene.
#pragma once

#include "gltf_materials.h"

#include "shadowkit/core/result.h"

#include <tiny_gltf.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cstring>
#include <string>
#include <unordered_map>

namespace shadowkit::scene::formats {

// Elements an accessor may hold before it is refused: 2^28 (a 4 GiB float4 array), so a
// hostile count cannot make us allocate without bound.
inline constexpr size_t kMaxAccessorCount = size_t(1) << 28;

// One component as glTF reads it: normalized signed integers as max(c / (2^(n−1) − 1), −1),
// unsigned as c / (2^n − 1), others as they are.
inline double component(int type, bool normalized, const unsigned char* p) {
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float f;
        std::memcpy(&f, p, 4);
        return f;
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        int8_t v;
        std::memcpy(&v, p, 1);
        return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return normalized ? *p / 255.0 : *p;
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        int16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        uint32_t v;
        std::memcpy(&v, p, 4);
        return v;
    }
    default:
        return 0.0;
    }
}

// One accessor, checked, read element by element with sparse values substituted.
class AccessorReader {
public:
    static core::Result<AccessorReader> open(const tinygltf::Model& model, int index, const std::string& where) {
        const std::string what = where + ": accessor " + std::to_string(index);
        if (index < 0 || size_t(index) >= model.accessors.size()) return core::makeError(what + ": no such accessor");
        AccessorReader r;
        const tinygltf::Accessor& a = model.accessors[size_t(index)];
        r.m_type = a.componentType;
        r.m_normalized = a.normalized;
        r.m_count = a.count;
        r.m_components = tinygltf::GetNumComponentsInType(uint32_t(a.type));
        r.m_componentSize = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
        if (r.m_components <= 0 || r.m_componentSize <= 0)
            return core::makeError(what + ": unknown type or component type");
        if (a.count > kMaxAccessorCount) return core::makeError(what + ": more elements than shadowkit reads (2^28)");
        const size_t elementSize = size_t(r.m_components) * size_t(r.m_componentSize);
        if (a.bufferView >= 0) {
            if (size_t(a.bufferView) >= model.bufferViews.size())
                return core::makeError(what + ": no such buffer view");
            const int stride = a.ByteStride(model.bufferViews[size_t(a.bufferView)]);
            if (stride <= 0) return core::makeError(what + ": bad byte stride");
            r.m_stride = size_t(stride);
            auto base = bytesOf(model, a.bufferView, a.byteOffset, a.count, elementSize, r.m_stride, what);
            if (!base) return base.errorInfo();
            r.m_base = *base;
        }
        if (a.sparse.isSparse) {
            const auto& s = a.sparse;
            const size_t n = size_t(s.count);
            const int indexSize = tinygltf::GetComponentSizeInBytes(uint32_t(s.indices.componentType));
            if (s.count < 0 || n > a.count || indexSize <= 0)
                return core::makeError(what + ": bad sparse count or index type");
            auto indices = bytesOf(model, s.indices.bufferView, size_t(s.indices.byteOffset), n, size_t(indexSize),
                                   size_t(indexSize), what);
            auto values =
                bytesOf(model, s.values.bufferView, size_t(s.values.byteOffset), n, elementSize, elementSize, what);
            if (!indices) return indices.errorInfo();
            if (!values) return values.errorInfo();
            r.m_sparseValues = *values;
            for (size_t k = 0; k < n; ++k) {
                const size_t i = size_t(component(s.indices.componentType, false, *indices + k * size_t(indexSize)));
                if (i >= a.count) return core::makeError(what + ": a sparse index lies past the accessor's count");
                r.m_sparse[i] = k;
            }
        }
        return r;
    }

    size_t count() const { return m_count; }
    double get(size_t i, int c) const {
        if (c >= m_components) return 0.0;
        const size_t offset = size_t(c) * size_t(m_componentSize);
        if (!m_sparse.empty())
            if (const auto it = m_sparse.find(i); it != m_sparse.end())
                return component(m_type, m_normalized,
                                 m_sparseValues + it->second * size_t(m_components * m_componentSize) + offset);
        return m_base ? component(m_type, m_normalized, m_base + i * m_stride + offset) : 0.0;
    }
    glm::vec4 read(size_t i, glm::vec4 fallback = glm::vec4(0, 0, 0, 1)) const {
        for (int c = 0; c < std::min(m_components, 4); ++c) fallback[c] = float(get(i, c));
        return fallback;
    }

private:
    int m_type = 0;
    bool m_normalized = false;
    size_t m_count = 0, m_stride = 0;
    int m_components = 0, m_componentSize = 0;
    const unsigned char* m_base = nullptr; // null: a sparse accessor over zeros
    const unsigned char* m_sparseValues = nullptr;
    std::unordered_map<size_t, size_t> m_sparse; // element -> position among the sparse values
};

} // namespace shadowkit::scene::formats
