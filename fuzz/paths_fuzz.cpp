// Camera path files (data/paths/*.json's format): a parsed path gives, at every frame's time, a
// usable camera under a finite sun over a small forest and over a scene without ground (framed
// there when the path says "on_loaded_scene": "frame") — or, where its eye and target meet
// between keys, the one error viewAt may give; bad files give a one-line error naming the file.
#include "fuzz_support.h"

#include "shadowkit/scene/camera_path.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace shadowkit;
    const auto file = fuzz::writeInput(data, size, ".json");
    const auto path = scene::loadCameraPath(file);
    if (!path) {
        if (path.error().find('\n') != std::string::npos || path.error().find(file.string()) == std::string::npos)
            std::abort();
        return 0;
    }
    // Up to 9 frames spread over the path, its first and last among them, and each key's time.
    std::vector<double> times;
    const int samples = std::min(path->frames, 9);
    for (int i = 0; i < samples; ++i)
        times.push_back(path->timeOfFrame(samples == 1 ? 0 : int(int64_t(i) * (path->frames - 1) / (samples - 1))));
    for (const scene::CameraKey& key : path->camera) times.push_back(key.time);
    for (const double t : times) {
        if (!std::isfinite(t)) std::abort();
        for (const scene::Scene* world : {&fuzz::smallForest(), &fuzz::smallModel()}) {
            const auto view = scene::viewAt(*path, *world, t);
            if (!view) {
                if (view.error().find('\n') != std::string::npos ||
                    view.error().find("eye and target meet") == std::string::npos)
                    std::abort(); // a parsed path fails only where its eye and target meet
                continue;
            }
            if (!view->camera.validate() || !core::isFinite(view->light.wsDirection)) std::abort();
            if (view->framed != (path->frameLoadedScene && world == &fuzz::smallModel())) std::abort();
        }
    }
    return 0;
}
