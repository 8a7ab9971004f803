// shadowkit-osg-sample: a scene drawn by OpenSceneGraph from a camera file, with OSG's own
// shadows or shadowkit's shadow camera, and the shadow term written as a mask for
// `shadowkit score` (docs/engine-integration.md, "OpenSceneGraph"): the sun's, or where the
// camera file has a spot or point light (`shadowkit setup --sun off --light spot:...`), that lamp's.
//
//   shadowkit export --out forest.obj
//   shadowkit setup --view perpendicular > camera.json
//   xvfb-run -a shadowkit-osg-sample forest.obj camera.json mask.png --technique tsm
//   shadowkit score mask.png --view perpendicular --size 640x360
//
// The switch an OSG user makes is one line (below, `makeShadowMap`): a
// shadowkit::osgadapter::ShadowMap where an osgShadow::ViewDependentShadowMap was.
#include "shadowkit/osg/shadow_map.h"

#include "common/sample_options.h"
#include "shadowkit/core/error_driven.h"

#include <osg/LightSource>
#include <osg/Program>
#include <osg/Timer>
#include <osgDB/ReadFile>
#include <osgDB/WriteFile>
#include <osgShadow/ShadowedScene>
#include <osgViewer/Viewer>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

namespace core = shadowkit::core;
namespace samples = shadowkit::samples;

using samples::fail;
using samples::Options;
using samples::Shot;

// A technique a shot may name: OSG's own, or one the adapter draws.
void checkTechnique(const std::string& name) {
    if (name == "osg" || name == "osg-perspective" || name == "osg-split" || name == "auto") return;
    const auto technique = core::parseTechnique(name);
    if (!technique)
        fail("technique " + name + ": not osg, osg-perspective or osg-split (OSG's own) nor one of " +
             core::techniqueNameList());
    if (auto usable = shadowkit::osgadapter::checkTechnique(*technique); !usable) fail(usable.error());
}

// Both kinds of shadow map, with the casters drawn by the fixed-function pipeline: the mask's
// shader below is set on the scene and would otherwise run in the depth pass too.
template <class Base>
class WithPlainCasters : public Base {
public:
    void init() override {
        Base::init();
        if (this->_shadowCastingStateSet.valid())
            this->_shadowCastingStateSet->setAttributeAndModes(new osg::Program,
                                                               osg::StateAttribute::ON | osg::StateAttribute::OVERRIDE);
    }
};

osg::ref_ptr<osgShadow::ShadowTechnique> makeShadowMap(const std::string& name, int mapSize,
                                                       osgShadow::ShadowSettings& settings) {
    const auto side = static_cast<short>(mapSize); // checked in [16, 16384]
    settings.setTextureSize({side, side});
    if (name.rfind("osg", 0) == 0) {
        // OSG's own: a box around what the view sees (osg), its light-space perspective warp
        // (osg-perspective, its default) or that warp split over two maps of half the texels.
        if (name == "osg")
            settings.setShadowMapProjectionHint(osgShadow::ShadowSettings::ORTHOGRAPHIC_SHADOW_MAP);
        else if (name == "osg-perspective" || name == "osg-split")
            settings.setShadowMapProjectionHint(osgShadow::ShadowSettings::PERSPECTIVE_SHADOW_MAP);
        if (name == "osg-split") {
            settings.setNumShadowMapsPerLight(2);
            const auto half = static_cast<short>(std::lround(mapSize / std::sqrt(2.0))); // the same texel memory
            settings.setTextureSize({half, half});
        }
        return new WithPlainCasters<osgShadow::ViewDependentShadowMap>;
    }
    // The one line an OSG user changes: shadowkit's ShadowMap for OSG's ViewDependentShadowMap.
    osg::ref_ptr<WithPlainCasters<shadowkit::osgadapter::ShadowMap>> shadowMap =
        new WithPlainCasters<shadowkit::osgadapter::ShadowMap>;
    if (name == "auto") { // draw() hands it the receivers
        core::AutoOptions options;
        options.cascades = 1;
        options.texelBudget = int64_t(mapSize) * mapSize;
        if (auto valid = shadowMap->setAuto(options); !valid) fail(valid.error());
        return shadowMap;
    }
    const auto technique = core::parseTechnique(name); // checked by checkTechnique
    core::ShadowSetupInputs inputs;
    inputs.technique = *technique;
    shadowMap->setInputs(inputs);
    return shadowMap;
}

// The sun's visibility per pixel, grey, alpha 1 where a surface was drawn: shadow2DProj of
// each map VDSM made, as its own shader reads them, without the shading.
osg::ref_ptr<osg::Program> maskProgram(int maps, unsigned firstUnit) {
    std::string source = "#version 120\n";
    std::string visibility = "1.0";
    for (int i = 0; i < maps; ++i) {
        const std::string n = std::to_string(i), unit = std::to_string(firstUnit + unsigned(i));
        source += "uniform sampler2DShadow shadowTexture" + n + ";\n";
        visibility += " * shadow2DProj(shadowTexture" + n + ", gl_TexCoord[" + unit + "]).r";
    }
    source += "void main() { float lit = " + visibility + "; gl_FragColor = vec4(lit, lit, lit, 1.0); }\n";
    osg::ref_ptr<osg::Program> program = new osg::Program;
    program->addShader(new osg::Shader(osg::Shader::FRAGMENT, source));
    return program;
}

// What the camera sees, for `auto`, in the pbuffer's 8-bit colour over two frames: the
// surfaces' world normals (n / 2 + 1/2), then their view depth over the far plane in 24 bits;
// alpha 1 where a surface was drawn. The read-back an application hands the adapter from its own
// depth and normal buffers (core::receiverSamples).
const char* kSurfaceVertex = R"(#version 120
varying vec3 esPosition;
void main() { esPosition = (gl_ModelViewMatrix * gl_Vertex).xyz; gl_Position = ftransform(); })";
const char* kNormalFragment = R"(#version 120
uniform mat3 worldFromEye;
varying vec3 esPosition;
void main() {
    vec3 n = normalize(cross(dFdx(esPosition), dFdy(esPosition)));
    if (dot(n, -esPosition) < 0.0) n = -n;
    gl_FragColor = vec4(0.5 * (worldFromEye * n) + 0.5, 1.0);
})";
const char* kDepthFragment = R"(#version 120
uniform float zFar;
varying vec3 esPosition;
void main() {
    float d = floor(clamp(-esPosition.z / zFar, 0.0, 1.0) * 16777215.0);
    vec3 bytes = vec3(floor(d / 65536.0), mod(floor(d / 256.0), 256.0), mod(d, 256.0));
    gl_FragColor = vec4(bytes / 255.0, 1.0);
})";

osg::ref_ptr<osg::Program> surfaceProgram(const char* fragment) {
    osg::ref_ptr<osg::Program> program = new osg::Program;
    program->addShader(new osg::Shader(osg::Shader::VERTEX, kSurfaceVertex));
    program->addShader(new osg::Shader(osg::Shader::FRAGMENT, fragment));
    return program;
}

// Draws one shot of the model and writes it; the model is shared between shots.
// The one viewer of every shot: a pbuffer of the mask's size, read back after each frame
// (Xvfb's GLX and Mesa headless). One context for the run: Xvfb resets when its last client
// leaves, and a context opened during the reset finds no display.
struct Viewer {
    osgViewer::Viewer viewer;
    osg::ref_ptr<osg::Image> frame = new osg::Image;
};

void realize(const Options& o, Viewer& v) {
    osg::ref_ptr<osg::GraphicsContext::Traits> traits = new osg::GraphicsContext::Traits;
    traits->readDISPLAY(); // the X display xvfb-run made, not :0
    traits->setUndefinedScreenDetailsToDefaultScreen();
    traits->width = o.width, traits->height = o.height;
    traits->pbuffer = true, traits->alpha = 8, traits->depth = 24, traits->doubleBuffer = false;
    osg::ref_ptr<osg::GraphicsContext> gc = osg::GraphicsContext::createGraphicsContext(traits.get());
    if (!gc) fail("no OpenGL context: run under xvfb-run (OpenSceneGraph's Debian build has GLX, not EGL)");
    v.viewer.setThreadingModel(osgViewer::Viewer::SingleThreaded);
    v.viewer.setLightingMode(osg::View::NO_LIGHT);
    osg::Camera* camera = v.viewer.getCamera();
    camera->setGraphicsContext(gc.get());
    camera->setViewport(0, 0, o.width, o.height);
    camera->setClearColor({0.0f, 0.0f, 0.0f, 0.0f}); // alpha 0: no surface
    camera->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    v.frame->allocateImage(o.width, o.height, 1, GL_RGBA, GL_UNSIGNED_BYTE);
    camera->attach(osg::Camera::COLOR_BUFFER, v.frame.get());
}

// The receivers the shot's camera sees (its viewer camera already placed), top row first.
std::vector<core::ReceiverSample> receiversSeen(const Options& o, const samples::CameraAndSun& view, osg::Node* model,
                                                Viewer& v) {
    osg::StateSet* state = model->getOrCreateStateSet();
    const osg::Matrixd eyeFromWorld = v.viewer.getCamera()->getViewMatrix();
    osg::Matrix3 worldFromEye; // the view's rotation, inverted: its transpose (row vectors)
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) worldFromEye(r, c) = float(eyeFromWorld(c, r));
    state->getOrCreateUniform("worldFromEye", osg::Uniform::FLOAT_MAT3)->set(worldFromEye);
    state->getOrCreateUniform("zFar", osg::Uniform::FLOAT)->set(float(view.zFar));
    v.viewer.setSceneData(model);
    std::vector<unsigned char> normals, depths;
    for (const char* fragment : {kNormalFragment, kDepthFragment}) {
        state->setAttribute(surfaceProgram(fragment));
        v.viewer.frame();
        const unsigned char* data = v.frame->data();
        (fragment == kNormalFragment ? normals : depths).assign(data, data + size_t(o.width) * size_t(o.height) * 4);
    }
    core::RasterBuffers raster;
    raster.width = o.width, raster.height = o.height;
    for (int y = 0; y < o.height; ++y)
        for (int x = 0; x < o.width; ++x) {
            const size_t at =
                (size_t(o.height - 1 - y) * size_t(o.width) + size_t(x)) * 4; // OpenGL's rows: bottom first
            const bool drawn = depths[at + 3] != 0;
            const double d = (depths[at] * 65536.0 + depths[at + 1] * 256.0 + depths[at + 2]) / 16777215.0;
            raster.viewDepth.push_back(drawn ? float(d * view.zFar) : 0.0f);
            const glm::vec3 n(normals[at] / 127.5f - 1.0f, normals[at + 1] / 127.5f - 1.0f,
                              normals[at + 2] / 127.5f - 1.0f);
            raster.wsNormal.push_back(drawn ? glm::normalize(n) : glm::vec3(0.0f, 1.0f, 0.0f));
        }
    return samples::receiversOf(raster, view);
}

// The model's program: the mask's, or none for the engine's own picture.
void setMaskProgram(const Options& o, osg::Node* model, const osgShadow::ShadowSettings& settings) {
    if (o.picture)
        model->getOrCreateStateSet()->removeAttribute(osg::StateAttribute::PROGRAM);
    else
        model->getOrCreateStateSet()->setAttribute(
            maskProgram(int(settings.getNumShadowMapsPerLight()), settings.getBaseShadowTextureUnit()));
}

// Draws one shot of the model and writes it; the model is shared between shots.
void draw(const Options& o, const Shot& shot, osg::Node* model, Viewer& v) {
    const samples::CameraAndSun& view = shot.view;
    const auto vec = [](const samples::Vec3& xyz) { return osg::Vec3d(xyz[0], xyz[1], xyz[2]); };
    osg::ref_ptr<osgShadow::ShadowedScene> shadowed = new osgShadow::ShadowedScene;
    osg::ref_ptr<osgShadow::ShadowSettings> settings = shadowed->getShadowSettings();
    settings->setLightNum(0);
    shadowed->setShadowTechnique(makeShadowMap(shot.technique, o.mapSize, *settings).get());
    osg::ref_ptr<osg::LightSource> light = new osg::LightSource;
    light->getLight()->setLightNum(0);
    if (const auto& lamp = view.lamp) { // the camera file's lamp alone: w = 1, a cutoff of half the cone or 180
        light->getLight()->setPosition(osg::Vec4(vec(lamp->position), 1.0));
        if (!lamp->point) light->getLight()->setDirection(vec(lamp->direction));
        light->getLight()->setSpotCutoff(lamp->point ? 180.0f : float(0.5 * lamp->coneDegrees));
        // OSG's lights fade rather than end: the fall-off that reaches the lamp's range, which the
        // adapter's map then spans (the truth's lamp ends there).
        shadowkit::osgadapter::setReach(*light->getLight(), lamp->range);
    } else {
        light->getLight()->setPosition(osg::Vec4(-vec(view.sunTravel), 0.0)); // w = 0: towards a directional light
    }
    light->getLight()->setAmbient({0.3f, 0.3f, 0.3f, 1.0f});
    shadowed->addChild(light);
    shadowed->addChild(model);
    setMaskProgram(o, model, *settings);

    osg::Camera* camera = v.viewer.getCamera();
    camera->setProjectionMatrixAsPerspective(view.fovY, double(o.width) / o.height, view.zNear, view.zFar);
    camera->setViewMatrixAsLookAt(vec(view.eye), vec(view.eye) + vec(view.direction), vec(view.up));
    if (!v.viewer.isRealized()) v.viewer.realize();
    if (auto* ours = dynamic_cast<shadowkit::osgadapter::ShadowMap*>(shadowed->getShadowTechnique());
        ours && shot.technique == "auto") {
        shadowed->removeChild(model);
        ours->setReceivers(receiversSeen(o, view, model, v), o.width, o.height);
        shadowed->addChild(model);
        setMaskProgram(o, model, *settings);
    }
    v.viewer.setSceneData(shadowed);
    const osg::Timer_t drawStart = osg::Timer::instance()->tick();
    v.viewer.frame();
    const double drawSeconds = osg::Timer::instance()->delta_s(drawStart, osg::Timer::instance()->tick());
    shadowed->removeChild(model);

    // Read back what was written: a full disk or a missing folder must not pass as "wrote".
    osg::ref_ptr<osg::Image> written =
        osgDB::writeImageFile(*v.frame, shot.out) ? osgDB::readImageFile(shot.out) : nullptr;
    if (!written || written->s() != o.width || written->t() != o.height) fail(shot.out + ": could not be written");
    std::string technique = shot.technique;
    if (const auto* ours = dynamic_cast<const shadowkit::osgadapter::ShadowMap*>(shadowed->getShadowTechnique())) {
        if (ours->lastChoice()) technique += " chose " + core::describe(*ours->lastChoice());
        // A point light among what the camera sees gets a map over part of it: the shot says so.
        if (const auto& point = ours->lastPointSetup(); point && !point->views.empty())
            for (const std::string& note : point->fallbacks) technique += "; " + note;
    }
    std::printf("wrote %s (%dx%d, %s, %d² map, drawn in %.1f s)\n", shot.out.c_str(), o.width, o.height,
                technique.c_str(), o.mapSize, drawSeconds);
}

} // namespace

int main(int argc, char** argv) {
    samples::programName() = "shadowkit-osg-sample";
    const Options o = samples::parse(argc, argv, checkTechnique, /*offersPicture=*/true);
    // shadowkit's scenes are y-up, as OBJ is: OSG's OBJ reader would turn them z-up.
    const osg::Timer_t loadStart = osg::Timer::instance()->tick();
    osg::ref_ptr<osg::Node> model = osgDB::readNodeFile(o.scene, new osgDB::Options("noRotation"));
    if (!model) fail(o.scene + ": OpenSceneGraph could not read it (an .obj, or a format it has a plugin for)");
    std::printf("loaded %s in %.1f s\n", o.scene.c_str(),
                osg::Timer::instance()->delta_s(loadStart, osg::Timer::instance()->tick()));
    Viewer viewer;
    realize(o, viewer);
    for (const Shot& shot : o.shots) draw(o, shot, model.get(), viewer);
    return 0;
}
