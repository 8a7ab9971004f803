// shadowkit-ogre-sample: a scene drawn by OGRE 1.12 from a camera file, with OGRE's own
// shadow camera set-ups or shadowkit's, and the shadow term written as a mask for
// `shadowkit score` (docs/engine-integration.md, "OGRE"): the sun's, or where the camera file
// has a spot or point light (`shadowkit setup --sun off --light spot:...`), that lamp's.
//
//   shadowkit export --out forest.obj && shadowkit setup --view aerial > aerial.json
//   xvfb-run -a shadowkit-ogre-sample forest.obj aerial.json mask.png --technique tsm
//   shadowkit score mask.png --view aerial --size 640x360
//
// The switch an OGRE user makes is one line (below, `makeCameraSetup`):
//   sceneManager->setShadowCameraSetup(std::make_shared<shadowkit::ogreadapter::ShadowCameraSetup>());
// The rest is a plain depth shadow map, the same for every set-up: the casters write their
// clip depth into a float texture, the receivers compare against it. One map per light, or four
// split along the view for OGRE's PSSM and shadowkit's cascades (`ogre-pssm`, `csm`), each of
// half the side: the same texel memory as one map of --map-size; or for a point light, `cube`:
// the adapter's cube faces, six textures of --map-size (setPointLightCubeFaces).
#include "shadowkit/ogre/shadow_camera_setup.h"

#include "common/sample_options.h"
#include "shadowkit/core/error_driven.h"
#include "shadowkit/scene/image.h"

#include <Ogre.h>
#include <OgreShadowCameraSetupFocused.h>
#include <OgreShadowCameraSetupLiSPSM.h>
#include <OgreShadowCameraSetupPSSM.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

namespace {

namespace core = shadowkit::core;
namespace samples = shadowkit::samples;

using samples::fail;
using samples::Options;
using samples::Shot;

// Split set-ups draw four maps of half the side, one per split of the view; `cube` a point
// light's six faces, each of the full side.
constexpr int kSplitMaps = 4, kCubeMaps = 6;
bool isSplit(const std::string& name) { return name == "ogre-pssm" || name == "csm"; }
int mapsOf(const std::string& name) { return isSplit(name) ? kSplitMaps : name == "cube" ? kCubeMaps : 1; }
int mapSideOf(const std::string& name, int mapSize) { return isSplit(name) ? mapSize / 2 : mapSize; }

// A technique a shot may name: OGRE's own set-ups, or the adapter's.
void checkTechnique(const std::string& name) {
    if (name == "ogre" || name == "ogre-focused" || name == "ogre-lispsm" || name == "ogre-pssm" || name == "auto" ||
        name == "cube")
        return;
    const auto technique = core::parseTechnique(name);
    if (!technique)
        fail("technique " + name +
             ": not ogre, ogre-focused, ogre-lispsm or ogre-pssm (OGRE's own) nor one of tsm, lispsm, psm, "
             "focused, standard, csm, auto, cube (shadowkit's; cube: a point light's cube faces)");
    if (auto usable = shadowkit::ogreadapter::checkTechnique(*technique); !usable) fail(usable.error());
}

Ogre::ShadowCameraSetupPtr makeCameraSetup(const std::string& name, int mapSize) {
    if (name == "ogre") return std::make_shared<Ogre::DefaultShadowCameraSetup>();
    if (name == "ogre-focused") return std::make_shared<Ogre::FocusedShadowCameraSetup>();
    if (name == "ogre-lispsm") return std::make_shared<Ogre::LiSPSMShadowCameraSetup>();
    if (name == "ogre-pssm") return std::make_shared<Ogre::PSSMShadowCameraSetup>(); // split per shot (draw)
    // The one line an OGRE user changes: shadowkit's set-up for OGRE's.
    auto setup = std::make_shared<shadowkit::ogreadapter::ShadowCameraSetup>();
    setup->setPointLightCubeFaces(name == "cube");
    if (name == "auto") {
        // Over single maps of this texel budget: the sample gives each shot's light its
        // textures before the frame (draw() hands the receivers).
        core::AutoOptions options;
        options.cascades = 1;
        options.texelBudget = int64_t(mapSize) * mapSize;
        if (auto valid = setup->setAuto(options); !valid) fail(valid.error());
        return setup;
    }
    core::ShadowSetupInputs inputs;
    // Checked by checkTechnique; `cube` draws a point light's faces and nothing else.
    inputs.technique = name == "cube" ? core::Technique::Tsm : *core::parseTechnique(name);
    inputs.mapSize = mapSideOf(name, mapSize);
    inputs.cascades.count = kSplitMaps;
    (void)setup->setInputs(inputs);
    return setup;
}

// The depth map and its lookup, as plain GLSL 1.20 for OGRE's GL render system: casters
// write their window depth, after the rasteriser's slope-scaled offset, into a float texture;
// receivers project themselves with the shadow texture's matrix, compare, and write the sun's
// visibility (alpha 1: drawn). The offset is OSG's default (1.1 × slope + 4 units), the same
// for every set-up: a constant bias in depth units would swallow the shadows of a warped map,
// whose depth range is spent unevenly.
// The set-ups fit the map's near plane to what the camera needs and ask that casters nearer
// the sun be clamped to it (ShadowSetup::depthClamp); OGRE 1.12 has no depth clamp, so the
// caster shader flattens them onto the near plane itself ("pancaking").
const char* kCasterVertex = R"(#version 120
uniform mat4 worldViewProj;
void main() {
    gl_Position = worldViewProj * gl_Vertex;
    gl_Position.z = max(gl_Position.z, -gl_Position.w);
})";
const char* kCasterFragment = R"(#version 120
void main() { gl_FragColor = vec4(gl_FragCoord.z); })";
const char* kReceiverVertex = R"(#version 120
uniform mat4 worldViewProj;
uniform mat4 textureWorldViewProj;
varying vec4 shadowCoord;
void main() { gl_Position = worldViewProj * gl_Vertex; shadowCoord = textureWorldViewProj * gl_Vertex; })";
const char* kReceiverFragment = R"(#version 120
uniform sampler2D shadowMap;
varying vec4 shadowCoord;
void main() {
    vec3 p = shadowCoord.xyz / shadowCoord.w;
    float lit = 1.0;
    if (all(greaterThanEqual(p.xy, vec2(0.0))) && all(lessThanEqual(p.xy, vec2(1.0))))
        lit = 0.5 * p.z + 0.5 <= texture2D(shadowMap, p.xy).r ? 1.0 : 0.0;
    gl_FragColor = vec4(lit, lit, lit, 1.0);
})";

// The same lookup in four maps split along the view: each map serves the view depths up to its
// entry of splitFar (set every frame from the set-up: SplitDepths below).
const char* kSplitReceiverVertex = R"(#version 120
uniform mat4 worldViewProj;
uniform mat4 worldView;
uniform mat4 textureWorldViewProj0, textureWorldViewProj1, textureWorldViewProj2, textureWorldViewProj3;
varying vec4 shadowCoord0, shadowCoord1, shadowCoord2, shadowCoord3;
varying float viewDepth;
void main() {
    gl_Position = worldViewProj * gl_Vertex;
    viewDepth = -(worldView * gl_Vertex).z;
    shadowCoord0 = textureWorldViewProj0 * gl_Vertex;
    shadowCoord1 = textureWorldViewProj1 * gl_Vertex;
    shadowCoord2 = textureWorldViewProj2 * gl_Vertex;
    shadowCoord3 = textureWorldViewProj3 * gl_Vertex;
})";
const char* kSplitReceiverFragment = R"(#version 120
uniform sampler2D shadowMap0, shadowMap1, shadowMap2, shadowMap3;
uniform vec4 splitFar;
varying vec4 shadowCoord0, shadowCoord1, shadowCoord2, shadowCoord3;
varying float viewDepth;
float litIn(sampler2D map, vec4 coord) {
    vec3 p = coord.xyz / coord.w;
    if (any(lessThan(p.xy, vec2(0.0))) || any(greaterThan(p.xy, vec2(1.0)))) return 1.0;
    return 0.5 * p.z + 0.5 <= texture2D(map, p.xy).r ? 1.0 : 0.0;
}
void main() {
    float lit = 1.0;
    if (viewDepth <= splitFar.x) lit = litIn(shadowMap0, shadowCoord0);
    else if (viewDepth <= splitFar.y) lit = litIn(shadowMap1, shadowCoord1);
    else if (viewDepth <= splitFar.z) lit = litIn(shadowMap2, shadowCoord2);
    else if (viewDepth <= splitFar.w) lit = litIn(shadowMap3, shadowCoord3);
    gl_FragColor = vec4(lit, lit, lit, 1.0);
})";

// A point light's cube faces (`cube`), one texture each: a receiver lies in one face's frustum
// and outside the others' (behind their camera, beyond their sides or their far plane), which
// read lit, as the textures the adapter points at nothing do; so the faces' terms multiply.
const char* kFacesReceiverVertex = R"(#version 120
uniform mat4 worldViewProj;
uniform mat4 textureWorldViewProj0, textureWorldViewProj1, textureWorldViewProj2;
uniform mat4 textureWorldViewProj3, textureWorldViewProj4, textureWorldViewProj5;
varying vec4 shadowCoord0, shadowCoord1, shadowCoord2, shadowCoord3, shadowCoord4, shadowCoord5;
void main() {
    gl_Position = worldViewProj * gl_Vertex;
    shadowCoord0 = textureWorldViewProj0 * gl_Vertex;
    shadowCoord1 = textureWorldViewProj1 * gl_Vertex;
    shadowCoord2 = textureWorldViewProj2 * gl_Vertex;
    shadowCoord3 = textureWorldViewProj3 * gl_Vertex;
    shadowCoord4 = textureWorldViewProj4 * gl_Vertex;
    shadowCoord5 = textureWorldViewProj5 * gl_Vertex;
})";
const char* kFacesReceiverFragment = R"(#version 120
uniform sampler2D shadowMap0, shadowMap1, shadowMap2, shadowMap3, shadowMap4, shadowMap5;
varying vec4 shadowCoord0, shadowCoord1, shadowCoord2, shadowCoord3, shadowCoord4, shadowCoord5;
float litIn(sampler2D map, vec4 coord) {
    if (coord.w <= 0.0) return 1.0;
    vec3 p = coord.xyz / coord.w;
    if (any(lessThan(p.xy, vec2(0.0))) || any(greaterThan(p.xy, vec2(1.0))) || p.z > 1.0) return 1.0;
    return 0.5 * p.z + 0.5 <= texture2D(map, p.xy).r ? 1.0 : 0.0;
}
void main() {
    float lit = litIn(shadowMap0, shadowCoord0) * litIn(shadowMap1, shadowCoord1) * litIn(shadowMap2, shadowCoord2) *
                litIn(shadowMap3, shadowCoord3) * litIn(shadowMap4, shadowCoord4) * litIn(shadowMap5, shadowCoord5);
    gl_FragColor = vec4(lit, lit, lit, 1.0);
})";

// What the camera sees, for `auto`: each pixel's view depth and its triangle's normal (turned
// towards the eye) into a float target, the read-back an application hands the adapter from its
// own depth and normal buffers (core::receiverSamples).
const char* kSurfaceVertex = R"(#version 120
uniform mat4 worldViewProj;
uniform mat4 worldView;
uniform mat4 world;
varying vec3 wsPosition;
varying float viewDepth;
void main() {
    gl_Position = worldViewProj * gl_Vertex;
    wsPosition = (world * gl_Vertex).xyz;
    viewDepth = -(worldView * gl_Vertex).z;
})";
const char* kSurfaceFragment = R"(#version 120
uniform vec3 wsEye;
varying vec3 wsPosition;
varying float viewDepth;
void main() {
    vec3 n = normalize(cross(dFdx(wsPosition), dFdy(wsPosition)));
    if (dot(n, wsEye - wsPosition) < 0.0) n = -n;
    gl_FragColor = vec4(viewDepth, n);
})";

Ogre::GpuProgramPtr program(const std::string& name, Ogre::GpuProgramType type, const char* source) {
    Ogre::HighLevelGpuProgramPtr p = Ogre::HighLevelGpuProgramManager::getSingleton().createProgram(
        name, Ogre::ResourceGroupManager::DEFAULT_RESOURCE_GROUP_NAME, "glsl", type);
    p->setSource(source);
    p->load();
    if (p->hasCompileError()) fail("OGRE could not compile " + name);
    return p;
}

// A material NAME of one pass drawing NAME.vert and NAME.frag (made by program()), the vertex
// program given the world-view-projection matrix.
Ogre::MaterialPtr programmedMaterial(const std::string& name) {
    Ogre::MaterialPtr material =
        Ogre::MaterialManager::getSingleton().create(name, Ogre::ResourceGroupManager::DEFAULT_RESOURCE_GROUP_NAME);
    Ogre::Pass* pass = material->getTechnique(0)->getPass(0);
    pass->setVertexProgram(name + ".vert");
    pass->setFragmentProgram(name + ".frag");
    pass->getVertexProgramParameters()->setNamedAutoConstant("worldViewProj",
                                                             Ogre::GpuProgramParameters::ACT_WORLDVIEWPROJ_MATRIX);
    return material;
}

// A shadow texture unit: the next of the light's shadow textures, white (lit) beyond its border.
void addShadowUnit(Ogre::Pass* pass) {
    Ogre::TextureUnitState* shadow = pass->createTextureUnitState();
    shadow->setContentType(Ogre::TextureUnitState::CONTENT_SHADOW);
    shadow->setTextureAddressingMode(Ogre::TextureUnitState::TAM_BORDER);
    shadow->setTextureBorderColour(Ogre::ColourValue::White);
    shadow->setTextureFiltering(Ogre::TFO_NONE);
}

// The receivers' pass of a point light's cube faces.
void makeFacesReceiver() {
    program("sk/receiver-faces.vert", Ogre::GPT_VERTEX_PROGRAM, kFacesReceiverVertex);
    program("sk/receiver-faces.frag", Ogre::GPT_FRAGMENT_PROGRAM, kFacesReceiverFragment);
    Ogre::Pass* pass = programmedMaterial("sk/receiver-faces")->getTechnique(0)->getPass(0);
    for (int i = 0; i < kCubeMaps; ++i) {
        const std::string n = std::to_string(i);
        pass->getVertexProgramParameters()->setNamedAutoConstant(
            "textureWorldViewProj" + n, Ogre::GpuProgramParameters::ACT_TEXTURE_WORLDVIEWPROJ_MATRIX, size_t(i));
        pass->getFragmentProgramParameters()->setNamedConstant("shadowMap" + n, i);
        addShadowUnit(pass);
    }
}

// The receivers' pass of the split set-ups.
Ogre::Pass* makeSplitReceiver() {
    program("sk/receiver-split.vert", Ogre::GPT_VERTEX_PROGRAM, kSplitReceiverVertex);
    program("sk/receiver-split.frag", Ogre::GPT_FRAGMENT_PROGRAM, kSplitReceiverFragment);
    Ogre::Pass* pass = programmedMaterial("sk/receiver-split")->getTechnique(0)->getPass(0);
    const auto vertex = pass->getVertexProgramParameters(), fragment = pass->getFragmentProgramParameters();
    vertex->setNamedAutoConstant("worldView", Ogre::GpuProgramParameters::ACT_WORLDVIEW_MATRIX);
    for (int i = 0; i < kSplitMaps; ++i) {
        const std::string n = std::to_string(i);
        vertex->setNamedAutoConstant("textureWorldViewProj" + n,
                                     Ogre::GpuProgramParameters::ACT_TEXTURE_WORLDVIEWPROJ_MATRIX, size_t(i));
        fragment->setNamedConstant("shadowMap" + n, i);
        addShadowUnit(pass);
    }
    return pass;
}

// The float target `auto`'s receivers are drawn into, a quarter of the frame a side.
struct ReceiverTarget {
    Ogre::RenderTexture* target = nullptr;
    int width = 0, height = 0;
};

ReceiverTarget makeReceiverTarget(Ogre::Camera* camera, int width, int height) {
    program("sk/surface.vert", Ogre::GPT_VERTEX_PROGRAM, kSurfaceVertex);
    program("sk/surface.frag", Ogre::GPT_FRAGMENT_PROGRAM, kSurfaceFragment);
    const Ogre::MaterialPtr material = programmedMaterial("sk/surface");
    material->setReceiveShadows(false);
    Ogre::Pass* pass = material->getTechnique(0)->getPass(0);
    pass->setCullingMode(Ogre::CULL_NONE);
    pass->getVertexProgramParameters()->setNamedAutoConstant("worldView",
                                                             Ogre::GpuProgramParameters::ACT_WORLDVIEW_MATRIX);
    pass->getVertexProgramParameters()->setNamedAutoConstant("world", Ogre::GpuProgramParameters::ACT_WORLD_MATRIX);
    pass->getFragmentProgramParameters()->setNamedAutoConstant("wsEye",
                                                               Ogre::GpuProgramParameters::ACT_CAMERA_POSITION);
    ReceiverTarget out{nullptr, std::max(width / 4, 16), std::max(height / 4, 9)};
    Ogre::TexturePtr texture = Ogre::TextureManager::getSingleton().createManual(
        "sk/receivers", Ogre::ResourceGroupManager::DEFAULT_RESOURCE_GROUP_NAME, Ogre::TEX_TYPE_2D,
        Ogre::uint(out.width), Ogre::uint(out.height), 0, Ogre::PF_FLOAT32_RGBA, Ogre::TU_RENDERTARGET);
    out.target = texture->getBuffer()->getRenderTarget();
    out.target->setAutoUpdated(false);
    Ogre::Viewport* viewport = out.target->addViewport(camera);
    viewport->setShadowsEnabled(false);
    viewport->setOverlaysEnabled(false);
    viewport->setBackgroundColour(Ogre::ColourValue(0, 0, 0, 0)); // view depth 0: nothing drawn
    return out;
}

// The receivers the shot's camera sees: the scene drawn with sk/surface, read back top row first,
// thinned to at most 4,096 facing the sun (core::receiverSamples).
std::vector<core::ReceiverSample> receiversSeen(const ReceiverTarget& t, Ogre::ManualObject* scene,
                                                const samples::CameraAndSun& view) {
    const std::string material = scene->getSections().front()->getMaterialName();
    scene->setMaterialName(0, "sk/surface");
    t.target->update();
    scene->setMaterialName(0, material);
    std::vector<float> texels(size_t(t.width) * size_t(t.height) * 4);
    const Ogre::PixelBox pixels(Ogre::uint32(t.width), Ogre::uint32(t.height), 1, Ogre::PF_FLOAT32_RGBA, texels.data());
    t.target->copyContentsToMemory(pixels, pixels);
    core::RasterBuffers raster;
    raster.width = t.width, raster.height = t.height;
    for (size_t i = 0; i < texels.size(); i += 4) {
        raster.viewDepth.push_back(texels[i]);
        raster.wsNormal.emplace_back(texels[i + 1], texels[i + 2], texels[i + 3]);
    }
    return samples::receiversOf(raster, view);
}

// Sets the split receivers' splitFar once the frame's shadow textures are drawn, when the
// adapter's set-up for this frame is known: OGRE's PSSM splits are fixed before the frame.
class SplitDepths : public Ogre::SceneManager::Listener {
public:
    explicit SplitDepths(Ogre::Pass* receiver) : m_receiver(receiver) {}
    void use(Ogre::ShadowCameraSetupPtr setup) { m_setup = std::move(setup); }
    void shadowTexturesUpdated(size_t) override {
        Ogre::Vector4 far(0, 0, 0, 0);
        if (auto* pssm = dynamic_cast<Ogre::PSSMShadowCameraSetup*>(m_setup.get())) {
            const auto& points = pssm->getSplitPoints(); // near, then each split's far
            for (size_t i = 0; i < kSplitMaps && i + 1 < points.size(); ++i) far[i] = points[i + 1];
        } else if (auto* ours = dynamic_cast<shadowkit::ogreadapter::ShadowCameraSetup*>(m_setup.get())) {
            if (!ours->lastSetup() && ours->lastError().empty()) return; // a lamp, not the sun: one map, no splits
            if (!ours->lastSetup()) fail("the adapter's cascades failed: " + ours->lastError());
            const auto& views = ours->lastSetup()->views;
            for (size_t i = 0; i < kSplitMaps && i < views.size(); ++i)
                far[i] = views[i].split ? Ogre::Real(views[i].split->y) : Ogre::Real(0);
        }
        m_receiver->getFragmentProgramParameters()->setNamedConstant("splitFar", far);
    }

private:
    Ogre::Pass* m_receiver;
    Ogre::ShadowCameraSetupPtr m_setup;
};

void makeMaterials(Ogre::SceneManager* sm) {
    program("sk/caster.vert", Ogre::GPT_VERTEX_PROGRAM, kCasterVertex);
    program("sk/caster.frag", Ogre::GPT_FRAGMENT_PROGRAM, kCasterFragment);
    program("sk/receiver.vert", Ogre::GPT_VERTEX_PROGRAM, kReceiverVertex);
    program("sk/receiver.frag", Ogre::GPT_FRAGMENT_PROGRAM, kReceiverFragment);

    const Ogre::MaterialPtr caster = programmedMaterial("sk/caster");
    Ogre::Pass* cp = caster->getTechnique(0)->getPass(0);
    cp->setCullingMode(Ogre::CULL_NONE);
    cp->setDepthBias(-4.0f, -1.1f); // OGRE: positive brings a surface nearer; away from the sun
    sm->setShadowTextureCasterMaterial(caster);

    Ogre::Pass* rp = programmedMaterial("sk/receiver")->getTechnique(0)->getPass(0);
    rp->getVertexProgramParameters()->setNamedAutoConstant(
        "textureWorldViewProj", Ogre::GpuProgramParameters::ACT_TEXTURE_WORLDVIEWPROJ_MATRIX, 0);
    rp->getFragmentProgramParameters()->setNamedConstant("shadowMap", 0);
    addShadowUnit(rp);
}

// The OBJ as one ManualObject: positions only (the mask needs no shading), 32-bit indices.
Ogre::ManualObject* loadObj(Ogre::SceneManager* sm, const std::string& file) {
    tinyobj::ObjReader reader;
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    if (!reader.ParseFromFile(file, config)) fail(file + ": " + reader.Error());
    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    Ogre::ManualObject* mesh = sm->createManualObject("scene");
    mesh->setCastShadows(true);
    mesh->estimateVertexCount(attrib.vertices.size() / 3);
    mesh->begin("sk/receiver", Ogre::RenderOperation::OT_TRIANGLE_LIST);
    for (size_t i = 0; i + 2 < attrib.vertices.size(); i += 3)
        mesh->position(attrib.vertices[i], attrib.vertices[i + 1], attrib.vertices[i + 2]);
    for (const tinyobj::shape_t& shape : reader.GetShapes())
        for (const tinyobj::index_t& index : shape.mesh.indices) mesh->index(Ogre::uint32(index.vertex_index));
    mesh->end();
    return mesh;
}

void draw(const Options& o, const Shot& shot, Ogre::Root& root, Ogre::SceneManager* sm, Ogre::RenderWindow* window,
          Ogre::ManualObject* scene, SplitDepths& splits, const ReceiverTarget& receivers) {
    const Ogre::ShadowCameraSetupPtr setup = makeCameraSetup(shot.technique, o.mapSize);
    sm->setShadowCameraSetup(setup);
    const int maps = mapsOf(shot.technique);
    sm->setShadowTextureCountPerLightType(Ogre::Light::LT_DIRECTIONAL, size_t(maps));
    sm->setShadowTextureSettings(Ogre::uint16(mapSideOf(shot.technique, o.mapSize)), Ogre::uint16(maps),
                                 Ogre::PF_FLOAT32_R);
    if (shot.technique == "cube" && !(shot.view.lamp && shot.view.lamp->point))
        fail(shot.out + ": technique cube draws a camera file's point light, and this one has none");
    scene->setMaterialName(0, shot.technique == "cube" ? "sk/receiver-faces"
                              : maps > 1               ? "sk/receiver-split"
                                                       : "sk/receiver");
    splits.use(setup);
    Ogre::Light* sun = sm->getLight("sun");
    const auto vec = [](const samples::Vec3& v) {
        return Ogre::Vector3(Ogre::Real(v[0]), Ogre::Real(v[1]), Ogre::Real(v[2]));
    };
    if (const auto& lamp = shot.view.lamp) { // the camera file's lamp alone, one shadow texture
        sun->setType(lamp->point ? Ogre::Light::LT_POINT : Ogre::Light::LT_SPOTLIGHT);
        if (!lamp->point) {
            sun->setSpotlightRange(Ogre::Degree(Ogre::Real(0.8 * lamp->coneDegrees)),
                                   Ogre::Degree(Ogre::Real(lamp->coneDegrees)));
            sun->getParentSceneNode()->setDirection(vec(lamp->direction), Ogre::Node::TS_WORLD);
        }
        sun->setAttenuation(Ogre::Real(lamp->range), 1.0f, 0.0f, 0.0f);
        sun->getParentSceneNode()->setPosition(vec(lamp->position));
        sm->setShadowTextureCountPerLightType(sun->getType(), size_t(shot.technique == "cube" ? kCubeMaps : 1));
    } else {
        sun->setType(Ogre::Light::LT_DIRECTIONAL);
        sun->getParentSceneNode()->setDirection(vec(shot.view.sunTravel), Ogre::Node::TS_WORLD);
    }
    Ogre::Camera* camera = sm->getCamera("camera");
    Ogre::SceneNode* eye = camera->getParentSceneNode();
    eye->setPosition(vec(shot.view.eye));
    eye->setDirection(vec(shot.view.direction), Ogre::Node::TS_WORLD);
    camera->setFOVy(Ogre::Degree(Ogre::Real(shot.view.fovY)));
    camera->setNearClipDistance(Ogre::Real(shot.view.zNear));
    camera->setFarClipDistance(Ogre::Real(shot.view.zFar));
    camera->setAspectRatio(Ogre::Real(o.width) / Ogre::Real(o.height));
    if (auto* pssm = dynamic_cast<Ogre::PSSMShadowCameraSetup*>(setup.get()))
        pssm->calculateSplitPoints(kSplitMaps, Ogre::Real(shot.view.zNear), Ogre::Real(shot.view.zFar));
    if (shot.technique == "auto") {
        auto* ours = static_cast<shadowkit::ogreadapter::ShadowCameraSetup*>(setup.get());
        sm->getRootSceneNode()->_update(true, false);
        ours->setReceivers(receiversSeen(receivers, scene, shot.view), receivers.width, receivers.height);
    }

    const auto start = std::chrono::steady_clock::now();
    root.renderOneFrame();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // Copied out top row first, RGBA bytes, and written by shadowkit's own PNG writer, which
    // checks every write (OGRE 1.12's STBI codec frees with delete[] what it took with malloc).
    shadowkit::scene::Image frame(o.width, o.height);
    const Ogre::PixelBox pixels(Ogre::uint32(o.width), Ogre::uint32(o.height), 1, Ogre::PF_BYTE_RGBA,
                                frame.rgba.data());
    window->copyContentsToMemory(pixels, pixels);
    if (auto written = shadowkit::scene::writePng(frame, shot.out); !written) fail(written.error());
    std::string technique = shot.technique;
    if (const auto* ours = dynamic_cast<const shadowkit::ogreadapter::ShadowCameraSetup*>(setup.get())) {
        if (ours->lastChoice()) technique += " chose " + core::describe(*ours->lastChoice());
        // A point light among what the camera sees gets a map over part of it: the shot says so.
        if (const auto& point = ours->lastPointSetup(); point && !point->views.empty())
            for (const std::string& note : point->fallbacks) technique += "; " + note;
    }
    std::printf("wrote %s (%dx%d, %s, %d × %d² maps, drawn in %.1f s)\n", shot.out.c_str(), o.width, o.height,
                technique.c_str(), maps, mapSideOf(shot.technique, o.mapSize), seconds);
}

} // namespace

int main(int argc, char** argv) {
    samples::programName() = "shadowkit-ogre-sample";
    const Options o = samples::parse(argc, argv, checkTechnique, /*offersPicture=*/false);
    auto log = std::make_unique<Ogre::LogManager>();
    log->createLog("shadowkit-ogre-sample.log", true, false, true); // quiet: no console, no file
    Ogre::Root root("", "", "");
    const std::string plugins = OGRE_PLUGIN_DIR;
    try {
        root.loadPlugin(plugins + "/RenderSystem_GL");
    } catch (const Ogre::Exception& e) {
        fail("OGRE's plugins in " + plugins + ": " + e.getDescription());
    }
    root.setRenderSystem(root.getRenderSystemByName("OpenGL Rendering Subsystem"));
    root.initialise(false);
    Ogre::RenderWindow* window = nullptr;
    try {
        window = root.createRenderWindow("shadowkit", unsigned(o.width), unsigned(o.height), false);
    } catch (const Ogre::Exception& e) {
        fail("no OpenGL window: run under xvfb-run (OGRE's Debian build has GLX, not EGL): " + e.getDescription());
    }
    // OGRE's scene manager sets up its shadow programs from the ShadowVolume media even for
    // texture shadows.
    Ogre::ResourceGroupManager::getSingleton().addResourceLocation(OGRE_MEDIA_DIR "/ShadowVolume", "FileSystem");
    Ogre::ResourceGroupManager::getSingleton().initialiseAllResourceGroups();
    Ogre::SceneManager* sm = root.createSceneManager();
    makeMaterials(sm);
    makeFacesReceiver();
    SplitDepths splits(makeSplitReceiver());
    sm->addListener(&splits);
    sm->setShadowTechnique(Ogre::SHADOWTYPE_TEXTURE_ADDITIVE_INTEGRATED);
    sm->setShadowTextureSelfShadow(true);
    sm->setShadowDirLightTextureOffset(0.0f);

    const auto loadStart = std::chrono::steady_clock::now();
    Ogre::ManualObject* scene = loadObj(sm, o.scene);
    sm->getRootSceneNode()->createChildSceneNode()->attachObject(scene);
    std::printf("loaded %s in %.1f s\n", o.scene.c_str(),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - loadStart).count());

    Ogre::Light* sun = sm->createLight("sun");
    sun->setType(Ogre::Light::LT_DIRECTIONAL);
    sm->getRootSceneNode()->createChildSceneNode()->attachObject(sun);
    Ogre::Camera* camera = sm->createCamera("camera");
    Ogre::SceneNode* eye = sm->getRootSceneNode()->createChildSceneNode();
    eye->attachObject(camera);
    const samples::Vec3& up = o.shots.front().view.up;
    eye->setFixedYawAxis(true, Ogre::Vector3(Ogre::Real(up[0]), Ogre::Real(up[1]), Ogre::Real(up[2])));
    Ogre::Viewport* viewport = window->addViewport(camera);
    viewport->setBackgroundColour(Ogre::ColourValue(0, 0, 0, 0)); // alpha 0: no surface
    viewport->setShadowsEnabled(true);
    const ReceiverTarget receivers = makeReceiverTarget(camera, o.width, o.height);
    for (const Shot& shot : o.shots) draw(o, shot, root, sm, window, scene, splits, receivers);
    sm->removeListener(&splits);
    return 0;
}
