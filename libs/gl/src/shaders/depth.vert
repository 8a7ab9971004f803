#version 450 core
// Depth-only pass into the shadow map: one instanced draw per mesh batch.
layout(location = 0) in vec3 osPosition;

layout(std430, binding = 0) readonly buffer Instances { mat4 worldFromObject[]; };

layout(std140, binding = 1) uniform DepthPass {
    mat4 clipFromWorld;          // the shadow view's light clip space
    vec4 linearDepthFromWorld;   // row: linear depth along the light, [0,1] over B
    vec4 depthLayout;            // x: 1 linear, 0 hyperbolic (clip z / w)
    vec4 bias;                   // linear layout: x slope factor, y constant (depth units)
};

// World position for the linear layout: interpolated perspective-correctly, so the
// fragment shader can compute the exact linear depth (see depth.frag).
out vec3 wsPosition;

void main() {
    const vec4 ws = worldFromObject[gl_InstanceID] * vec4(osPosition, 1.0);
    wsPosition = ws.xyz;
    gl_Position = clipFromWorld * ws;
}
