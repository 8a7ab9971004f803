// The declarations docs/engine-integration.md tells an engine to write before appending the
// installed glsl/shadowkit_shadows.glsl: its cascades' arrays through the three accessor macros
// and PCSS's raw depths. Shared by the tests that compile the installed file bare.
#pragma once

#include <string_view>

namespace shadowkit::gl::testing {

inline constexpr std::string_view kEngineDeclarations = R"glsl(
layout(binding = 0) uniform sampler2DArrayShadow myShadowMaps;
layout(binding = 1) uniform sampler2DArray myShadowDepths;
uniform mat4 myTextureFromWorld[4];
uniform vec4 myLinearDepthFromWorld[4];
uniform vec4 mySplits[4];
#define SK_SHADOW_TEXTURE_FROM_WORLD(i) myTextureFromWorld[i]
#define SK_SHADOW_LINEAR_DEPTH_FROM_WORLD(i) myLinearDepthFromWorld[i]
#define SK_SHADOW_SPLIT(i) mySplits[i].xy
#define SK_SHADOW_DEPTHS myShadowDepths
)glsl";

} // namespace shadowkit::gl::testing
