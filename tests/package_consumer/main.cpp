// Uses only shadowkit::core: camera, light and bounds in, matrices out.
#include <shadowkit/core/shadow_setup.h>
#include <shadowkit/core/version.h>
#include <shadowkit/shadowkit_c.h>

#include <cmath>
#include <cstdio>

int main() {
    using namespace shadowkit::core;
    ShadowSetupInputs in;
    in.wsSceneBounds = Aabb::fromMinMax(Vec3(-512, 0, -512), Vec3(512, 30, 512));
    in.light = DirectionalLight::fromSunAngles(45, 90).value();
    const auto setup = computeShadowSetup(in);
    if (!setup || !std::isfinite(setup->views[0].clipFromWorld[0][0])) return 1;
    // The C API is installed with the core (its export header too).
    shadowkit_inputs c;
    shadowkit_default_inputs(&c);
    c.scene_min[0] = c.scene_min[2] = -512, c.scene_max[0] = c.scene_max[2] = 512, c.scene_max[1] = 30;
    shadowkit_setup out;
    char error[200];
    if (shadowkit_compute_setup(&c, &out, error, sizeof error) != 0) return 2;
    std::printf("shadowkit %s: %s set-up with %zu body points\n", SHADOWKIT_VERSION_STRING,
                techniqueName(setup->technique).data(), setup->body.vertices().size());
    return 0;
}
