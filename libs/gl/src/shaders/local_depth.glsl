// The local lights' depth pass (local_shadows.h), shared by its stages. The C++ side is
// LocalDepthUniforms in uniforms.h. One draw writes every cube face of a point light that
// sees something (or a spot light's one view): replica r of each instance, or invocation r
// of the geometry shader, goes to face faceOf(r) at array layer layerBase + face.
layout(std140, binding = SK_LOCAL_DEPTH_BINDING) uniform LocalDepth {
    mat4 faceClipFromWorld[6]; // per cube face (GL order +X, -X, +Y, -Y, +Z, -Z); a spot's view in [0]
    vec4 wsLightInvRange;      // xyz: the light; w: 1 / range
    ivec4 faceOfReplica[2];    // [r / 4][r % 4]
    int layerBase;
    int replicas;              // faces written by one draw, 1 to 6
};

int faceOf(int replica) { return faceOfReplica[replica / 4][replica % 4]; }

// The rasterised depth of a vertex `w` its clip w: a lower bound of the distance over range that
// local_depth.frag writes anywhere on the vertex's triangles, so it can declare
// layout(depth_greater) and early depth tests reject covered fragments before they are shaded.
// A point p of a triangle lies within its longest edge L of each vertex p_i, so by the triangle
// inequality |p − light| ≥ |p_i − light| − L: each vertex rasterised at that (`leastMetres`), any
// interpolation of them, screen-linear as the rasteriser's is, stays at or below the largest,
// which is at or below the distance at p. Under depth clamping both are clamped alike.
float skLocalConservativeClipZ(float leastMetres, float w) { return (leastMetres * wsLightInvRange.w - 1e-6) * w; }
