#version 450 core
// Declarations shared by the camera passes (main and eval). Prepended to their sources.
// The C++ side of Frame is FrameUniforms in uniforms.h (size checked at link time).
layout(std430, binding = 0) readonly buffer Instances { mat4 worldFromObject[]; };

#define SK_MAX_CASCADES 8

layout(std140, binding = 0) uniform Frame {
    mat4 clipFromWorld;       // camera
    vec4 wsEye;               // xyz
    vec4 wsViewForward;       // xyz, unit: view depth = dot(ws - eye, forward)
    vec4 wsTowardsLight;      // xyz, unit
    vec4 sunRadiance;         // rgb
    vec4 ambientRadiance;     // rgb
    vec4 fogColorDensity;     // rgb, a: density in 1/m
    vec4 shadowParams;        // x: texels per side, y: maps, z: 1 linear depth layout, w: 1 colour splits
    vec4 filterParams;        // x: 0 hard, 1 hardware 2x2 PCF, 2 N x N PCF, 3 Poisson; y: N; z: Poisson radius (texels); w: 1 receiver-plane bias
    vec4 biasParams;          // x: normal offset (texels' world size), y: 1 read the blurred mask instead
    mat4 shadowClipFromWorld[SK_MAX_CASCADES];        // light clip space of each map
    vec4 shadowLinearDepthFromWorld[SK_MAX_CASCADES]; // rows, see DepthPass
    vec4 cascadeRange[SK_MAX_CASCADES];               // x, y: view depth [start, end] each map serves
};
