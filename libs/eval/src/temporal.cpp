// Flicker between consecutive frames, against truth, at exactly the same world points: this
// frame's surface points are looked up in the previous frame's shadow maps as well as in
// their own (the caller draws the previous set-up from this camera), so a camera that moves
// over still shadows shows no flicker at all, with no resampling between the two frames'
// pixel grids to blur the figure, and a texel grid that slides with the camera shows the
// whole band its edges jump over. Rendered changes where the truth changed too (a moving sun
// or caster) are not flicker; they are reported apart as truth_change_pct.
#include "shadowkit/eval/temporal.h"

#include "shadowkit/core/conventions.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

namespace shadowkit::eval {
namespace {

constexpr uint8_t kEvaluated = 4, kRenderedLit = 1, kTruthLit = 2;

} // namespace

ShadowStates shadowStates(const core::PerspectiveCamera& camera, const TruthBuffers& truth,
                          const Comparison& comparison) {
    SK_ASSERT(comparison.classes.size() == truth.surfaceId.size(), "shadowStates(): truth and comparison sizes differ");
    ShadowStates s;
    s.camera = camera;
    s.width = truth.width;
    s.height = truth.height;
    s.surfaceId = truth.surfaceId;
    s.viewDepth = truth.viewDepth;
    s.wsPosition = truth.wsPosition;
    s.state.assign(comparison.classes.size(), 0);
    for (size_t i = 0; i < comparison.classes.size(); ++i) {
        switch (comparison.classes[i]) {
        case PixelClass::LitCorrect:
            s.state[i] = kEvaluated | kRenderedLit | kTruthLit;
            break;
        case PixelClass::ShadowCorrect:
            s.state[i] = kEvaluated;
            break;
        case PixelClass::FalseShadow:
            s.state[i] = kEvaluated | kTruthLit;
            break;
        case PixelClass::FalseLit:
            s.state[i] = kEvaluated | kRenderedLit;
            break;
        case PixelClass::NotEvaluated:
        case PixelClass::Excluded:
            break;
        }
    }
    return s;
}

TemporalFigures compareFrames(const ShadowStates& previous, const ShadowStates& current,
                              const PreviousShadowsHere& before, const TemporalOptions& options,
                              std::span<const uint32_t> reshaped) {
    SK_ASSERT(before.raster.shadowTerm.size() == current.state.size() && before.truthLit.size() == current.state.size(),
              "compareFrames(): the previous shadows must be of this frame's pixels");
    TemporalFigures out;
    const core::Mat4 previousClipFromWorld = previous.camera.clipFromWorld();
    const core::Vec3 previousForward = glm::normalize(previous.camera.wsDirection);
    auto sameDepth = [&](double a, double b) { return std::abs(a - b) <= options.depthTolerance * b; };
    // Was this world point in view last frame? One of the four pixels round its projection
    // shows its surface at its depth.
    auto seenBefore = [&](const core::Vec3& ws, uint32_t surface) {
        const core::Vec4 cs = previousClipFromWorld * core::Vec4(ws, 1.0);
        if (!(cs.w > 0.0)) return false;
        const double px = (cs.x / cs.w * 0.5 + 0.5) * previous.width - 0.5;
        const double py = (0.5 - cs.y / cs.w * 0.5) * previous.height - 0.5;
        const int x0 = static_cast<int>(std::floor(px)), y0 = static_cast<int>(std::floor(py));
        const double depth = glm::dot(ws - previous.camera.wsEye, previousForward);
        for (int k = 0; k < 4; ++k) {
            const int x = x0 + k % 2, y = y0 + k / 2;
            if (x < 0 || y < 0 || x >= previous.width || y >= previous.height) continue;
            const size_t j = static_cast<size_t>(y) * static_cast<size_t>(previous.width) + static_cast<size_t>(x);
            if ((previous.state[j] & kEvaluated) && previous.surfaceId[j] == surface &&
                sameDepth(previous.viewDepth[j], depth))
                return true;
        }
        return false;
    };
    const std::unordered_set<uint32_t> reshapedSurfaces(reshaped.begin(), reshaped.end());
    int64_t flicker = 0, truthChanged = 0;
    for (size_t i = 0; i < current.state.size(); ++i) {
        const uint8_t now = current.state[i];
        if (!(now & kEvaluated)) continue;
        if (!reshapedSurfaces.empty() && reshapedSurfaces.count(current.surfaceId[i] - 1)) continue;
        if (before.raster.surfaceId[i] != current.surfaceId[i] ||
            !sameDepth(before.raster.viewDepth[i], current.viewDepth[i]))
            continue;
        if (!seenBefore(current.wsPosition[i], current.surfaceId[i])) continue;
        ++out.comparedPx;
        const bool renderedLitBefore = before.raster.shadowTerm[i] >= options.shadowThreshold;
        const bool truthLitBefore = before.truthLit[i] != 0;
        if (truthLitBefore != ((now & kTruthLit) != 0))
            ++truthChanged;
        else if (renderedLitBefore != ((now & kRenderedLit) != 0))
            ++flicker;
    }
    if (out.comparedPx > 0) {
        out.flickerPct = 100.0 * double(flicker) / double(out.comparedPx);
        out.truthChangePct = 100.0 * double(truthChanged) / double(out.comparedPx);
    }
    return out;
}

LevelPops levelPops(const core::RasterBuffers& ownLevels, const core::RasterBuffers& previousLevels,
                    const TemporalOptions& options) {
    SK_ASSERT(ownLevels.surfaceId.size() == previousLevels.surfaceId.size(),
              "levelPops(): both drawings must be of the same camera and size");
    int64_t drawn = 0, surface = 0, shadow = 0;
    for (size_t i = 0; i < ownLevels.surfaceId.size(); ++i) {
        const uint32_t a = ownLevels.surfaceId[i], b = previousLevels.surfaceId[i];
        if (a == 0 && b == 0) continue;
        ++drawn;
        const double depthA = ownLevels.viewDepth[i], depthB = previousLevels.viewDepth[i];
        if (a != b || std::abs(depthA - depthB) > options.depthTolerance * std::max(depthA, depthB)) {
            ++surface;
            continue;
        }
        const bool shadowedA = ownLevels.shadowTerm[i] < options.shadowThreshold;
        const bool shadowedB = previousLevels.shadowTerm[i] < options.shadowThreshold;
        shadow += shadowedA != shadowedB;
    }
    LevelPops out;
    out.drawnPx = drawn;
    if (drawn == 0) return out;
    out.surfacePct = 100.0 * double(surface) / double(drawn);
    out.shadowPct = 100.0 * double(shadow) / double(drawn);
    out.popPct = out.surfacePct + out.shadowPct;
    return out;
}

} // namespace shadowkit::eval
