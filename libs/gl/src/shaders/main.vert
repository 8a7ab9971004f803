// Camera passes: positions, normals, surface identity and shadow-map clip coordinates.
layout(location = 0) in vec3 osPosition;
layout(location = 1) in vec3 osNormal;
layout(location = 2) in vec3 albedo;

// Global index of this batch's first instance: surface identity shared with the ray tracer.
layout(location = 0) uniform uint instanceBase;

out vec3 wsPosition;
out vec3 wsNormal;
out vec3 vAlbedo;
flat out uint vSurfaceId;
// Interpolated in clip space and divided per fragment: correct for perspective warps too,
// where dividing per vertex would interpolate the wrong way.
out vec4 csShadow;

void main() {
    const mat4 m = worldFromObject[gl_InstanceID];
    const vec4 ws = m * vec4(osPosition, 1.0);
    wsPosition = ws.xyz;
    wsNormal = mat3(m) * osNormal; // rigid + uniform scale: renormalised per fragment
    vAlbedo = albedo;
    vSurfaceId = instanceBase + uint(gl_InstanceID) + 1u;
    csShadow = shadowClipFromWorld * ws;
    gl_Position = clipFromWorld * ws;
}
