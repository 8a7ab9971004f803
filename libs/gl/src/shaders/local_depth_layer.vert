// Local lights' depth pass, layered from the vertex shader (GL_ARB_shader_viewport_layer_array):
// every instance is drawn `replicas` times, each copy to its own cube face, so all the faces
// of a light are written by one instanced draw per batch, with no geometry shader.
layout(location = 0) in vec3 osPosition;
#ifdef SK_MATERIAL
layout(location = 3) in vec2 uv; // the base colour texture's coordinates (material.glsl)
out vec2 vUv;
#endif

layout(std430, binding = SK_INSTANCES_BINDING) readonly buffer Instances { mat4 worldFromObject[]; };

out vec3 wsPosition;
// The longest edge, in object space, of the mesh's triangles this vertex belongs to (GpuScene).
layout(location = SK_EDGE_ATTRIBUTE) in float osLongestEdge;

void main() {
    const uint copies = uint(replicas);
    const uint entry = skVisibleEntry(uint(gl_InstanceID) / copies);
    const uint instance = skInstanceOf(entry);
    SK_PASS_CROSSING(entry);
    const int face = faceOf(int(uint(gl_InstanceID) % copies));
    vec3 os = osPosition;
#ifdef SK_MATERIAL
    vUv = uv;
#endif
    if (skImpostorGrid.x > 0) { // an impostor's card, turned to the light
        vec2 cardUv;
        os = skImpostorCorner(osPosition, worldFromObject[instance], vec4(wsLightInvRange.xyz, 1.0), cardUv);
#ifdef SK_MATERIAL
        vUv = cardUv;
#endif
    }
    const vec4 ws = worldFromObject[instance] * vec4(os, 1.0);
    wsPosition = ws.xyz;
    gl_Position = faceClipFromWorld[face] * ws;
    const float wsLongestEdge = osLongestEdge * skLargestStretch(worldFromObject[instance]);
    gl_Position.z = skLocalConservativeClipZ(distance(ws.xyz, wsLightInvRange.xyz) - wsLongestEdge, gl_Position.w);
    gl_Layer = layerBase + face;
}
