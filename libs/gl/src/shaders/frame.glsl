#version 450 core
// Declarations shared by the camera passes (main and eval). Prepended to their sources.
// The C++ side of Frame is FrameUniforms in uniforms.h (size checked at link time).
layout(std430, binding = 0) readonly buffer Instances { mat4 worldFromObject[]; };

layout(std140, binding = 0) uniform Frame {
    mat4 clipFromWorld;       // camera
    mat4 shadowClipFromWorld; // light clip space of the shadow map
    vec4 wsEye;               // xyz
    vec4 wsViewForward;       // xyz, unit: view depth = dot(ws - eye, forward)
    vec4 wsTowardsLight;      // xyz, unit
    vec4 sunRadiance;         // rgb
    vec4 ambientRadiance;     // rgb
    vec4 fogColorDensity;     // rgb, a: density in 1/m
    vec4 shadowMapSize;       // x: texels per side
    vec4 shadowLinearDepthFromWorld; // row, see DepthPass
    vec4 shadowDepthLayout;   // x: 1 linear, 0 hyperbolic
};
