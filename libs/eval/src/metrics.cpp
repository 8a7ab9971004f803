#include "shadowkit/eval/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace shadowkit::eval {

double pixelsPerTexel(const glm::mat2& j) {
    // Singular values of a 2x2 matrix: s² = (S ± √(S² − 4 det²)) / 2, S = Σ entries².
    const double a = j[0][0], b = j[1][0], c = j[0][1], d = j[1][1];
    const double s = a * a + b * b + c * c + d * d;
    const double det = a * d - b * c;
    const double root = std::sqrt(std::max(0.0, s * s - 4.0 * det * det));
    const double smallest = std::sqrt(std::max(0.0, 0.5 * (s - root)));
    return smallest > 0.0 ? 1.0 / smallest : std::numeric_limits<double>::infinity();
}

namespace {

// Figures from per-pixel classes and pixels-per-texel values; `ppt` is reordered.
void finishFigures(Figures& f, int64_t falseShadow, int64_t falseLit, int64_t undersampled, std::vector<double>& ppt) {
    if (f.validPx == 0) return;
    const double scale = 100.0 / static_cast<double>(f.validPx);
    f.falseShadowPct = scale * static_cast<double>(falseShadow);
    f.falseLitPct = scale * static_cast<double>(falseLit);
    f.wrongPct = f.falseShadowPct + f.falseLitPct;
    f.undersampledPct = scale * static_cast<double>(undersampled);
    auto percentile = [&](double q) {
        const auto k = static_cast<size_t>(std::min(q * static_cast<double>(ppt.size()), double(ppt.size() - 1)));
        std::nth_element(ppt.begin(), ppt.begin() + static_cast<ptrdiff_t>(k), ppt.end());
        return ppt[k];
    };
    f.pixelsPerTexelP50 = percentile(0.50);
    f.pixelsPerTexelP99 = percentile(0.99);
}

// Higher matters more when several lights' classes meet in one pixel.
int weight(PixelClass c) {
    switch (c) {
    case PixelClass::NotEvaluated: return 0;
    case PixelClass::Excluded: return 1;
    case PixelClass::LitCorrect: return 2;
    case PixelClass::ShadowCorrect: return 3;
    case PixelClass::FalseLit: return 4;
    case PixelClass::FalseShadow: return 5;
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
        if (part->classes.size() != n || part->pixelsPerTexel.size() != n) return core::makeError("combine: comparisons of different sizes");
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

core::Result<Comparison> compare(const core::RasterBuffers& raster, const TruthBuffers& truth, const CompareOptions& options) {
    if (raster.width != truth.width || raster.height != truth.height)
        return core::makeError("compare: raster " + std::to_string(raster.width) + "x" + std::to_string(raster.height) +
                               " and truth " + std::to_string(truth.width) + "x" + std::to_string(truth.height) + " differ");
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
        if (renderedLit == truthLit) out.classes[i] = truthLit ? PixelClass::LitCorrect : PixelClass::ShadowCorrect;
        else if (truthLit) out.classes[i] = PixelClass::FalseShadow, ++falseShadow;
        else out.classes[i] = PixelClass::FalseLit, ++falseLit;
        const double p = pixelsPerTexel(raster.texelFromPixel[i]);
        out.pixelsPerTexel[i] = static_cast<float>(p);
        ppt.push_back(p);
        undersampled += p > 1.0;
    }
    finishFigures(out.figures, falseShadow, falseLit, undersampled, ppt);
    return out;
}

} // namespace shadowkit::eval
