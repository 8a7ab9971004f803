// Axis-aligned bounding box.
#pragma once

#include "shadowkit/core/conventions.h"

#include <array>
#include <limits>

namespace shadowkit::core {

/// An axis-aligned box in world space, empty when min > max (the default).
struct Aabb {
    /// An empty box (min > max); extending it by any point makes it that point.
    Vec3 min{std::numeric_limits<double>::infinity()};
    Vec3 max{-std::numeric_limits<double>::infinity()}; ///< the upper corner (min: the lower)

    /// The box with these corners (not checked: lo > hi on an axis is an empty box).
    static Aabb fromMinMax(const Vec3& lo, const Vec3& hi) { return {lo, hi}; }

    /// True when min > max on an axis, or a bound is NaN.
    bool isEmpty() const { return !(min.x <= max.x && min.y <= max.y && min.z <= max.z); } // NaN-safe
    /// The midpoint of the corners.
    Vec3 center() const { return 0.5 * (min + max); }
    /// max − min: the size along each axis.
    Vec3 extent() const { return max - min; }
    /// Length of the diagonal; 0 when empty.
    double diagonal() const { return isEmpty() ? 0.0 : glm::length(max - min); }

    /// Grows the box to hold p.
    void extend(const Vec3& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    /// Grows the box to hold b (an empty b changes nothing).
    void extend(const Aabb& b) {
        if (!b.isEmpty()) {
            extend(b.min);
            extend(b.max);
        }
    }
    /// True if p lies in the box grown by eps metres on every side.
    bool contains(const Vec3& p, double eps = 0.0) const {
        return p.x >= min.x - eps && p.y >= min.y - eps && p.z >= min.z - eps && p.x <= max.x + eps &&
               p.y <= max.y + eps && p.z <= max.z + eps;
    }
    /// Squared distance from p to the box: 0 inside.
    double distanceSquared(const Vec3& p) const {
        const Vec3 d = glm::max(glm::max(min - p, p - max), Vec3(0.0));
        return glm::dot(d, d);
    }
    /// Corner i: bit 0 selects x, bit 1 y, bit 2 z (0 = min, 1 = max).
    Vec3 corner(int i) const { return {(i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y, (i & 4) ? max.z : min.z}; }
    /// The eight corners, in corner(i) order.
    std::array<Vec3, 8> corners() const {
        std::array<Vec3, 8> c;
        for (int i = 0; i < 8; ++i) c[static_cast<size_t>(i)] = corner(i);
        return c;
    }
};

/// Bounds of points after a transform (a box of a box is the box of its 8 corners).
Aabb transformBounds(const Mat4& bFromA, const Aabb& aBox);

} // namespace shadowkit::core
