// Core's maths types in shadowkit::visibility, named there as in core: the visibility
// algorithms are written in core's vocabulary, one room further out.
#pragma once

#include "shadowkit/core/aabb.h"
#include "shadowkit/core/conventions.h"

namespace shadowkit::visibility {

using core::Aabb;
using core::Mat4;
using core::Vec2;
using core::Vec3;
using core::Vec4;

} // namespace shadowkit::visibility
