// Temporal hysteresis for shadow set-ups: a set-up fitted for a camera a little larger than
// the real one is kept, matrices unchanged, for as long as the real camera stays inside what
// it was fitted for. While it is kept, every shadow lies on the same texels from frame to
// frame — no flicker at all on still receivers, for any technique, warped or not — and when
// the camera leaves, one refit. This is how `--stabilize` makes LiSPSM and TSM stable: their
// texel grids cannot be snapped as a uniform map's can (a texel's size varies over a warped
// map, so no shift of it resamples the same world points), but they can be held.
#pragma once

#include "shadowkit/core/camera.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/shadow_setup.h"

#include <optional>

namespace shadowkit::core {

struct HysteresisOptions {
    double radiusMetres = 4.0; // the eye may move this far from where the set-up was fitted, > 0
    double turnDegrees = 5.0;  // and the view direction turn this much, [0, 45]
};

// Fails naming the field ("hysteresis.radius", "hysteresis.turn").
Status validate(const HysteresisOptions& options);

// A camera whose frustum holds the frustum of every camera with the same projection and up
// vector, its eye within `radiusMetres` of `camera`'s and its direction within `turnDegrees`
// of it: both fields of view widened to hold every turned camera's corner rays, the eye moved
// back along the view until the ball of radius r round it is inside (r / sin of the narrower
// widened half-angle; a frustum from any eye in the ball whose rays lie within the widened
// angles stays inside, the pyramid being convex), the far plane beyond the farthest frustum
// corner of any of them, the near plane no farther than the nearest real eye can be.
// Precondition: camera.validate(), validate(options).
PerspectiveCamera enclosingCamera(const PerspectiveCamera& camera, const HysteresisOptions& options);

class SetupHysteresis {
public:
    explicit SetupHysteresis(HysteresisOptions options = {}) : m_options(options) {}

    // This frame's set-up: the kept one while the camera is within reach of the one it was
    // fitted for and nothing else changed (light, scene bounds grown, technique, map size,
    // projection), else a new one fitted for enclosingCamera(inputs.camera).
    Result<ShadowSetup> next(const ShadowSetupInputs& inputs);
    bool refitted() const { return m_refitted; } // by the last next()
    void reset() { m_fit.reset(); }

private:
    bool holds(const ShadowSetupInputs& inputs) const;

    HysteresisOptions m_options;
    struct Fit {
        ShadowSetupInputs inputs; // as given (the real camera)
        ShadowSetup setup;
    };
    std::optional<Fit> m_fit;
    bool m_refitted = false;
};

} // namespace shadowkit::core
