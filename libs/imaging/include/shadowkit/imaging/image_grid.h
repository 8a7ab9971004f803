// A captioned grid of images (`shadowkit compare`): cells left to right, top to bottom,
// each with its caption word-wrapped underneath in the bitmap font.
#pragma once

#include "shadowkit/scene/image.h"

#include <string>
#include <vector>

namespace shadowkit::imaging {

// `columns` <= 0: about square. Cells take the first image's size (larger ones are cropped).
scene::Image captionedGrid(const std::vector<scene::Image>& cells, const std::vector<std::string>& captions,
                           int columns = 0);

// Greedy word wrap to `width` pixels of the bitmap font at `scale`.
std::vector<std::string> wrapText(const std::string& text, int width, int scale);

} // namespace shadowkit::imaging
