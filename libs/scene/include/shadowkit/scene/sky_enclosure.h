// A model shipped inside its sky: a sky sphere, dome or box round the scene.
//
// Game and web assets often bring their sky as a mesh — a sphere or box many times the size of
// the model, lit by nothing (an unlit material or an emissive texture), which an engine draws
// first and tells not to cast shadows. A file cannot say so in glTF or OBJ, and to a shadow map and
// a ray tracer such a mesh is a caster like any other: it stands between every point of the model
// and every sun above the horizon, so the whole model is in its shadow, truth and raster agreeing
// that nothing is lit — every figure then measures nothing.
//
// What is left out is what no sun could get past: a static instance that
// - is at least kSkyExtentRatio times the rest of the scene across (box diagonals; a room is not
//   its furniture's sky),
// - holds the rest's box within its own across the ground and at the top (a dome ends at the
//   horizon, the ground below it may reach lower), and
// - is met by every ray from the top of the rest's box towards the sky — from its four top
//   corners and its top's middle, at elevations from 5° to the zenith, all round — so that it
//   hides the sky from the scene whatever the sun.
// A terrain round a village in a valley leaves the sky open above it; a closed hall no bigger
// than kSkyExtentRatio times its contents stays a hall. Several skies one in another are each
// left out, the outermost first.
#pragma once

#include "shadowkit/scene/scene.h"

#include <string>
#include <vector>

namespace shadowkit::scene {

/// How many times the rest of the scene's box diagonal a sky's box diagonal is at least.
inline constexpr double kSkyExtentRatio = 4.0;

/// One instance left out as a sky, and what made it one.
struct SkyEnclosure {
    InstanceRef instance;  ///< into the scene as it was before anything was left out
    std::string meshName;  ///< its mesh's name (may be empty)
    double skyMetres = 0;  ///< its box's diagonal
    double restMetres = 0; ///< the rest of the scene's box diagonal, without it
};

/// The static instances of `scene` that hide the whole sky from the rest of it (above), the
/// outermost first. Reads the scene only.
std::vector<SkyEnclosure> findSkyEnclosures(const Scene& scene);

/// Leaves those instances out of `scene` (a batch left with none is dropped, with its mesh when no
/// other batch draws it; tracks and deformations follow their batches), and returns them.
std::vector<SkyEnclosure> leaveOutSkyEnclosures(Scene& scene);

} // namespace shadowkit::scene
