// Seed 003's layered cube pass: one geometry-shader invocation per face emits the triangle
// into that face's layer (gl_Layer), so a light's cube is written in one pass.
layout(triangles, invocations = 6) in;
layout(triangle_strip, max_vertices = 3) out;

in vec3 vsWorld[];
out vec3 wsPosition;
#ifdef SK_MATERIAL
in vec2 vsUv[];
out vec2 vUv;
flat in uint vsCrossing[]; // local_depth_world.vert's (visible.glsl)
flat out uint vCrossing;   // to material.glsl
#endif

void main() {
    if (gl_InvocationID >= replicas) return;
    const int face = faceOf(gl_InvocationID);
    for (int i = 0; i < 3; ++i) {
        wsPosition = vsWorld[i];
#ifdef SK_MATERIAL
        vUv = vsUv[i];
        vCrossing = vsCrossing[i];
#endif
        gl_Position = faceClipFromWorld[face] * vec4(vsWorld[i], 1.0);
        gl_Layer = layerBase + face;
        EmitVertex();
    }
    EndPrimitive();
}
