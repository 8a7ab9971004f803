#include "shadowkit/eval/level_map.h"

#include "shadowkit/eval/maps.h"
#include "shadowkit/imaging/bitmap_font.h"

#include <algorithm>
#include <array>
#include <map>

namespace shadowkit::eval {
namespace {

// The level of global instance `id - 1` in `levels`; id 0 (nothing) and ids out of range: none.
uint8_t levelOf(std::span<const uint8_t> levels, uint32_t id) {
    return id == 0 || id > levels.size() ? kLevelNotDrawn : levels[id - 1];
}

} // namespace

const uint8_t* levelColor(uint8_t level) {
    // The full mesh cool blue; each coarser level warmer, so the rings of a forest read outwards.
    static constexpr uint8_t colors[][3] = {
        {70, 110, 200}, {60, 175, 90}, {235, 200, 50}, {235, 110, 40}, {200, 50, 120}};
    static constexpr uint8_t notDrawn[3] = {150, 150, 150};
    if (level == kLevelNotDrawn || level == kNoCaster) return notDrawn;
    return colors[std::min<size_t>(level, std::size(colors) - 1)];
}

LevelMap levelMap(std::span<const uint32_t> surfaceId, std::span<const uint32_t> casters,
                  std::span<const uint8_t> cameraLevels, std::span<const uint8_t> sunLevels, int width, int height) {
    LevelMap map{width, height, {}, {}};
    const size_t n = size_t(width) * size_t(height);
    map.surface.resize(n);
    map.caster.resize(n);
    for (size_t i = 0; i < n; ++i) {
        map.surface[i] = levelOf(cameraLevels, surfaceId[i]);
        map.caster[i] = casters[i] == 0 ? kNoCaster : levelOf(sunLevels, casters[i]);
    }
    return map;
}

std::vector<CasterLevelFigures> casterLevelFigures(const LevelMap& map, const Comparison& comparison) {
    std::map<uint8_t, CasterLevelFigures> byLevel;
    for (size_t i = 0; i < map.caster.size() && i < comparison.classes.size(); ++i) {
        const PixelClass c = comparison.classes[i];
        if (map.caster[i] == kNoCaster || (c != PixelClass::ShadowCorrect && c != PixelClass::FalseLit)) continue;
        CasterLevelFigures& f = byLevel[map.caster[i]];
        f.level = map.caster[i];
        ++f.shadowedPx;
        if (c == PixelClass::FalseLit) ++f.falseLitPx;
    }
    std::vector<CasterLevelFigures> out;
    for (const auto& [level, figures] : byLevel) out.push_back(figures);
    return out;
}

scene::Image levelMapImage(const LevelMap& map) {
    const int width = map.width, height = map.height;
    const int scale = std::max(1, width / 640); // label size
    const int legendHeight = (imaging::kGlyphHeight + 8) * scale;
    scene::Image image(width, height + legendHeight);
    const uint8_t* dark = ErrorMapColors::notEvaluated; // the error maps' background: no surface drawn
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const size_t i = size_t(y) * size_t(width) + size_t(x);
            if (map.caster[i] != kNoCaster) {
                image.setOpaque(x, y, levelColor(map.caster[i]));
                continue;
            }
            if (map.surface[i] == kLevelNotDrawn) {
                image.setOpaque(x, y, dark);
                continue;
            }
            // Lit or unevaluated surfaces: their own level, faded towards white.
            const uint8_t* c = levelColor(map.surface[i]);
            const uint8_t faded[3] = {uint8_t((c[0] + 2 * 235) / 3), uint8_t((c[1] + 2 * 235) / 3),
                                      uint8_t((c[2] + 2 * 235) / 3)};
            image.setOpaque(x, y, faded);
        }
    for (int y = height; y < height + legendHeight; ++y)
        for (int x = 0; x < width; ++x) image.setOpaque(x, y, dark);
    // Legend: a swatch and a name per level, then the grey of casters no pass drew.
    static constexpr uint8_t white[3] = {255, 255, 255};
    const std::array<std::pair<uint8_t, const char*>, 5> entries{
        {{0, "FULL"}, {1, "LEVEL 1"}, {2, "LEVEL 2"}, {3, "LEVEL 3"}, {kLevelNotDrawn, "NOT DRAWN"}}};
    int x = 4 * scale;
    const int top = height + 4 * scale;
    for (const auto& [level, name] : entries) {
        for (int dy = 0; dy < imaging::kGlyphHeight * scale; ++dy)
            for (int dx = 0; dx < imaging::kGlyphHeight * scale && x + dx < width; ++dx)
                image.setOpaque(x + dx, top + dy, levelColor(level));
        x += (imaging::kGlyphHeight + 3) * scale;
        imaging::drawText(image, x, top, name, white, scale);
        x += imaging::textWidth(name, scale) + 8 * scale;
    }
    return image;
}

} // namespace shadowkit::eval
