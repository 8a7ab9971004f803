#include "shadowkit/gl/receiver_samples.h"

#include "shadowkit/gl/renderer.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace shadowkit::gl {

core::Result<core::RasterBuffers> readReceivers(Renderer& renderer, const core::PerspectiveCamera& camera,
                                                const core::DirectionalLight& light,
                                                const core::ShadowSetup& shadowSetup, const RenderSettings& settings,
                                                const ReceiverSampling& sampling) {
    if (sampling.width < 1)
        return core::fieldError("sampling.width", "must be >= 1, got " + std::to_string(sampling.width));
    RenderSettings small = settings;
    small.width = std::min(sampling.width, settings.width);
    small.height = std::max(1, static_cast<int>(std::lround(double(small.width) * settings.height / settings.width)));
    small.blur.iterations = 0;
    small.receiverMask = false;
    small.filter = core::FilterSettings{};
    // The same levels of detail as the frame: a geometric error is fewer pixels of the
    // smaller image, so the bound shrinks with it (else coarser meshes, other normals).
    small.lodPixelError = settings.lodPixelError * float(small.width) / float(settings.width);
    return renderer.renderSurfaceBuffers(camera, light, shadowSetup, small);
}

} // namespace shadowkit::gl
