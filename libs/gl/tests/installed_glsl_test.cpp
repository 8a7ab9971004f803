// The installed GLSL (glsl/, share/shadowkit/glsl) as an engine appends it to a fragment shader of
// its own: shadowkit_shadows.glsl, and with opacity layers shadowkit_foliage_opacity.glsl after it,
// whose lookup the first file's skShadowMap and skVirtualShadow call through declarations. The
// renderer compiles the same two files inside its own programs; these compile them bare, with
// only the declarations docs/engine-integration.md tells an engine to write, so a dependency the
// pair gains on the renderer's own shader code, or an order that stops working, fails here.
#include "engine_declarations.h"
#include "headless_gl_test.h"

#include "gl_shaders.h"
#include "program.h"

#include <gtest/gtest.h>

#include <string>

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
