// Camera passes: positions, normals and surface identity.
layout(location = 0) in vec3 osPosition;
layout(location = 1) in vec3 osNormal;
layout(location = 2) in vec3 albedo;
#ifdef SK_MATERIAL
layout(location = 3) in vec2 uv; // the base colour texture's coordinates (material.glsl)
out vec2 vUv;
#endif

// Global index of this batch's first instance: surface identity shared with the ray tracer.
layout(location = SK_INSTANCE_BASE_LOCATION) uniform uint instanceBase;

// The geometric error of each level of detail the draw holds, in object metres (0: the full mesh):
// one level, or several in a multi-draw (GpuScene::drawLevels), the draw's index within it
// (gl_DrawIDARB, where vertex stages read it: program.h) naming its level.
layout(location = SK_LOD_ERROR_LOCATION) uniform float lodObjectErrors[SK_CULL_LEVELS];
#ifndef SK_DRAW_ID
#define SK_DRAW_ID 0u
#endif

out vec3 wsPosition;
out vec3 wsNormal;
out vec3 vAlbedo;
flat out uint vSurfaceId;
flat out float vLodError; // in world metres

// The camera's depth pre-pass and the camera passes run this shader in different programs; the
// passes then test against the pre-pass's depth with GL_LEQUAL (CameraPasses), which needs the
// same depth to the bit for the same vertex (GLSL 4.50 §4.8.1).
invariant gl_Position;

void main() {
    const uint entry = skVisibleEntry(uint(gl_InstanceID));
    const uint instance = skInstanceOf(entry);
    SK_PASS_CROSSING(entry);
    const mat4 m = worldFromObject[instance];
    const vec4 ws = m * vec4(osPosition, 1.0);
    wsPosition = ws.xyz;
    wsNormal = mat3(m) * osNormal; // rigid + uniform scale: renormalised per fragment
    vAlbedo = albedo;
#ifdef SK_MATERIAL
    vUv = uv;
#endif
    vSurfaceId = instanceBase + instance + 1u;
    // Rigid + uniform scale. The index clamped: a multi-draw of a large mesh's runs of clusters
    // (a depth pre-pass's, which reads no error) counts draws past the levels.
    vLodError = lodObjectErrors[min(SK_DRAW_ID, uint(SK_CULL_LEVELS - 1))] * length(m[0].xyz);
    gl_Position = clipFromWorld * ws;
}
