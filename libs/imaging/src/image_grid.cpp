#include "shadowkit/imaging/image_grid.h"

#include "shadowkit/imaging/bitmap_font.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace shadowkit::imaging {

std::vector<std::string> wrapText(const std::string& text, int width, int scale) {
    std::vector<std::string> lines(1);
    std::stringstream words(text);
    for (std::string word; words >> word;) {
        const std::string candidate = lines.back().empty() ? word : lines.back() + " " + word;
        if (textWidth(candidate, scale) > width && !lines.back().empty())
            lines.push_back(word);
        else
            lines.back() = candidate;
    }
    return lines;
}

scene::Image captionedGrid(const std::vector<scene::Image>& cells, const std::vector<std::string>& captions,
                           int columns) {
    const int n = static_cast<int>(cells.size());
    if (n == 0) return {};
    if (columns <= 0) columns = static_cast<int>(std::ceil(std::sqrt(double(n))));
    const int rows = (n + columns - 1) / columns;
    const int cellW = cells[0].width, cellH = cells[0].height, gap = 6, scale = cellW >= 600 ? 2 : 1;
    const int lineH = (kGlyphHeight + 3) * scale;
    size_t captionLines = 1;
    for (const std::string& c : captions) captionLines = std::max(captionLines, wrapText(c, cellW - 8, scale).size());
    const int captionH = static_cast<int>(captionLines) * lineH + 8;
    scene::Image grid(columns * (cellW + gap) + gap, rows * (cellH + captionH + gap) + gap);
    std::fill(grid.rgba.begin(), grid.rgba.end(), uint8_t{255});
    static constexpr uint8_t ink[3] = {20, 20, 20};
    for (int i = 0; i < n; ++i) {
        const scene::Image& cell = cells[size_t(i)];
        const int x0 = gap + (i % columns) * (cellW + gap), y0 = gap + (i / columns) * (cellH + captionH + gap);
        for (int y = 0; y < std::min(cellH, cell.height); ++y)
            std::copy_n(cell.pixel(0, y), 4 * std::min(cellW, cell.width), grid.pixel(x0, y0 + y));
        if (size_t(i) >= captions.size()) continue;
        int lineY = y0 + cellH + 4;
        for (const std::string& line : wrapText(captions[size_t(i)], cellW - 8, scale)) {
            drawText(grid, x0 + 4, lineY, line, ink, scale);
            lineY += lineH;
        }
    }
    return grid;
}

} // namespace shadowkit::imaging
