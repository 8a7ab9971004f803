// View files (data/views.json's format): parsed views resolve over a small forest, and framed
// over a scene without ground, to finite cameras and lights; bad files give a one-line error
// naming the file.
#include "fuzz_support.h"

#include "shadowkit/scene/views.h"

#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace shadowkit;
    const auto file = fuzz::writeInput(data, size, ".json");
    const auto views = scene::loadViews(file);
    if (!views) {
        if (views.error().find('\n') != std::string::npos || views.error().find(file.string()) == std::string::npos)
            std::abort();
        return 0;
    }
    for (const scene::ViewSpec& spec : *views)
        for (const scene::Scene* world : {&fuzz::smallForest(), &fuzz::smallModel()}) {
            const scene::ResolvedView view = scene::resolveView(spec, *world);
            if (!view.camera.validate() || !core::isFinite(view.light.wsDirection))
                std::abort(); // a parsed view is a usable one
            if (view.framed != (world == &fuzz::smallModel())) std::abort();
        }
    return 0;
}
