// Virtual shadow maps: the clipmap of a directional light.
//
// Based on: Fernando et al., "Adaptive Shadow Maps", SIGGRAPH 2001 (resolution where the view
// needs it, in pages); Lefohn et al., "Resolution-Matched Shadow Maps", ACM TOG 2007 (pages
// requested by the visible receivers, one texel per pixel); and the clipmap form of Unreal
// Engine 5's virtual shadow maps (a directional light's levels are 16k² virtual maps of 128²
// pages, level k's texel twice level k − 1's, centred on the camera and snapped to the page
// grid; documented in UE5's "Virtual Shadow Maps" pages).
//
// The maths:
//   - Light space is one rotation R of the world (the light looks down −Z, +Y north as the
//     standard map's), anchored at the grid origin g: ls(p) = R (p − g). It does not depend on
//     the camera, so neither does any page.
//   - Level e (an exponent) has texels of t = 2^e metres and pages of P t; its window is the
//     V / P × V / P pages around the eye, the eye snapped to the nearest page corner. Window
//     origins move by whole pages, so a page's square [x P t, (x + 1) P t] is fixed in the
//     world: its key (e, x, y) is stable while the sun is still.
//   - The level rule: a receiver at view depth d has a pixel footprint f = d · 2 tan(fovY / 2)
//     / H; it is served by e = floor(log2 f + lodBias), the largest texel no larger than the
//     footprint (one texel per pixel or finer). Its window then reaches at least
//     V t / 2 > V f / 4 around the eye, ~6 d for a 720-row image at 60°: every receiver the
//     rule assigns lies inside its level.
//   - Depth: the scene box along the light, snapped outwards to 1/8 of its power-of-two extent
//     relative to g, the same for every level and every frame with the same box.
#include "shadowkit/core/virtual_clipmap.h"

#include "shadowkit/core/aabb.h"
#include "shadowkit/core/light_frame.h"
#include "shadowkit/core/shadow_setup.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace shadowkit::core {
namespace {

bool isPowerOfTwo(int v) { return v > 0 && (v & (v - 1)) == 0; }

double texelMetres(int exponent) { return std::ldexp(1.0, exponent); }

// Page indices stay exact in double and far inside int64: an eye further from the grid origin
// than this many pages of the finest level moves the grid origin to itself (and says so).
constexpr double kMaxPageIndex = 0x1p50;

// The grid origin in light space (rotation only): ls(p) = R p − gridLs.
Vec3 gridInLight(const VirtualClipmap& c) { return Vec3(c.lightFromWorldRotation * Vec4(c.wsGridOrigin, 1.0)); }

} // namespace

Status validate(const VirtualOptions& o) {
    if (!isPowerOfTwo(o.virtualTexels) || o.virtualTexels < 1024 || o.virtualTexels > 65536)
        return fieldError("virtual.texels",
                          "must be a power of two in [1024, 65536], got " + std::to_string(o.virtualTexels));
    if (!isPowerOfTwo(o.pageTexels) || o.pageTexels < 16 || o.pageTexels > 1024 || o.pageTexels > o.virtualTexels / 8 ||
        o.virtualTexels / o.pageTexels > 512)
        return fieldError(
            "virtual.page_texels",
            "must be a power of two in [16, 1024] giving 8 to 512 pages per side of the virtual map, got " +
                std::to_string(o.pageTexels));
    if (o.firstLevel && (*o.firstLevel < -24 || *o.firstLevel > 24))
        return fieldError("virtual.first_level", "must be an exponent in [-24, 24] (texels of 2^e metres), got " +
                                                     std::to_string(*o.firstLevel));
    if (!std::isfinite(o.lodBias) || o.lodBias < -8.0 || o.lodBias > 8.0)
        return fieldError("virtual.lod_bias", "must be a number of levels in [-8, 8]");
    if (o.imageHeight < 1) return fieldError("virtual.image_height", "must be at least 1 pixel");
    return Ok{};
}

double pixelFootprintPerMetre(const PerspectiveCamera& camera, int imageHeight) {
    return 2.0 * std::tan(0.5 * glm::radians(camera.fovYDegrees)) / std::max(imageHeight, 1);
}

int clipmapExponentFor(double footprintMetres, double lodBias) {
    // Footprints far below a nanometre (a receiver on the eye) clamp to the lowest exponent.
    const double f = std::max(footprintMetres, 1e-9);
    return static_cast<int>(std::floor(std::log2(f) + lodBias));
}

int clipmapLevelFor(const VirtualClipmap& clipmap, int levelCount, double viewDepth) {
    const int e = clipmapExponentFor(viewDepth * clipmap.footprintPerMetre, clipmap.lodBias);
    return std::clamp(e - clipmap.firstExponent, 0, std::max(levelCount - 1, 0));
}

std::optional<int> clipmapLevelHolding(const ShadowSetup& setup, double viewDepth, const Vec3& wsPoint) {
    if (!setup.clipmap) return std::nullopt;
    const int levels = static_cast<int>(setup.views.size());
    for (int level = clipmapLevelFor(*setup.clipmap, levels, viewDepth); level < levels; ++level)
        if (clipmapPageOf(setup, level, wsPoint)) return level;
    return std::nullopt;
}

PageTableCell pageTableCellOf(int64_t pageX, int64_t pageY, int pagesPerSide) {
    // The non-negative remainder: grid indices run negative west and south of the grid origin.
    const auto cell = [n = int64_t(pagesPerSide)](int64_t i) { return static_cast<int>((i % n + n) % n); };
    return {cell(pageX), cell(pageY)};
}

std::optional<PageKey> clipmapPageOf(const ShadowSetup& setup, int level, const Vec3& wsPoint) {
    if (!setup.clipmap || level < 0 || level >= static_cast<int>(setup.views.size())) return std::nullopt;
    const VirtualClipmap& c = *setup.clipmap;
    const auto* info = std::get_if<ClipmapLevel>(&setup.views[level].warp);
    if (!info) return std::nullopt;
    const Vec3 ls = Vec3(c.lightFromWorldRotation * Vec4(wsPoint, 1.0)) - gridInLight(c);
    const double pageMetres = c.pageTexels * texelMetres(info->exponent);
    const double px = std::floor(ls.x / pageMetres), py = std::floor(ls.y / pageMetres);
    if (!(std::abs(px) < kMaxPageIndex && std::abs(py) < kMaxPageIndex)) return std::nullopt; // no level reaches
    const auto x = static_cast<int64_t>(px), y = static_cast<int64_t>(py);
    const int64_t pages = c.pagesPerSide();
    if (x < info->firstPageX || x >= info->firstPageX + pages || y < info->firstPageY || y >= info->firstPageY + pages)
        return std::nullopt;
    return PageKey{info->exponent, x, y};
}

Mat4 clipmapPageClipFromWorld(const VirtualClipmap& c, const PageKey& page, int guardTexels) {
    const double texel = texelMetres(page.exponent);
    const double pageMetres = c.pageTexels * texel;
    const double guard = guardTexels * texel;
    // ls = R (p − g), from quantities that do not depend on the camera.
    const Mat4 lightFromGrid = glm::translate(Mat4(1.0), -gridInLight(c)) * c.lightFromWorldRotation;
    const double x0 = static_cast<double>(page.x) * pageMetres - guard;
    const double y0 = static_cast<double>(page.y) * pageMetres - guard;
    const double side = pageMetres + 2.0 * guard;
    return orthoZeroToOne(x0, x0 + side, y0, y0 + side, -c.zNear, -c.zFar) * lightFromGrid;
}

ShadowView clipmapLevelView(const VirtualClipmap& c, int exponent, const Vec3& wsEye) {
    const Vec3 grid = gridInLight(c);
    const Vec3 eye = Vec3(c.lightFromWorldRotation * Vec4(wsEye, 1.0));
    const int pages = c.pagesPerSide();
    const double pageMetres = c.pageTexels * texelMetres(exponent);
    // The eye snapped to the nearest page corner of the grid.
    const ClipmapLevel level{exponent, std::llround((eye.x - grid.x) / pageMetres) - pages / 2,
                             std::llround((eye.y - grid.y) / pageMetres) - pages / 2};
    const double x0 = grid.x + static_cast<double>(level.firstPageX) * pageMetres;
    const double y0 = grid.y + static_cast<double>(level.firstPageY) * pageMetres;
    const double side = pages * pageMetres;
    ShadowView view;
    view.lightFromWorld = c.lightFromWorldRotation;
    view.clipFromLight = orthoZeroToOne(x0, x0 + side, y0, y0 + side, -(grid.z + c.zNear), -(grid.z + c.zFar));
    view.clipFromWorld = view.clipFromLight * view.lightFromWorld;
    view.warp = level;
    return view;
}

LightRect clipmapRectOf(const VirtualClipmap& c, const Vec3& wsMin, const Vec3& wsMax) {
    const Vec3 grid = gridInLight(c);
    LightRect r{INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (const Vec3& corner : Aabb::fromMinMax(wsMin, wsMax).corners()) {
        const Vec3 ls = Vec3(c.lightFromWorldRotation * Vec4(corner, 1.0)) - grid;
        r.minX = std::min(r.minX, ls.x), r.maxX = std::max(r.maxX, ls.x);
        r.minY = std::min(r.minY, ls.y), r.maxY = std::max(r.maxY, ls.y);
    }
    return r;
}

ShadowSetup computeVirtualClipmap(const ShadowSetupInputs& in) {
    const VirtualOptions& o = in.virtualMaps;
    ShadowSetup setup;
    setup.technique = Technique::Virtual;
    setup.mapSize = o.virtualTexels;
    setup.depthClamp = true;

    VirtualClipmap c;
    // North first, as the standard map: the frame depends on the light alone.
    c.lightFromWorldRotation = makeLightFrame(in.light.wsDirection, Vec3(0.0), {Vec3(0, 0, -1)}).lightFromWorld;
    c.wsGridOrigin = in.wsGridOrigin; // relative to the eye here: computeShadowSetup runs centred
    c.virtualTexels = o.virtualTexels;
    c.pageTexels = o.pageTexels;
    c.lodBias = o.lodBias;
    c.footprintPerMetre = pixelFootprintPerMetre(in.camera, o.imageHeight);
    Vec3 grid = gridInLight(c);
    const Vec3 eye = Vec3(c.lightFromWorldRotation * Vec4(in.camera.wsEye, 1.0));

    // How far a level must reach: the scene box around the eye, in light space.
    double reach = 0.0;
    for (const Vec3& corner : in.wsSceneBounds.corners()) {
        const Vec3 ls = Vec3(c.lightFromWorldRotation * Vec4(corner, 1.0));
        reach = std::max({reach, std::abs(ls.x - eye.x), std::abs(ls.y - eye.y)});
    }

    // Levels: from the footprint at the nearest visible depth to one past the farthest's.
    double dNear = in.camera.zNear, dFar = in.camera.zFar;
    if (in.visibleDepth) dNear = std::max(dNear, in.visibleDepth->x), dFar = std::min(dFar, in.visibleDepth->y);
    dFar = std::max(dFar, dNear);
    int first = o.firstLevel.value_or(clipmapExponentFor(dNear * c.footprintPerMetre, o.lodBias));
    int last = std::max(first, clipmapExponentFor(dFar * c.footprintPerMetre, o.lodBias) + 1);
    // No level coarser than the first whose window holds the whole scene box around the eye
    // (the window's centre is the eye snapped to a page corner: half a page less).
    const double halfTexels = 0.5 * (o.virtualTexels - o.pageTexels);
    const double sceneSize = std::max(in.wsSceneBounds.diagonal(), 1e-300); // floors relative to it: any units
    const int covering = static_cast<int>(std::ceil(std::log2(std::max(reach, 1e-6 * sceneSize) / halfTexels)));
    last = std::clamp(covering, first, last);
    if (last - first + 1 > kMaxClipmapLevels) {
        setup.fallbacks.emplace_back("more than " + std::to_string(kMaxClipmapLevels) +
                                     " clipmap levels needed: the finest dropped (near receivers get coarser texels)");
        first = last - kMaxClipmapLevels + 1;
    }
    c.firstExponent = first;

    // An eye beyond any page index: the grid passes through the eye instead. Pages are then not
    // anchored to the world, but the grid origin is part of what a page's depth depends on
    // (gl's PageContent), so every frame redraws its pages rather than reuse wrong ones.
    const double finestPage = o.pageTexels * texelMetres(first);
    if (!(std::max(std::abs(eye.x - grid.x), std::abs(eye.y - grid.y)) / finestPage <= kMaxPageIndex)) {
        c.wsGridOrigin = in.camera.wsEye;
        grid = gridInLight(c);
        setup.fallbacks.emplace_back("the eye lies more than 2^50 pages from the grid origin: the grid passes "
                                     "through the eye instead, and pages are redrawn every frame (set "
                                     "ShadowSetupInputs::wsGridOrigin near the scene)");
    }

    // Depth: the scene box along the light, relative to the grid origin, snapped outwards to an
    // eighth of the extent's power of two (at least a millionth of the scene's size): a box that
    // grows a little keeps its depth range, so cached pages stay valid.
    double zLo = INFINITY, zHi = -INFINITY;
    for (const Vec3& corner : in.wsSceneBounds.corners()) {
        const double z = Vec3(c.lightFromWorldRotation * Vec4(corner, 1.0)).z - grid.z;
        zLo = std::min(zLo, z), zHi = std::max(zHi, z);
    }
    const double step =
        std::ldexp(1.0, static_cast<int>(std::ceil(std::log2(std::max(zHi - zLo, 1e-6 * sceneSize))))) / 8.0;
    c.zNear = (std::floor(zHi / step) + 1.0) * step; // one step of margin towards the light
    c.zFar = (std::ceil(zLo / step) - 1.0) * step;

    for (int e = first; e <= last; ++e) setup.views.push_back(clipmapLevelView(c, e, in.camera.wsEye));
    setup.clipmap = c;
    return setup;
}

} // namespace shadowkit::core
