// The installed GLSL (glsl/, share/shadowkit/glsl) as an engine appends it to a fragment shader of
// its own: shadowkit_shadows.glsl, and after it shadowkit_foliage_opacity.glsl with opacity layers
// (whose lookup the first file's skShadowMap and skVirtualShadow call through declarations) and
// shadowkit_local_shadows.glsl for spot and point lights. The renderer compiles the same files
// inside its own programs; these compile them bare, with only the declarations
// docs/engine-integration.md tells an engine to write, so a dependency the files gain on the
// renderer's own shader code, or an order that stops working, fails here.
#include "engine_declarations.h"
#include "headless_gl_test.h"
#include "one_pixel_target.h"

#include "gl_object.h"
#include "gl_shaders.h"
#include "program.h"

#include <epoxy/gl.h>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace shadowkit;

namespace {

class InstalledGlslTest : public gl::testing::HeadlessGlTest {};

constexpr std::string_view kVertex = "void main() { gl_Position = vec4(0.0); }\n";

// The three opacity samplers, named as the foliage file asks.
constexpr std::string_view kOpacityDeclarations = R"glsl(
layout(binding = 10) uniform sampler2DArray myOpacityLayers;
layout(binding = 11) uniform sampler2DArray myOpacityFirst;
layout(binding = 12) uniform sampler2DArray myOpacityPrefiltered;
#define SK_SHADOW_OPACITY myOpacityLayers
#define SK_SHADOW_OPACITY_FIRST myOpacityFirst
#define SK_SHADOW_OPACITY_PREFILTERED myOpacityPrefiltered
)glsl";

// The engine's shading after the files: four cascades under the real sun, PCSS.
constexpr std::string_view kEngineShading = R"glsl(
out vec4 colour;
void main() {
    const vec3 wsPosition = vec3(gl_FragCoord.xy, 0.0), wsNormal = vec3(0.0, 1.0, 0.0);
    const float viewDepth = gl_FragCoord.z;
    const vec3 dx = dFdx(wsPosition), dy = dFdy(wsPosition);
    const SkShadowOptions o = SkShadowOptions(2048.0, true, 1.0, true, SK_FILTER_PCSS, 16, 16.0, 0.004625, 0.0, false);
    colour = vec4(vec3(skCascadedShadow(myShadowMaps, 4, o, viewDepth, wsPosition, normalize(wsNormal), dx, dy)), 1.0);
}
)glsl";

// An engine's virtual clipmap (docs/engine-integration.md): the page atlas, its page table, the
// levels' matrices and their first pages' cells in the table; the shading reads skVirtualShadow,
// which multiplies by the leaves' transmittance from the opacity atlases when the samplers are named.
constexpr std::string_view kVirtualLevels = R"glsl(
layout(binding = 2) uniform sampler2DArrayShadow myPageAtlas;
layout(binding = 3) uniform usampler2D myPageTable;
uniform mat4 myLevelTextureFromWorld[8];
#define SK_VIRTUAL_LEVEL_FROM_WORLD(i) myLevelTextureFromWorld[i]
)glsl";
constexpr std::string_view kVirtualTableOrigins = R"glsl(
uniform ivec2 myLevelTableOrigin[8];
#define SK_VIRTUAL_LEVEL_TABLE_ORIGIN(i) myLevelTableOrigin[i]
)glsl";

constexpr std::string_view kVirtualShading = R"glsl(
out vec4 colour;
void main() {
    const vec3 wsPosition = vec3(gl_FragCoord.xy, 0.0), wsNormal = vec3(0.0, 1.0, 0.0);
    const vec3 dx = dFdx(wsPosition), dy = dFdy(wsPosition);
    const SkShadowOptions o = SkShadowOptions(16384.0, false, 1.0, true, SK_FILTER_PCSS, 16, 8.0, 0.004625, 0.0, false);
    const SkVirtualMaps v = SkVirtualMaps(8, -6, 0.0015, 0.0, 128, 128, 10, 27, vec2(4104.0), 16384.0, 0.2);
    colour = vec4(vec3(skVirtualShadow(myPageAtlas, myPageTable, v, o, gl_FragCoord.z, wsPosition, wsNormal, dx, dy)), 1.0);
}
)glsl";

} // namespace

TEST_F(InstalledGlslTest, TheLookupAloneCompilesWithAnEnginesOwnDeclarations) {
    using namespace gl::shaders;
    const auto program = gl::buildProgram("engine shader", {kVertex},
                                          {gl::testing::kEngineDeclarations, kShadowkitShadowsGlsl, kEngineShading});
    EXPECT_TRUE(program) << program.error();
}

TEST_F(InstalledGlslTest, WithOpacityLayersTheFoliageFileAppendedAfterTheLookupCompletesIt) {
    using namespace gl::shaders;
    const auto program = gl::buildProgram("engine shader, opacity layers", {kVertex},
                                          {gl::testing::kEngineDeclarations, kOpacityDeclarations,
                                           kShadowkitShadowsGlsl, kShadowkitFoliageOpacityGlsl, kEngineShading});
    EXPECT_TRUE(program) << program.error();
}

TEST_F(InstalledGlslTest, VirtualMapsWithOpacityLayersCompileAndWithoutTheFoliageFileAreRefused) {
    using namespace gl::shaders;
    const auto program = gl::buildProgram("engine shader, virtual maps, opacity layers", {kVertex},
                                          {kVirtualLevels, kVirtualTableOrigins, kOpacityDeclarations,
                                           kShadowkitShadowsGlsl, kShadowkitFoliageOpacityGlsl, kVirtualShading});
    EXPECT_TRUE(program) << program.error();
    const auto plain = gl::buildProgram("engine shader, virtual maps", {kVertex},
                                        {kVirtualLevels, kVirtualTableOrigins, kShadowkitShadowsGlsl, kVirtualShading});
    EXPECT_TRUE(plain) << plain.error();
    // skVirtualShadow calls the declared skFoliageTransmittanceIn: never a silently unshadowed leaf.
    const auto missing = gl::buildProgram(
        "engine shader, virtual maps, foliage file missing", {kVertex},
        {kVirtualLevels, kVirtualTableOrigins, kOpacityDeclarations, kShadowkitShadowsGlsl, kVirtualShading});
    EXPECT_FALSE(missing);
}

TEST_F(InstalledGlslTest, VirtualMapsWithoutTheTablesOriginsAreRefusedNamingTheAccessor) {
    // The page table is toroidal: a lookup without each level's first cell would read other
    // pages' entries wherever a window has moved — refused, never compiled to the wrong page.
    using namespace gl::shaders;
    const auto program = gl::buildProgram("engine shader, virtual maps, no table origins", {kVertex},
                                          {kVirtualLevels, kShadowkitShadowsGlsl, kVirtualShading});
    ASSERT_FALSE(program);
    EXPECT_NE(program.error().find("SK_VIRTUAL_LEVEL_TABLE_ORIGIN"), std::string::npos) << program.error();
}

TEST_F(InstalledGlslTest, TheFoliageFileBeforeTheLookupIsRefusedNamingTheOrder) {
    using namespace gl::shaders;
    const auto program = gl::buildProgram("engine shader, files swapped", {kVertex},
                                          {gl::testing::kEngineDeclarations, kOpacityDeclarations,
                                           kShadowkitFoliageOpacityGlsl, kShadowkitShadowsGlsl, kEngineShading});
    ASSERT_FALSE(program);
    EXPECT_NE(program.error().find("append it after shadowkit_shadows.glsl"), std::string::npos) << program.error();
}

TEST_F(InstalledGlslTest, OpacityLayersNamedWithoutTheFoliageFileAreRefused) {
    // skShadowMap calls the declared skFoliageTransmittance: with no definition the program
    // cannot be made, never a silently unshadowed leaf. (Mesa names the function in its link log;
    // the wording is the driver's, so only the refusal is asserted.)
    using namespace gl::shaders;
    const auto program = gl::buildProgram(
        "engine shader, foliage file missing", {kVertex},
        {gl::testing::kEngineDeclarations, kOpacityDeclarations, kShadowkitShadowsGlsl, kEngineShading});
    EXPECT_FALSE(program);
}

// A reversed-Z engine's maps (SK_SHADOW_REVERSED_Z): every lookup — cascades, virtual pages, opacity
// layers — compiles with the depth turned at its entries. examples/minimal_gl --reversed-z draws
// with it (tests/minimal_gl_test.cmake: the same frames as the OpenGL convention's).
TEST_F(InstalledGlslTest, WithReversedZEveryLookupCompiles) {
    using namespace gl::shaders;
    constexpr std::string_view kReversed = "#define SK_SHADOW_REVERSED_Z\n";
    const auto cascades = gl::buildProgram("engine shader, reversed-Z, opacity layers", {kVertex},
                                           {kReversed, gl::testing::kEngineDeclarations, kOpacityDeclarations,
                                            kShadowkitShadowsGlsl, kShadowkitFoliageOpacityGlsl, kEngineShading});
    EXPECT_TRUE(cascades) << cascades.error();
    const auto virtualMaps = gl::buildProgram("engine shader, reversed-Z, virtual maps, opacity layers", {kVertex},
                                              {kReversed, kVirtualLevels, kVirtualTableOrigins, kOpacityDeclarations,
                                               kShadowkitShadowsGlsl, kShadowkitFoliageOpacityGlsl, kVirtualShading});
    EXPECT_TRUE(virtualMaps) << virtualMaps.error();
}

namespace {

// An engine's spot and point lights (docs/engine-integration.md, "Spot and point lights"): its
// maps named through the local file's accessors, either kind alone or both.
constexpr std::string_view kSpotMaps = R"glsl(
layout(binding = 4) uniform sampler2DArrayShadow mySpotMaps;
layout(binding = 5) uniform sampler2DArray mySpotDepths;
#define SK_SPOT_MAPS mySpotMaps
#define SK_SPOT_DEPTHS mySpotDepths
)glsl";
constexpr std::string_view kPointMaps = R"glsl(
layout(binding = 6) uniform samplerCubeArrayShadow myPointMaps;
#define SK_POINT_MAPS myPointMaps
)glsl";

constexpr std::string_view kLocalOptions = R"glsl(
out vec4 colour;
uniform mat4 mySpotTextureFromWorld;
const SkLocalShadowOptions kOptions = SkLocalShadowOptions(1.5, 0.5, 0.005, SK_FILTER_PCSS, 16, 16.0);
SkLocalLight myLight(int layer) { return SkLocalLight(vec3(0.0, 5.0, 0.0), 0.05, vec2(1.0 / 30.0, 0.0), 0.002, layer); }
)glsl";
constexpr std::string_view kSpotShading = R"glsl(
void main() {
    colour = vec4(vec3(skSpotShadow(myLight(0), mySpotTextureFromWorld, kOptions, gl_FragCoord.xyz, vec3(0, 1, 0))), 1.0);
}
)glsl";
constexpr std::string_view kPointShading = R"glsl(
void main() { colour = vec4(vec3(skPointShadow(myLight(0), kOptions, gl_FragCoord.xyz, vec3(0, 1, 0))), 1.0); }
)glsl";
constexpr std::string_view kBothShading = R"glsl(
void main() {
    const vec3 ws = gl_FragCoord.xyz, n = vec3(0.0, 1.0, 0.0);
    colour = vec4(vec3(skSpotShadow(myLight(0), mySpotTextureFromWorld, kOptions, ws, n) *
                       skPointShadow(myLight(1), kOptions, ws, n)), 1.0);
}
)glsl";

} // namespace

// The renderer compiles the local file between its own declarations and lighting; bare, it needs
// only the sun's file before it and the maps an engine names: spot lights alone, point lights alone
// (without their depths: PCSS falls back to the hard test), or both.
TEST_F(InstalledGlslTest, TheLocalLightsLookupCompilesForSpotsAloneForPointsAloneAndForBoth) {
    using namespace gl::shaders;
    const auto spots =
        gl::buildProgram("engine shader, spot lights", {kVertex},
                         {kSpotMaps, kShadowkitShadowsGlsl, kShadowkitLocalShadowsGlsl, kLocalOptions, kSpotShading});
    EXPECT_TRUE(spots) << spots.error();
    const auto points =
        gl::buildProgram("engine shader, point lights", {kVertex},
                         {kPointMaps, kShadowkitShadowsGlsl, kShadowkitLocalShadowsGlsl, kLocalOptions, kPointShading});
    EXPECT_TRUE(points) << points.error();
    const auto both =
        gl::buildProgram("engine shader, spot and point lights, reversed-Z sun", {kVertex},
                         {"#define SK_SHADOW_REVERSED_Z\n", kSpotMaps, kPointMaps, gl::testing::kEngineDeclarations,
                          kShadowkitShadowsGlsl, kShadowkitLocalShadowsGlsl, kLocalOptions, kBothShading});
    EXPECT_TRUE(both) << both.error();
    // A kind whose maps were not named has no lookup: never a silently unshadowed light.
    const auto unnamed =
        gl::buildProgram("engine shader, point lookup without point maps", {kVertex},
                         {kSpotMaps, kShadowkitShadowsGlsl, kShadowkitLocalShadowsGlsl, kLocalOptions, kPointShading});
    EXPECT_FALSE(unnamed);
}

TEST_F(InstalledGlslTest, TheLocalLightsFileBeforeTheLookupIsRefusedNamingTheOrder) {
    using namespace gl::shaders;
    const auto program =
        gl::buildProgram("engine shader, local file first", {kVertex},
                         {kSpotMaps, kShadowkitLocalShadowsGlsl, kShadowkitShadowsGlsl, kLocalOptions, kSpotShading});
    ASSERT_FALSE(program);
    EXPECT_NE(program.error().find("shadowkit_local_shadows.glsl: append it after shadowkit_shadows.glsl"),
              std::string::npos)
        << program.error();
}

namespace {

// skSpotShadow at one world point, the hard test, a lamp of no radius at wsLamp.
constexpr std::string_view kSpotAtOnePoint = R"glsl(
uniform mat4 textureFromWorld;
uniform vec3 wsLamp, wsPoint;
uniform float texelPerMetre;
out vec4 result;
void main() {
    const SkLocalShadowOptions o = SkLocalShadowOptions(1.5, 0.5, 0.005, SK_FILTER_HARD, 0, 0.0);
    const SkLocalLight l = SkLocalLight(wsLamp, 0.0, vec2(1.0 / 30.0, 0.0), texelPerMetre, 0);
    result = vec4(skSpotShadow(l, textureFromWorld, o, wsPoint, normalize(wsLamp - wsPoint)));
}
)glsl";

} // namespace

// A point light's one map aimed at part of what the camera sees (SHADOWKIT_LIGHT_POINT_AIMED_MAP,
// docs/engine-integration.md) leaves out receivers the lamp lights, and its set-up says they get
// no shadow from it; engines look such a map up with skSpotShadow, which must answer so — lit
// beside the map's square and behind the lamp, not the clamped edge's texel or, where w < 0, a
// texel of the mirrored image. A map whose every texel holds a caster at the lamp shadows every
// receiver it holds, the edge's within a texel past it too.
TEST_F(InstalledGlslTest, ASpotMapLooksUpWhatItHoldsAndLeavesTheRestLit) {
    using namespace gl::shaders;
    auto program = gl::buildProgram("spot lookup at one point", {gl::testing::kFullScreenTriangle},
                                    {kSpotMaps, kShadowkitShadowsGlsl, kShadowkitLocalShadowsGlsl, kSpotAtOnePoint});
    ASSERT_TRUE(program) << program.error();
    constexpr int kTexels = 16;
    const gl::Texture map = gl::createMapLayers(GL_DEPTH_COMPONENT32F, kTexels, 1, GL_NEAREST);
    const std::vector<float> atTheLamp(kTexels * kTexels, 0.0f);
    glTextureSubImage3D(map.id(), 0, 0, 0, 0, kTexels, kTexels, 1, GL_DEPTH_COMPONENT, GL_FLOAT, atTheLamp.data());
    glTextureParameteri(map.id(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTextureParameteri(map.id(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    glBindTextureUnit(4, map.id());
    const gl::testing::OnePixelTarget target;

    // The lamp 5 m up looking straight down through a 90° square: the ground's (±5, 0, ±5) at the
    // map's edges, a texel 0.125 of a metre's distance across.
    const glm::vec3 wsLamp(0.0f, 5.0f, 0.0f);
    const glm::mat4 textureFromClip =
        glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
    const glm::mat4 textureFromWorld = textureFromClip * glm::perspective(glm::radians(90.0f), 1.0f, 0.1f, 30.0f) *
                                       glm::lookAt(wsLamp, glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f));
    const GLuint p = program->id();
    glProgramUniformMatrix4fv(p, glGetUniformLocation(p, "textureFromWorld"), 1, GL_FALSE, &textureFromWorld[0][0]);
    glProgramUniform3f(p, glGetUniformLocation(p, "wsLamp"), wsLamp.x, wsLamp.y, wsLamp.z);
    glProgramUniform1f(p, glGetUniformLocation(p, "texelPerMetre"), 2.0f / kTexels);
    auto shadowAt = [&](glm::vec3 wsPoint) {
        glProgramUniform3f(p, glGetUniformLocation(p, "wsPoint"), wsPoint.x, wsPoint.y, wsPoint.z);
        return target.draw(p)[0];
    };
    // Held: under the lamp, near the edge, and a fifth of a texel past it (u = 1.0125).
    for (const glm::vec3 ws :
         {glm::vec3(0, 0, 0), glm::vec3(4.5f, 0, -3), glm::vec3(-4.9f, 0, 4.9f), glm::vec3(5.125f, 0, 0)})
        EXPECT_EQ(shadowAt(ws), 0.0f) << ws.x << "," << ws.y << "," << ws.z;
    // Not held: beside the square (u = 1.3, and past a corner), level with the lamp and behind it.
    for (const glm::vec3 ws :
         {glm::vec3(8, 0, 0), glm::vec3(-7, 0, 7), glm::vec3(10, 5, 0), glm::vec3(0, 10, 0), glm::vec3(3, 8, -2)})
        EXPECT_EQ(shadowAt(ws), 1.0f) << ws.x << "," << ws.y << "," << ws.z;
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}
