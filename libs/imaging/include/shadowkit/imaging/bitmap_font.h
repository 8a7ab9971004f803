// A 5x7 pixel bitmap font for labels in report images (plots, colour bars), so the
// project needs no font library. Upper-case letters, digits and . , : / - = ( ) % only;
// lower-case letters are drawn as upper case, anything else as a space.
#pragma once

#include "shadowkit/scene/image.h"

#include <string_view>

namespace shadowkit::imaging {

inline constexpr int kGlyphWidth = 5, kGlyphHeight = 7, kGlyphAdvance = 6; // pixels at scale 1

// Draws `text` with its top-left corner at (x, y); clipped to the image.
void drawText(scene::Image& image, int x, int y, std::string_view text, const uint8_t rgb[3], int scale = 1);
int textWidth(std::string_view text, int scale = 1);

} // namespace shadowkit::imaging
