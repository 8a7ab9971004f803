// Predicted pixels per texel at visible receivers (Wimmer et al. 2004 §4.1; sampling_error.h).
#include "shadowkit/core/sampling_error.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace shadowkit::core {

double pixelsPerTexel(const glm::dmat2& j) {
    // Singular values of a 2x2 matrix: s² = (S ± √(S² − 4 det²)) / 2, S = Σ entries². The
    // largest of the inverse's is 1 / the smallest of this one.
    const double a = j[0][0], b = j[1][0], c = j[0][1], d = j[1][1];
    const double s = a * a + b * b + c * c + d * d;
    const double det = a * d - b * c;
    const double root = std::sqrt(std::max(0.0, s * s - 4.0 * det * det));
    const double smallest = std::sqrt(std::max(0.0, 0.5 * (s - root)));
    return smallest > 0.0 ? 1.0 / smallest : std::numeric_limits<double>::infinity();
}

double percentileInPlace(std::span<double> values, double q) {
    if (values.empty()) return 0.0;
    const auto k = static_cast<size_t>(std::min(q * static_cast<double>(values.size()), double(values.size() - 1)));
    std::nth_element(values.begin(), values.begin() + static_cast<ptrdiff_t>(k), values.end());
    return values[k];
}

double samplingObjective(const SamplingFigures& figures) { return figures.p95 + figures.undersampledFraction; }

namespace {

// Derivative of the normalised device xy of clip = C·(p, 1) along the direction t:
// d(c.xy / c.w) = (c'.xy c.w − c.xy c'.w) / c.w², with c' = C·(t, 0).
Vec2 ndcDerivative(const Vec4& clip, const Mat4& clipFrom, const Vec3& t) {
    const Vec4 dc = clipFrom * Vec4(t, 0.0);
    return (Vec2(dc) * clip.w - Vec2(clip) * dc.w) / (clip.w * clip.w);
}

// Two unit vectors spanning the plane perpendicular to the unit `n`.
void tangentBasis(const Vec3& n, Vec3& u, Vec3& v) {
    const Vec3 helper = std::abs(n.x) < 0.9 ? Vec3(1.0, 0.0, 0.0) : Vec3(0.0, 1.0, 0.0);
    u = glm::normalize(glm::cross(n, helper));
    v = glm::cross(n, u);
}

} // namespace

std::vector<ReceiverSample> receiverSamples(const RasterBuffers& raster, const PerspectiveCamera& camera,
                                            const DirectionalLight& light, size_t maxSamples) {
    std::vector<ReceiverSample> out;
    const size_t n = static_cast<size_t>(std::max(raster.width, 0)) * static_cast<size_t>(std::max(raster.height, 0));
    if (maxSamples == 0 || raster.viewDepth.size() != n || raster.wsNormal.size() != n) return out;
    const Vec3 towardsLight = light.wsTowardsLight();
    std::vector<size_t> facing;
    for (size_t i = 0; i < n; ++i) {
        const float depth = raster.viewDepth[i];
        if (!(depth > 0.0f) || !std::isfinite(depth)) continue;
        if (facesLight(Vec3(raster.wsNormal[i]), towardsLight)) facing.push_back(i);
    }
    // The view ray through a pixel centre, scaled to view depth 1 (view space looks down −z).
    const Mat4 worldFromView = glm::inverse(camera.viewFromWorld());
    const double tanY = std::tan(glm::radians(camera.fovYDegrees) * 0.5), tanX = tanY * camera.aspect;
    const size_t count = std::min(maxSamples, facing.size());
    out.reserve(count);
    for (size_t k = 0; k < count; ++k) {
        const size_t i = facing[k * facing.size() / count];
        const int x = static_cast<int>(i % size_t(raster.width)), y = static_cast<int>(i / size_t(raster.width));
        const double ndcX = (2.0 * (x + 0.5)) / raster.width - 1.0;
        const double ndcY = 1.0 - (2.0 * (y + 0.5)) / raster.height; // rows run down
        const Vec3 vsPoint = Vec3(ndcX * tanX, ndcY * tanY, -1.0) * double(raster.viewDepth[i]);
        out.push_back({Vec3(worldFromView * Vec4(vsPoint, 1.0)), glm::normalize(Vec3(raster.wsNormal[i]))});
    }
    return out;
}

Result<SamplingErrorModel> SamplingErrorModel::create(const PerspectiveCamera& camera, int width, int height,
                                                      std::span<const ReceiverSample> samples) {
    if (auto s = camera.validate(); !s) return s.errorInfo();
    if (width <= 0 || height <= 0 || width > kMaxMapSize || height > kMaxMapSize)
        return makeError("sampling model: image size " + std::to_string(width) + "x" + std::to_string(height) +
                         " is not in [1, " + std::to_string(kMaxMapSize) + "]");
    SamplingErrorModel model;
    model.m_camera = camera;
    PerspectiveCamera atOrigin = camera;
    atOrigin.wsEye = Vec3(0.0);
    const Mat4 clipFromEyeRelative = atOrigin.clipFromWorld();
    const Vec3 forward = glm::normalize(camera.wsDirection);
    const Vec2 pixelScale(0.5 * width, -0.5 * height); // ndc → pixels, rows running down
    model.m_samples.reserve(samples.size());
    for (const ReceiverSample& s : samples) {
        const double normalLength = glm::length(s.wsNormal);
        if (!(normalLength > 0.0) || !std::isfinite(normalLength)) continue;
        Sample out;
        out.esPosition = s.wsPosition - camera.wsEye;
        out.viewDepth = glm::dot(out.esPosition, forward);
        const Vec4 clip = clipFromEyeRelative * Vec4(out.esPosition, 1.0);
        if (!(clip.w > 0.0) || !std::isfinite(out.viewDepth)) continue;
        tangentBasis(s.wsNormal / normalLength, out.tangentU, out.tangentV);
        const glm::dmat2 pixelFromTangent(ndcDerivative(clip, clipFromEyeRelative, out.tangentU) * pixelScale,
                                          ndcDerivative(clip, clipFromEyeRelative, out.tangentV) * pixelScale);
        const double det = glm::determinant(pixelFromTangent);
        if (!(std::abs(det) > 1e-12) || !std::isfinite(det)) continue; // edge-on: no pixel sees it
        out.tangentFromPixel = glm::inverse(pixelFromTangent);
        model.m_samples.push_back(out);
    }
    return model;
}

std::optional<Vec2> SamplingErrorModel::viewDepthRange() const {
    if (m_samples.empty()) return std::nullopt;
    Vec2 range(std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity());
    for (const Sample& s : m_samples) range = Vec2(std::min(range.x, s.viewDepth), std::max(range.y, s.viewDepth));
    return range;
}

void SamplingErrorModel::predict(const ShadowSetup& setup, std::span<double> out) const {
    const size_t maps = setup.views.size();
    if (maps == 0) {
        std::fill(out.begin(), out.end(), std::numeric_limits<double>::infinity());
        return;
    }
    // The views' eye-relative matrices take p − setup.wsEye; the samples are relative to the camera's eye.
    const Vec3 toSetupEye = m_camera.wsEye - setup.wsEye;
    const double texelScale = 0.5 * setup.mapSize;
    for (size_t i = 0; i < m_samples.size() && i < out.size(); ++i) {
        const Sample& s = m_samples[i];
        size_t map = 0;
        if (setup.clipmap) // a virtual clipmap: the level the marking and the lookup pick
            map =
                size_t(clipmapLevelHolding(setup, s.viewDepth, s.esPosition + m_camera.wsEye).value_or(int(maps) - 1));
        while (map + 1 < maps && setup.views[map].split && s.viewDepth > setup.views[map].split->y) ++map;
        const Mat4& clipFrom = setup.views[map].clipFromEyeRelative;
        const Vec4 clip = clipFrom * Vec4(s.esPosition + toSetupEye, 1.0);
        const glm::dmat2 texelFromTangent(ndcDerivative(clip, clipFrom, s.tangentU) * texelScale,
                                          ndcDerivative(clip, clipFrom, s.tangentV) * texelScale);
        const double ppt = pixelsPerTexel(texelFromTangent * s.tangentFromPixel);
        out[i] = std::isfinite(ppt) ? ppt : std::numeric_limits<double>::infinity();
    }
}

double SamplingErrorModel::predictUndersampled(const ShadowSetup& setup) const {
    m_scratch.resize(m_samples.size());
    predict(setup, m_scratch);
    size_t undersampled = 0;
    for (const double p : m_scratch) undersampled += p > 1.0;
    return m_scratch.empty() ? 0.0 : double(undersampled) / double(m_scratch.size());
}

SamplingFigures SamplingErrorModel::figures(const ShadowSetup& setup) const {
    SamplingFigures f;
    f.samples = m_samples.size();
    if (m_samples.empty()) return f;
    f.undersampledFraction = predictUndersampled(setup);
    // Ascending quantiles: each nth_element leaves the larger values above its index.
    f.p50 = percentileInPlace(m_scratch, 0.50);
    f.p95 = percentileInPlace(m_scratch, 0.95);
    f.p99 = percentileInPlace(m_scratch, 0.99);
    return f;
}

double SamplingErrorModel::objective(const ShadowSetup& setup) const {
    if (m_samples.empty()) return samplingObjective({});
    SamplingFigures f;
    f.undersampledFraction = predictUndersampled(setup);
    f.p95 = percentileInPlace(m_scratch, 0.95);
    return samplingObjective(f);
}

SamplingErrorModel SamplingErrorModel::subsampled(size_t maxSamples) const {
    SamplingErrorModel out;
    out.m_camera = m_camera;
    const size_t count = std::min(maxSamples, m_samples.size());
    out.m_samples.reserve(count);
    for (size_t k = 0; k < count; ++k) out.m_samples.push_back(m_samples[k * m_samples.size() / count]);
    return out;
}

} // namespace shadowkit::core
