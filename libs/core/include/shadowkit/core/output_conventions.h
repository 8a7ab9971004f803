// A set-up's matrices in the conventions of the engine that draws and samples the maps.
//
// The core computes in one convention (conventions.h): clip depth [0, 1] with 0 nearest the
// light, texture v = 0.5 · ndc.y + 0.5. An engine picks:
//   clip depth [0, 1] or [-1, 1]   what its API's rasteriser expects of the map's clip matrix;
//   reversed-Z                     the light's near side stored as 1 (better float precision);
//   texture origin                 where v = 0 lies in the map's memory.
// What each API wants, with the matrices used as they are (no flip of the clip y):
//
//   API                       clipDepth       textureOrigin   why
//   OpenGL (default)          MinusOneToOne   BottomLeft      window y up, row 0 at the bottom
//   OpenGL + glClipControl    ZeroToOne       BottomLeft      (what shadowkit's own renderer uses)
//   Vulkan                    ZeroToOne       BottomLeft      ndc y = -1 is framebuffer row 0 and v = 0:
//                                                             the flips of window and texture cancel
//   Direct3D 11/12, Metal     ZeroToOne       TopLeft         ndc y = +1 is row 0, v = 0 at the top
//
// Vulkan turns the map upside down in memory compared with OpenGL, which also flips its
// winding: an engine culling caster faces swaps front and back there.
//
// The stored depth (what the depth texture holds, in [0, 1]) is, for every convention,
//   d = ndc.z (ZeroToOne) or 0.5 · ndc.z + 0.5 (MinusOneToOne), and 1 − d when reversed,
// so a fragment is lit when its reference depth <= the stored one (>= when reversed).
#pragma once

#include "shadowkit/core/plane.h"
#include "shadowkit/core/shadow_setup.h"
#include "shadowkit/core/small_vector.h"

namespace shadowkit::core {

enum class TextureOrigin {
    BottomLeft, ///< v = 0 at the first row written by ndc y = -1: OpenGL, Vulkan
    TopLeft,    ///< v = 0 at ndc y = +1: Direct3D, Metal
};

/// The target API's clip depth range, depth direction and texture origin, for EngineShadowView.
struct OutputConventions {
    ClipDepthRange clipDepth = ClipDepthRange::ZeroToOne;    ///< of the matrices handed out
    bool reversedZ = false;                                  ///< the light's near side stored as 1
    TextureOrigin textureOrigin = TextureOrigin::BottomLeft; ///< where v = 0 lies

    /// OpenGL's default: clip depth [−1, 1], v = 0 at the bottom row.
    static constexpr OutputConventions openGL() {
        return {ClipDepthRange::MinusOneToOne, false, TextureOrigin::BottomLeft};
    }
    /// Vulkan: clip depth [0, 1], v = 0 at row 0 (its flipped NDC y and texture rows cancel).
    static constexpr OutputConventions vulkan() {
        return {ClipDepthRange::ZeroToOne, false, TextureOrigin::BottomLeft};
    }
    /// Direct3D 11/12 and Metal: clip depth [0, 1], v = 0 at the top row.
    static constexpr OutputConventions direct3D() { return {ClipDepthRange::ZeroToOne, false, TextureOrigin::TopLeft}; }
};

/// One shadow view as an engine uses it.
struct EngineShadowView {
    /// Draw the map with this: the core's clipFromWorld with its depth row rewritten.
    Mat4 clipFromWorld{1.0};
    /// Look the map up with this: (u, v, d, 1) · w for a world point, so (u, v) = xy / w and, for
    /// the Hyperbolic layout, the reference depth d = z / w in the stored depth's convention.
    Mat4 textureFromWorld{1.0};
    /// Linear layout: the stored depth is dot(linearDepthFromWorld, (p, 1)), reversed when asked,
    /// written per fragment and compared the same way (the reference depth is not z / w then).
    Vec4 linearDepthFromWorld{0.0};
    /// Outward planes a caster's bounds must not lie wholly outside of to be drawn: the four
    /// sides and the far plane, and the near plane only when the set-up has no depth clamp
    /// (with clamping, casters between the map's near plane and the light still cast).
    SmallVector<Plane, 6> wsCullingPlanes;
    std::optional<Vec2> split; ///< cascades: the view-depth range this map serves
    /// Camera-relative rendering (large worlds): the same three for p − wsEye, the eye the set-up
    /// was computed around (ShadowView's eye-relative members).
    Mat4 clipFromEyeRelative{1.0};
    Mat4 textureFromEyeRelative{1.0};     ///< textureFromWorld for p − wsEye
    Vec4 linearDepthFromEyeRelative{0.0}; ///< linearDepthFromWorld for p − wsEye
    Vec3 wsEye{0.0};                      ///< the origin of the eye-relative members
    /// What referenceDepth needs: the set-up's layout, the convention, and for local lights the
    /// light and the distance range the stored depth spans.
    DepthLayout depthLayout = DepthLayout::Hyperbolic;
    bool reversedZ = false;    ///< the convention's depth direction
    Vec3 wsLightPosition{0.0}; ///< local lights: the light
    Vec2 lightDistance{0.0};   ///< local lights: [near, far] distance the stored depth spans
};

/// The matrix that takes the core's clip space to the chosen one (applied on the left).
Mat4 clipConversion(const OutputConventions& conventions);
EngineShadowView toEngineView(const ShadowView& view, const ShadowSetup& setup, const OutputConventions& conventions);

/// The reference depth of a world point for the map, in the stored depth's convention: z / w of
/// textureFromWorld for Hyperbolic maps, the linear row for Linear maps, the distance to the
/// light over lightDistance for LightDistance maps.
double referenceDepth(const EngineShadowView& view, const Vec3& wsPoint);

/// The world size (metres) of one texel of the map drawn with clipFromWorld at wsPoint, on a
/// plane facing the light: the distance to move a receiver along its normal for a normal
/// offset of one texel. +inf where the projection degenerates there (behind its centre).
double wsTexelSize(const Mat4& clipFromWorld, int mapSize, const Vec3& wsLightDirection, const Vec3& wsPoint);

} // namespace shadowkit::core
