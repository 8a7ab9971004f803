// Uniform block layouts, declared once in C++ (std140: every member 16-byte aligned) and
// checked against the shaders when the programs are built (checkUniformBlock).
#pragma once

#include <glm/glm.hpp>

namespace shadowkit::gl {

struct DepthPassUniforms { // GLSL: DepthPass, binding 1
    glm::mat4 clipFromWorld;
    glm::vec4 linearDepthFromWorld; // row: depth = dot(row, (ws, 1))
    glm::vec4 depthLayout;          // x: 1 linear, 0 hyperbolic
    glm::vec4 bias;                 // linear layout: x slope factor, y constant in depth units
};

inline constexpr int kMaxCascades = 8; // GLSL: SK_MAX_CASCADES

struct FrameUniforms { // GLSL: Frame, binding 0
    glm::mat4 clipFromWorld;
    glm::vec4 wsEye;
    glm::vec4 wsViewForward;
    glm::vec4 wsTowardsLight;
    glm::vec4 sunRadiance;
    glm::vec4 ambientRadiance;
    glm::vec4 fogColorDensity;
    glm::vec4 shadowParams; // x texels per side, y maps, z linear layout, w colour splits
    glm::vec4 filterParams; // x kind (0 hard, 1 pcf2, 2 grid, 3 poisson), y taps, z poisson radius, w receiver plane
    glm::vec4 biasParams;   // x normal offset, y read the blurred mask
    glm::mat4 shadowClipFromWorld[kMaxCascades];
    glm::vec4 shadowLinearDepthFromWorld[kMaxCascades];
    glm::vec4 cascadeRange[kMaxCascades];
};

struct BlurUniforms { // GLSL: Blur, binding 2
    glm::vec4 params; // x radius (pixels at depth 0), y depth falloff (1/m), z relative depth threshold
};

inline constexpr unsigned kFrameBinding = 0;
inline constexpr unsigned kBlurBinding = 2;
inline constexpr unsigned kShadowMaskUnit = 1;
inline constexpr unsigned kDepthPassBinding = 1;
inline constexpr unsigned kInstancesBinding = 0; // shader storage
inline constexpr unsigned kShadowMapUnit = 0;
inline constexpr int kInstanceBaseLocation = 0; // uniform uint instanceBase (main.vert)

} // namespace shadowkit::gl
