#version 450 core
// Main (camera) pass: positions, normals and the shadow-map clip coordinates per vertex.
layout(location = 0) in vec3 osPosition;
layout(location = 1) in vec3 osNormal;
layout(location = 2) in vec3 albedo;

layout(std430, binding = 0) readonly buffer Instances { mat4 worldFromObject[]; };

layout(std140, binding = 0) uniform Frame {
    mat4 clipFromWorld;       // camera
    mat4 shadowClipFromWorld; // light clip space of the shadow map
    vec4 wsEye;               // xyz
    vec4 wsTowardsLight;      // xyz, unit
    vec4 sunRadiance;         // rgb
    vec4 ambientRadiance;     // rgb
    vec4 fogColorDensity;     // rgb, a: density in 1/m
};

out vec3 wsPosition;
out vec3 wsNormal;
out vec3 vAlbedo;
// Interpolated in clip space and divided per fragment: correct for perspective warps too,
// where dividing per vertex would interpolate the wrong way.
out vec4 csShadow;

void main() {
    const mat4 m = worldFromObject[gl_InstanceID];
    const vec4 ws = m * vec4(osPosition, 1.0);
    wsPosition = ws.xyz;
    wsNormal = mat3(m) * osNormal; // rigid + uniform scale: renormalised per fragment
    vAlbedo = albedo;
    csShadow = shadowClipFromWorld * ws;
    gl_Position = clipFromWorld * ws;
}
