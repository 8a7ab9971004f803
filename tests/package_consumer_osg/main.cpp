// The adapter from the installed package: one shadow camera for a camera over a box, finite.
#include <shadowkit/osg/shadow_map.h>

#include <cmath>
#include <cstdio>

int main() {
    osg::ref_ptr<shadowkit::osgadapter::ShadowMap> shadowMap = new shadowkit::osgadapter::ShadowMap;
    const osg::Matrixd view = osg::Matrixd::lookAt(osg::Vec3d(0, 20, 0), osg::Vec3d(0, 20, -1), osg::Vec3d(0, 1, 0));
    const osg::Matrixd projection = osg::Matrixd::perspective(60.0, 1.5, 0.5, 500.0);
    const osg::BoundingBoxd box(osg::Vec3d(-500, -5, -500), osg::Vec3d(500, 50, 500));
    auto camera = shadowkit::osgadapter::shadowCameraFor(view, projection, INFINITY, osg::Vec3d(-0.5, -0.8, 0.2), box,
                                                         shadowMap->inputs());
    if (!camera) {
        std::printf("%s\n", camera.error().c_str());
        return 1;
    }
    for (int i = 0; i < 16; ++i)
        if (!std::isfinite(camera->projectionMatrix.ptr()[i])) return 1;
    std::printf("shadowkit osg: %s\n", shadowkit::core::techniqueName(camera->setup.technique).data());
    return 0;
}
