#include "shadowkit/core/output_conventions.h"

#include <cmath>

namespace shadowkit::core {

namespace {

// The plane where dot(row, (p, 1)) = 0, keeping dot >= 0 inside, with an outward unit normal.
Plane insideWhereNonNegative(const Vec4& row) {
    const double length = glm::length(Vec3(row));
    return {-Vec3(row) / length, -row.w / length};
}

Vec4 matrixRow(const Mat4& m, int r) { return {m[0][r], m[1][r], m[2][r], m[3][r]}; }

} // namespace

Mat4 clipConversion(const OutputConventions& conventions) {
    // Core clip depth z lies in [0, w] with 0 nearest the light. Rewritten as z' = α z + β w:
    //   [0, 1]:  z' = z,       reversed z' = w − z
    //   [-1, 1]: z' = 2z − w,  reversed z' = w − 2z
    const bool wide = conventions.clipDepth == ClipDepthRange::MinusOneToOne;
    const double alpha = (wide ? 2.0 : 1.0) * (conventions.reversedZ ? -1.0 : 1.0);
    const double beta = conventions.reversedZ ? 1.0 : (wide ? -1.0 : 0.0);
    Mat4 m(1.0);
    m[2][2] = alpha; // column z, row z
    m[3][2] = beta;  // column w, row z
    return m;
}

EngineShadowView toEngineView(const ShadowView& view, const ShadowSetup& setup, const OutputConventions& conventions) {
    EngineShadowView out;
    out.clipFromWorld = clipConversion(conventions) * view.clipFromWorld;

    // Texture space from core clip space, everything still multiplied by w:
    //   u w = 0.5 x + 0.5 w,  v w = ±0.5 y + 0.5 w (− for a top-left origin),
    //   d w = z (the stored depth is core ndc z in every clip convention), or w − z reversed.
    Mat4 textureFromClip(0.0);
    textureFromClip[0][0] = 0.5;
    textureFromClip[1][1] = conventions.textureOrigin == TextureOrigin::TopLeft ? -0.5 : 0.5;
    textureFromClip[2][2] = conventions.reversedZ ? -1.0 : 1.0;
    textureFromClip[3] = Vec4(0.5, 0.5, conventions.reversedZ ? 1.0 : 0.0, 1.0);
    out.textureFromWorld = textureFromClip * view.clipFromWorld;
    auto linear = [&](const Vec4& row) { return conventions.reversedZ ? Vec4(0, 0, 0, 1) - row : row; };
    out.linearDepthFromWorld = linear(view.linearDepthFromWorld);

    out.clipFromEyeRelative = clipConversion(conventions) * view.clipFromEyeRelative;
    out.textureFromEyeRelative = textureFromClip * view.clipFromEyeRelative;
    out.linearDepthFromEyeRelative = linear(view.linearDepthFromEyeRelative);
    out.wsEye = setup.wsEye;

    // Gribb and Hartmann's planes from the core clip matrix's rows: -w <= x <= w, -w <= y <= w,
    // z <= w, and 0 <= z only without depth clamping.
    const Mat4& m = view.clipFromWorld;
    const Vec4 x = matrixRow(m, 0), y = matrixRow(m, 1), z = matrixRow(m, 2), w = matrixRow(m, 3);
    for (const Vec4& row : {w + x, w - x, w + y, w - y, w - z})
        out.wsCullingPlanes.push_back(insideWhereNonNegative(row));
    if (!setup.depthClamp) out.wsCullingPlanes.push_back(insideWhereNonNegative(z));

    out.split = view.split;
    out.depthLayout = setup.depthLayout;
    out.reversedZ = conventions.reversedZ;
    out.wsLightPosition = setup.wsLightPosition;
    out.lightDistance = view.lightDistance;
    return out;
}

double referenceDepth(const EngineShadowView& view, const Vec3& wsPoint) {
    switch (view.depthLayout) {
    case DepthLayout::Hyperbolic: {
        const Vec4 t = view.textureFromWorld * Vec4(wsPoint, 1.0);
        return t.z / t.w;
    }
    case DepthLayout::Linear:
        return glm::dot(view.linearDepthFromWorld, Vec4(wsPoint, 1.0));
    case DepthLayout::LightDistance: {
        const double d = (glm::distance(wsPoint, view.wsLightPosition) - view.lightDistance.x) /
                         (view.lightDistance.y - view.lightDistance.x);
        return view.reversedZ ? 1.0 - d : d;
    }
    }
    return NAN;
}

double wsTexelSize(const Mat4& m, int mapSize, const Vec3& wsLightDirection, const Vec3& wsPoint) {
    const Vec4 c = m * Vec4(wsPoint, 1.0);
    if (!(c.w > 0.0)) return INFINITY;
    const Vec3 l = glm::normalize(wsLightDirection);
    const Vec3 e1 = glm::normalize(std::abs(l.y) < 0.9 ? glm::cross(l, Vec3(0, 1, 0)) : glm::cross(l, Vec3(1, 0, 0)));
    const Vec3 e2 = glm::cross(l, e1);
    // ∂(x/w)/∂e = (dx·w − x·dw) / w² for the clip-space change d = M (e, 0); the texel's size is
    // (2 / mapSize) ndc over the square root of the area scale |det ∂ndc.xy/∂(e1, e2)|.
    auto derivative = [&](const Vec3& e) {
        const Vec4 d = m * Vec4(e, 0.0);
        return Vec2((d.x * c.w - c.x * d.w) / (c.w * c.w), (d.y * c.w - c.y * d.w) / (c.w * c.w));
    };
    const Vec2 j1 = derivative(e1), j2 = derivative(e2);
    const double det = std::abs(j1.x * j2.y - j1.y * j2.x);
    if (!(det > 0.0)) return INFINITY;
    return (2.0 / mapSize) / std::sqrt(det);
}

} // namespace shadowkit::core
