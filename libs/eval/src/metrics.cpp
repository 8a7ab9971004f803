#include "shadowkit/eval/metrics.h"

#include "shadowkit/core/sampling_error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace shadowkit::eval {

namespace {

// Figures from per-pixel classes and pixels-per-texel values; `ppt` is reordered.
void finishFigures(Figures& f, int64_t falseShadow, int64_t falseLit, int64_t undersampled, std::vector<double>& ppt) {
    if (f.validPx == 0) return;
    const double scale = 100.0 / static_cast<double>(f.validPx);
    f.falseShadowPct = scale * static_cast<double>(falseShadow);
    f.falseLitPct = scale * static_cast<double>(falseLit);
    f.wrongPct = f.falseShadowPct + f.falseLitPct;
    f.undersampledPct = scale * static_cast<double>(undersampled);
    // The same percentiles as the sampling model predicts (core/sampling_error.h).
    f.pixelsPerTexelP50 = core::percentileInPlace(ppt, 0.50);
    f.pixelsPerTexelP95 = core::percentileInPlace(ppt, 0.95);
    f.pixelsPerTexelP99 = core::percentileInPlace(ppt, 0.99);
}

// Higher matters more when several lights' classes meet in one pixel.
int weight(PixelClass c) {
    switch (c) {
    case PixelClass::NotEvaluated:
        return 0;
    case PixelClass::Excluded:
        return 1;
    case PixelClass::LitCorrect:
        return 2;
    case PixelClass::ShadowCorrect:
        return 3;
    case PixelClass::FalseLit:
        return 4;
    case PixelClass::FalseShadow:
        return 5;
    }
    return 0;
}

} // namespace

core::Result<Comparison> combine(std::span<const Comparison* const> parts) {
    if (parts.empty()) return core::makeError("combine: no comparisons");
    if (parts.size() == 1) return *parts[0];
    const size_t n = parts[0]->classes.size();
    Comparison out;
    out.classes.assign(n, PixelClass::NotEvaluated);
    out.pixelsPerTexel.assign(n, std::numeric_limits<float>::quiet_NaN());
    int64_t falseShadow = 0, falseLit = 0, undersampled = 0;
    std::vector<double> ppt;
    for (const Comparison* part : parts) {
        if (part->classes.size() != n || part->pixelsPerTexel.size() != n)
            return core::makeError("combine: comparisons of different sizes");
        out.figures.validPx += part->figures.validPx;
        out.figures.excludedPx += part->figures.excludedPx;
        for (size_t i = 0; i < n; ++i) {
            const PixelClass c = part->classes[i];
            if (weight(c) > weight(out.classes[i])) out.classes[i] = c;
            falseShadow += c == PixelClass::FalseShadow;
            falseLit += c == PixelClass::FalseLit;
            const float p = part->pixelsPerTexel[i];
            if (std::isnan(p)) continue;
            ppt.push_back(p);
            undersampled += p > 1.0f;
            if (!(out.pixelsPerTexel[i] >= p)) out.pixelsPerTexel[i] = p;
        }
    }
    finishFigures(out.figures, falseShadow, falseLit, undersampled, ppt);
    return out;
}

core::Result<Comparison> compare(const core::RasterBuffers& raster, const TruthBuffers& truth,
                                 const CompareOptions& options) {
    if (raster.width != truth.width || raster.height != truth.height)
        return core::makeError("compare: raster " + std::to_string(raster.width) + "x" + std::to_string(raster.height) +
                               " and truth " + std::to_string(truth.width) + "x" + std::to_string(truth.height) +
                               " differ");
    const size_t n = static_cast<size_t>(raster.width) * static_cast<size_t>(raster.height);
    Comparison out;
    out.classes.assign(n, PixelClass::NotEvaluated);
    out.pixelsPerTexel.assign(n, std::numeric_limits<float>::quiet_NaN());
    int64_t falseShadow = 0, falseLit = 0, undersampled = 0;
    std::vector<double> ppt;
    for (size_t i = 0; i < n; ++i) {
        if (!truth.surfaceId[i] || !truth.facesLight[i]) continue;
        const double depthRay = truth.viewDepth[i];
        const bool agree = raster.surfaceId[i] == truth.surfaceId[i] &&
                           std::abs(raster.viewDepth[i] - depthRay) <= options.depthTolerance * depthRay;
        if (!agree) {
            out.classes[i] = PixelClass::Excluded;
            ++out.figures.excludedPx;
            continue;
        }
        ++out.figures.validPx;
        const bool renderedLit = raster.shadowTerm[i] >= options.shadowThreshold;
        const bool truthLit = truth.lit[i] != 0;
        if (renderedLit == truthLit)
            out.classes[i] = truthLit ? PixelClass::LitCorrect : PixelClass::ShadowCorrect;
        else if (truthLit)
            out.classes[i] = PixelClass::FalseShadow, ++falseShadow;
        else
            out.classes[i] = PixelClass::FalseLit, ++falseLit;
        if (raster.texelFromPixel.empty()) continue; // no map known (a mask from elsewhere: eval/score.h)
        const double p = core::pixelsPerTexel(glm::dmat2(raster.texelFromPixel[i]));
        out.pixelsPerTexel[i] = static_cast<float>(p);
        ppt.push_back(p);
        undersampled += p > 1.0;
    }
    finishFigures(out.figures, falseShadow, falseLit, undersampled, ppt);
    return out;
}

} // namespace shadowkit::eval
