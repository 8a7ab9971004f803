#include "shadowkit/eval/score.h"

#include "shadowkit/eval/npy.h"
#include "shadowkit/scene/file_read.h"
#include "shadowkit/scene/image.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace shadowkit::eval {

namespace {

// The mask's values as visibility, refused in one line where one is not in [0, 1].
core::Status checkVisibility(const ShadowMask& mask, const std::string& name) {
    for (size_t i = 0; i < mask.visibility.size(); ++i) {
        const float v = mask.visibility[i];
        if (!(v >= 0.0f && v <= 1.0f)) // NaN too
            return core::makeError(name + ": pixel (" + std::to_string(i % size_t(mask.width)) + ", " +
                                   std::to_string(i / size_t(mask.width)) + ") holds " + std::to_string(v) +
                                   ", not a visibility in [0, 1]");
    }
    return core::Ok{};
}

} // namespace

core::Result<ShadowMask> loadShadowMask(const std::filesystem::path& file) {
    const std::string name = file.string();
    ShadowMask mask;
    if (file.extension() == ".npy") {
        auto npy = readNpyImage(file);
        if (!npy) return npy.errorInfo();
        mask = {npy->width, npy->height, std::move(npy->values), {}};
    } else {
        const auto text = scene::readFile(file);
        if (!text) return text.errorInfo();
        const std::vector<uint8_t> bytes(text->begin(), text->end());
        auto png = scene::decodeLevels(bytes, name);
        if (!png) return png.errorInfo();
        mask = {png->width, png->height, std::move(png->level), {}};
        if (!png->alpha.empty()) {
            mask.drawn.resize(png->alpha.size());
            for (size_t i = 0; i < png->alpha.size(); ++i) mask.drawn[i] = png->alpha[i] > 0.5f;
        }
    }
    if (auto s = checkVisibility(mask, name); !s) return s.errorInfo();
    return mask;
}

core::Result<Comparison> scoreMask(const ShadowMask& mask, const TruthBuffers& truth, const ScoreOptions& options) {
    if (mask.width != truth.width || mask.height != truth.height)
        return core::makeError("the mask is " + std::to_string(mask.width) + "×" + std::to_string(mask.height) +
                               " pixels and the camera's image " + std::to_string(truth.width) + "×" +
                               std::to_string(truth.height) +
                               ": render the mask at the camera's size, or give that size");
    const size_t n = mask.visibility.size();
    if (!mask.drawn.empty()) {
        size_t mismatched = 0;
        for (size_t i = 0; i < n; ++i) mismatched += (mask.drawn[i] != 0) != (truth.surfaceId[i] != 0);
        const double fraction = double(mismatched) / double(n);
        if (fraction > options.maxDrawnMismatch) {
            char text[256];
            std::snprintf(text, sizeof text,
                          "the mask's drawn pixels (alpha) and the scene's surfaces from this camera disagree on "
                          "%.1f %% of the image (at most %.1f %%): was it drawn from another camera or of another "
                          "scene?",
                          100.0 * fraction, 100.0 * options.maxDrawnMismatch);
            return core::makeError(text);
        }
    }
    // The mask as the rasterised buffers of eval::compare, on the truth's own surfaces: where
    // the mask drew nothing the surface is missing (0) and the pixel is excluded like a
    // silhouette the rasteriser and the rays disagree on.
    core::RasterBuffers raster;
    raster.width = mask.width;
    raster.height = mask.height;
    raster.shadowTerm = mask.visibility;
    raster.surfaceId = truth.surfaceId;
    raster.viewDepth = truth.viewDepth;
    if (!mask.drawn.empty())
        for (size_t i = 0; i < n; ++i)
            if (!mask.drawn[i]) raster.surfaceId[i] = 0;
    return compare(raster, truth, options.compare);
}

} // namespace shadowkit::eval
