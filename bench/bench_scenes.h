// What the set-up benchmarks share: the default forest (built once; only its bounds matter)
// and a standard view resolved over it.
#pragma once

#include "shadowkit/core/result.h"
#include "shadowkit/scene/forest.h"
#include "shadowkit/scene/views.h"

#include <string>

namespace shadowkit::bench {

inline const scene::Scene& defaultForest() {
    static const scene::Scene s = [] {
        scene::ForestOptions o;
        o.trees = 10000;
        return scene::makeForest(o);
    }();
    return s;
}

// The standard view of that name over the default forest; an error names what is missing.
inline core::Result<scene::ResolvedView> standardView(const std::string& name) {
    const auto views = scene::loadViews(std::filesystem::path(SHADOWKIT_SOURCE_DATA_DIR) / "views.json");
    if (!views) return views.errorInfo();
    const auto spec = scene::findView(*views, name);
    if (!spec) return spec.errorInfo();
    return scene::resolveView(*spec, defaultForest());
}

} // namespace shadowkit::bench
