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
    // The triangle's least distance from the light, a bound every vertex rasterises at
    // (skLocalConservativeClipZ): the largest vertex distance less the longest edge, or the
    // distance to the triangle's plane, whichever is nearer the truth. The plane's only where the
    // triangle is no sliver (its area at least a hundredth of its longest edge squared), whose
    // normal rounding would tilt, and with a margin. None for a triangle the light sees edge-on
    // (its plane within 0.6° of the light): its fragments, a line across the map, interpolate
    // their positions from a projection of no area, and one such fragment of 2.2 M on the leafy
    // forest wrote a distance 0.4 m short of any point of its triangle.
    const vec3 light = wsLightInvRange.xyz;
    const vec3 a = vsWorld[0], b = vsWorld[1], c = vsWorld[2];
    const float longest = max(max(distance(a, b), distance(b, c)), distance(c, a));
    const vec3 normal = cross(b - a, c - a);
    const bool sliver = length(normal) < 0.02 * longest * longest;
    const float plane = sliver ? 0.0 : 0.99 * abs(dot(normalize(normal), a - light));
    const bool edgeOn = sliver || plane < 0.01 * distance(a, light);
    const float least =
        edgeOn ? 0.0 : max(max(max(distance(a, light), distance(b, light)), distance(c, light)) - 1.001 * longest, plane);
    for (int i = 0; i < 3; ++i) {
        wsPosition = vsWorld[i];
#ifdef SK_MATERIAL
        vUv = vsUv[i];
        vCrossing = vsCrossing[i];
#endif
        gl_Position = faceClipFromWorld[face] * vec4(vsWorld[i], 1.0);
        gl_Position.z = skLocalConservativeClipZ(least, gl_Position.w);
        gl_Layer = layerBase + face;
        EmitVertex();
    }
    EndPrimitive();
}
