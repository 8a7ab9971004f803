// Virtual shadow maps for the sun: a clipmap of large virtual maps split into pages, of which
// only the pages under visible receivers are ever allocated and rendered.
//
// The maths of it, pure (no GL): the clipmap's levels for a camera and a sun, the level that
// serves a receiver, and the world-anchored keys of its pages. The page pool, the marking of
// requested pages and their rendering live in libs/gl (virtual_pages.h); the lookup in
// glsl/shadowkit_shadows.glsl. See docs/virtual-shadow-maps.md.
#pragma once

#include "shadowkit/core/camera.h"
#include "shadowkit/core/conventions.h"
#include "shadowkit/core/result.h"

#include <cstdint>
#include <optional>

namespace shadowkit::core {

struct ShadowSetup;
struct ShadowSetupInputs;
struct ShadowView;

/// The clipmap's parameters: virtual map and page sizes, the levels, the level rule.
struct VirtualOptions {
    /// Texels per side of each level's virtual map, a power of two in [1024, 65536]. 16384 as
    /// Unreal Engine 5: with a texel of about one pixel, a level reaches ~6 view depths around the
    /// eye, so every receiver lies well inside the level its footprint picks.
    int virtualTexels = 16384;
    /// Texels per side of a page, a power of two in [16, 1024], at most virtualTexels / 8 and at
    /// least virtualTexels / 512 (the page table's side). 128 as UE5 and Timberdoodle: small
    /// enough that a page holds little that is not seen, large enough that a 1280 × 720 view
    /// needs a few hundred of them.
    int pageTexels = 128;
    /// Exponent of the finest level: its texel is 2^firstLevel metres. Unset: the footprint of
    /// a pixel at the nearest visible depth (ShadowSetupInputs::visibleDepth), else at the
    /// camera's near plane. In [-24, 24].
    std::optional<int> firstLevel;
    /// Added to log2 of the footprint before the level is chosen: +1 halves the resolution
    /// everywhere (UE's ResolutionLodBiasDirectional). Finite, in [-8, 8].
    double lodBias = 0.0;
    /// Rows of the camera's image, for the footprint of a pixel (the frame driver sets it from
    /// each frame's view). >= 1.
    int imageHeight = 720;
};
/// Checks the ranges above; error fields "virtual.texels", "virtual.page_texels",
/// "virtual.first_level", "virtual.lod_bias", "virtual.image_height".
Status validate(const VirtualOptions& options);

/// At most this many levels (texel sizes from 2^e to 2^(e+15) metres).
inline constexpr int kMaxClipmapLevels = 16;

/// One level of the clipmap: ShadowView::warp of a virtual set-up's views.
struct ClipmapLevel {
    int exponent = 0; ///< the level's texel is 2^exponent metres on a side
    /// Page-grid index along light-space x of the level's first page (its corner nearest −x, −y),
    /// counted from the grid origin (ShadowSetupInputs::wsGridOrigin): the level's window.
    int64_t firstPageX = 0;
    int64_t firstPageY = 0; ///< the same along light-space y
};

/// Where a page has its entry in a level's block of a page table, pagesPerSide² entries a level:
/// the cell (x mod n, y mod n) of its grid index. Addressed so — toroidally, as a clipmap keeps its
/// texels (Tanner et al. 1998, "The Clipmap", §4) — a window that moves by a page keeps the entry
/// of every page it still covers where it was, and only the row or column it uncovers changes:
/// a frame uploads those, not the level. The window's first page's cell is where its row 0,
/// column 0 lies; the lookup adds it to a page's place in the window, modulo n.
struct PageTableCell {
    int x = 0; ///< column, in [0, pagesPerSide)
    int y = 0; ///< row, in [0, pagesPerSide)
};
PageTableCell pageTableCellOf(int64_t pageX, int64_t pageY, int pagesPerSide);

/// What every level shares, in world space: the light's orientation, the grid the pages are
/// anchored to, the depth range. All of it depends on the sun and the scene box alone, never
/// on the camera, so a page rendered in one frame holds the same depths in the next.
struct VirtualClipmap {
    Mat4 lightFromWorldRotation{1.0}; ///< the light frame's rotation (no translation)
    Vec3 wsGridOrigin{0.0};           ///< the world point every level's page grid passes through
    /// Light-space depth range of the scene box, relative to the grid origin and snapped
    /// outwards (so a mover that grows the box a little does not change it): zNear is the
    /// highest z (nearest the light), mapped to depth 0.
    double zNear = 0.0;
    double zFar = 1.0;              ///< the lowest z (farthest from the light), mapped to depth 1
    int virtualTexels = 16384;      ///< VirtualOptions::virtualTexels
    int pageTexels = 128;           ///< VirtualOptions::pageTexels
    int firstExponent = 0;          ///< exponent of level 0 (the finest)
    double lodBias = 0.0;           ///< VirtualOptions::lodBias
    double footprintPerMetre = 0.0; ///< a pixel's size at view depth 1 m (pixelFootprintPerMetre)

    int pagesPerSide() const { return virtualTexels / pageTexels; } ///< pages per side of a level's window
};

/// A page of one level, anchored to the world: the same key while the sun is still, whatever
/// the camera does (a level's window slides over the grid; its pages keep their keys).
struct PageKey {
    int exponent = 0;                                ///< the level's (ClipmapLevel::exponent)
    int64_t x = 0;                                   ///< page-grid index along light-space x from the grid origin
    int64_t y = 0;                                   ///< along light-space y
    bool operator==(const PageKey&) const = default; ///< the same page
};

/// A pixel's size in metres at view depth 1 m: 2 tan(fovY / 2) / image rows. Times the view
/// depth, the footprint of a pixel there.
double pixelFootprintPerMetre(const PerspectiveCamera& camera, int imageHeight);

/// The level exponent for a footprint in metres: floor(log2(footprint) + lodBias), i.e. the
/// largest texel of 2^e metres that is no larger than the footprint (times 2^-lodBias).
int clipmapExponentFor(double footprintMetres, double lodBias);

/// The index of the level serving a receiver at `viewDepth` (the level rule, clamped to the
/// clipmap's levels): what the marking pass and the lookup both compute.
int clipmapLevelFor(const VirtualClipmap& clipmap, int levelCount, double viewDepth);

/// The level that serves a receiver at `wsPoint`, `viewDepth` from the eye: the rule's
/// (clipmapLevelFor), or the first coarser one whose window holds the point — a narrow field
/// of view (under ~10° at 720 rows) has pixels so small that the rule's level does not reach
/// as far as the view does. nullopt when no level holds it.
std::optional<int> clipmapLevelHolding(const ShadowSetup& setup, double viewDepth, const Vec3& wsPoint);

/// The key of the page of `level` (a view of a virtual set-up) holding `wsPoint`, or nullopt
/// when the point lies outside the level's window.
std::optional<PageKey> clipmapPageOf(const ShadowSetup& setup, int level, const Vec3& wsPoint);

/// The clip matrix that renders one page into its own viewport: the page's square, grown by
/// `guardTexels` on every side, in the coordinates `clipmap` is in (world, or the renderer's
/// scene space after rebased()). Built from the clipmap's camera-independent frame only, so a
/// page's matrix is the same in every frame: a cached page and a fresh one hold the same depths.
Mat4 clipmapPageClipFromWorld(const VirtualClipmap& clipmap, const PageKey& page, int guardTexels);

/// Level `exponent` of `clipmap` around an eye at `wsEye` (coordinates as `clipmap`'s): its
/// window — the virtualTexels² texels around the eye snapped to the page grid — as an
/// orthographic view, ShadowView::warp its ClipmapLevel. What computeVirtualClipmap makes of
/// each level; also how a clipmap kept from an earlier sun is placed around a later eye (gl's
/// page budget keeps levels of the previous sun on screen while the new sun's are drawn).
ShadowView clipmapLevelView(const VirtualClipmap& clipmap, int exponent, const Vec3& wsEye);

/// The light-space square [min, max] (x, y, relative to the grid origin) of a world box,
/// for invalidation: the pages of a level whose squares meet it.
struct LightRect {
    double minX = 0.0; ///< light-space x from the grid origin, lowest
    double minY = 0.0; ///< light-space y, lowest
    double maxX = 0.0; ///< light-space x, highest
    double maxY = 0.0; ///< light-space y, highest
};
LightRect clipmapRectOf(const VirtualClipmap& clipmap, const Vec3& wsMin, const Vec3& wsMax);

/// Technique::Virtual: the clipmap's levels as the set-up's views, finest first — each an
/// orthographic map of virtualTexels² over its window, ShadowView::warp its ClipmapLevel —
/// and ShadowSetup::clipmap. Levels run from the first (VirtualOptions::firstLevel) to the
/// one serving the farthest visible receivers plus one (their fallback), no coarser than
/// needed to hold the whole scene box, at most kMaxClipmapLevels (the finest dropped first,
/// with a note in `fallbacks`). For computeShadowSetup, which calls it relative to the eye.
ShadowSetup computeVirtualClipmap(const ShadowSetupInputs& inputs);

} // namespace shadowkit::core
