// Local lights' depth pass with a geometry shader: the vertex stage only places the vertex in
// the world; local_depth.geom projects each triangle into every face.
layout(location = 0) in vec3 osPosition;
#ifdef SK_MATERIAL
layout(location = 3) in vec2 uv; // the base colour texture's coordinates (material.glsl)
out vec2 vsUv; // to local_depth.geom
#endif

layout(std430, binding = SK_INSTANCES_BINDING) readonly buffer Instances { mat4 worldFromObject[]; };

out vec3 vsWorld;

void main() {
    const uint entry = skVisibleEntry(uint(gl_InstanceID));
    const mat4 worldFromThis = worldFromObject[skInstanceOf(entry)];
    vec3 os = osPosition;
#ifdef SK_MATERIAL
    vsUv = uv;
#endif
    if (skImpostorGrid.x > 0) { // an impostor's card, turned to the light
        vec2 cardUv;
        os = skImpostorCorner(osPosition, worldFromThis, vec4(wsLightInvRange.xyz, 1.0), cardUv);
#ifdef SK_MATERIAL
        vsUv = cardUv;
#endif
    }
    const vec4 ws = worldFromThis * vec4(os, 1.0);
    SK_PASS_CROSSING(entry); // through local_depth.geom
    vsWorld = ws.xyz;
    gl_Position = ws;
}
