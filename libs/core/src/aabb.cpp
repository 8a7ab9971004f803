#include "shadowkit/core/aabb.h"

namespace shadowkit::core {

Aabb transformBounds(const Mat4& bFromA, const Aabb& aBox) {
    Aabb out;
    if (aBox.isEmpty()) return out;
    for (const Vec3& c : aBox.corners()) {
        const Vec4 p = bFromA * Vec4(c, 1.0);
        out.extend(Vec3(p) / p.w);
    }
    return out;
}

} // namespace shadowkit::core
