// Scenes and views the rendering tests share: a small procedural forest and a standard
// view placed over it.
#pragma once

#include "shadowkit/core/camera.h"
#include "shadowkit/gl/render_settings.h"
#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/image.h"
#include "shadowkit/scene/views.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>

namespace shadowkit::gl::testing {

inline scene::Scene smallForest(int trees, double terrainSize, int terrainResolution) {
    scene::ForestOptions o;
    o.trees = trees;
    o.terrainSize = terrainSize;
    o.terrainResolution = terrainResolution;
    return scene::makeForest(o);
}

// A small leafy forest (alpha-tested cards, their levels down to billboard clouds): 300 trees on
// 300 m, a few rocks and buildings, nothing moving.
inline scene::Scene smallLeafyForest() {
    scene::ForestOptions o;
    o.kind = scene::ForestKind::Leafy;
    o.trees = 300, o.terrainSize = 300, o.terrainResolution = 16;
    o.rocks = 4, o.buildings = 2, o.movers = 0;
    return scene::makeForest(o);
}

// 20 m from the origin and 10 m up, looking at it: the box-over-plane tests' camera.
inline core::PerspectiveCamera obliqueCamera() {
    core::PerspectiveCamera cam;
    cam.wsEye = {0, 10, 20};
    cam.wsDirection = -cam.wsEye; // at the origin
    cam.fovYDegrees = 40;
    cam.aspect = 1.0;
    cam.zNear = 0.5;
    cam.zFar = 60;
    return cam;
}

// Luminance of the pixel of `image`, drawn by `cam`, that shows world point `ws`.
inline double luminanceAt(const scene::Image& image, const core::PerspectiveCamera& cam, const core::Vec3& ws) {
    const core::Vec4 cs = cam.clipFromWorld() * core::Vec4(ws, 1.0);
    const int x = static_cast<int>((cs.x / cs.w * 0.5 + 0.5) * image.width);
    const int y = static_cast<int>((0.5 - cs.y / cs.w * 0.5) * image.height); // top row first
    const uint8_t* p = image.pixel(x, y);
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

// The settings of a small frame (width x height pixels) with this culling.
inline RenderSettings smallFrame(int width, int height, Culling culling) {
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.culling = culling;
    return settings;
}

// The named view of data/views.json over `scene`; a failed test and a default view when
// the file or the view is missing.
inline scene::ResolvedView standardView(const scene::Scene& scene, const std::string& name) {
    auto views = scene::loadViews(std::filesystem::path(SHADOWKIT_SOURCE_DATA_DIR) / "views.json");
    if (!views) {
        ADD_FAILURE() << views.error();
        return {};
    }
    auto spec = scene::findView(*views, name);
    if (!spec) {
        ADD_FAILURE() << spec.error();
        return {};
    }
    return scene::resolveView(*spec, scene);
}

} // namespace shadowkit::gl::testing
