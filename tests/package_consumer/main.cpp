// Uses only shadowkit::core: camera, light and bounds in, matrices out.
#include <shadowkit/core/shadow_setup.h>
#include <shadowkit/core/version.h>

#include <cmath>
#include <cstdio>

int main() {
    using namespace shadowkit::core;
    ShadowSetupInputs in;
    in.wsSceneBounds = Aabb::fromMinMax(Vec3(-512, 0, -512), Vec3(512, 30, 512));
    in.light = DirectionalLight::fromSunAngles(45, 90).value();
    const auto setup = computeShadowSetup(in);
    if (!setup || !std::isfinite(setup->views[0].clipFromWorld[0][0])) return 1;
    std::printf("shadowkit %s: %s set-up with %zu body points\n", SHADOWKIT_VERSION_STRING, techniqueName(setup->technique).data(),
                setup->body.vertices().size());
    return 0;
}
