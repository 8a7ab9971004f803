// Which level of detail drew what each pixel shows and what shadows it: the report's level map.
//
// Levels of detail trade a caster's exact shape for fewer triangles (a tree's billboard clouds,
// docs/materials.md "Foliage levels of detail"), and a shadow map cannot say which trade a pixel
// paid for: its texels hold a depth, not the level that wrote it. The truth can. The shadow ray
// of a pixel the truth puts in shadow meets a first caster; the renderer says at which level its
// sun pass drew that caster (gl::Renderer::levelsDrawn). So each shadowed pixel gets its
// caster's level, and the figures split by it: of the pixels whose caster was a cloud, how many
// came out lit. A false shadow has no caster in the truth and is not split.
#pragma once

#include "shadowkit/eval/metrics.h"
#include "shadowkit/scene/image.h"

#include <cstdint>
#include <span>
#include <vector>

namespace shadowkit::eval {

// Level values: 0 the full mesh, then coarser levels; these two mark what has none.
inline constexpr uint8_t kLevelNotDrawn = 0xff; // the pass drew no level of it (gl::kLevelNotDrawn)
inline constexpr uint8_t kNoCaster = 0xfe;      // the truth has no caster here (lit, sky, facing away)

struct LevelMap {
    int width = 0, height = 0;
    // Row-major, top row first.
    std::vector<uint8_t> surface; // the camera pass's level of the instance drawn at the pixel (kLevelNotDrawn: none)
    std::vector<uint8_t> caster;  // the sun pass's level of the truth's caster (kNoCaster where it has none)
};

// From the raster's surface ids (global instance + 1, 0 for none), the truth's casters
// (castersAt) and the level each pass drew each global instance at. Ids beyond the levels'
// ranges count as not drawn. Precondition: surfaceId and casters have width × height entries.
LevelMap levelMap(std::span<const uint32_t> surfaceId, std::span<const uint32_t> casters,
                  std::span<const uint8_t> cameraLevels, std::span<const uint8_t> sunLevels, int width, int height);

// The truth's shadowed pixels (valid: ShadowCorrect or FalseLit) split by their caster's level.
struct CasterLevelFigures {
    uint8_t level = 0;      // a level, or kLevelNotDrawn: the sun pass drew no level of the caster
    int64_t shadowedPx = 0; // valid pixels the truth shadows whose caster was drawn at `level`
    int64_t falseLitPx = 0; // of them, rendered lit
};
// One entry per level that casts onto some valid pixel, in increasing level order.
std::vector<CasterLevelFigures> casterLevelFigures(const LevelMap& map, const Comparison& comparison);

// The map as a picture with a legend under it: where the truth is in shadow, the colour of its
// caster's level; elsewhere the surface's own level, faded; the sky and pixels no level drew dark.
scene::Image levelMapImage(const LevelMap& map);
// The legend's colour of a level (coarser levels warmer); kLevelNotDrawn grey.
const uint8_t* levelColor(uint8_t level);

} // namespace shadowkit::eval
