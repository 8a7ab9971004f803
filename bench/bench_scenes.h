// What the benchmarks share: the default forest and the leafy one (each built once), a
// standard view resolved over either, and the `flythrough` path's frames over any scene — the
// moving camera a benchmark iterates over so that no two iterations share their inputs.
#pragma once

#include "shadowkit/core/result.h"
#include "shadowkit/scene/camera_path.h"
#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/views.h"

#include <string>
#include <vector>

namespace shadowkit::bench {

inline const scene::Scene& defaultForest() {
    static const scene::Scene s = [] {
        scene::ForestOptions o;
        o.trees = 10000;
        return scene::makeForest(o);
    }();
    return s;
}

// The leafy forest of `--forest leafy` (10,000 trees of wood and alpha-tested leaf cards).
inline const scene::Scene& leafyForest() {
    static const scene::Scene s = [] {
        scene::ForestOptions o;
        o.kind = scene::ForestKind::Leafy;
        o.trees = 10000;
        return scene::makeForest(o);
    }();
    return s;
}

// The standard view of that name over `over`; an error names what is missing.
inline core::Result<scene::ResolvedView> standardView(const std::string& name,
                                                      const scene::Scene& over = defaultForest()) {
    const auto views = scene::loadViews(std::filesystem::path(SHADOWKIT_SOURCE_DATA_DIR) / "views.json");
    if (!views) return views.errorInfo();
    const auto spec = scene::findView(*views, name);
    if (!spec) return spec.errorInfo();
    return scene::resolveView(*spec, over);
}

// Every frame of data/paths/flythrough.json over `scene` (cameras on its terrain, the path's own
// sun); an error names what is missing.
inline core::Result<std::vector<scene::ResolvedView>> flythroughViews(const scene::Scene& scene) {
    const auto path = scene::findCameraPath("flythrough", std::filesystem::path(SHADOWKIT_SOURCE_DATA_DIR) / "paths");
    if (!path) return path.errorInfo();
    std::vector<scene::ResolvedView> views;
    for (int i = 0; i < path->frames; ++i) {
        auto view = scene::viewAt(*path, scene, path->timeOfFrame(i));
        if (!view) return view.errorInfo();
        views.push_back(std::move(view).value());
    }
    return views;
}

} // namespace shadowkit::bench
