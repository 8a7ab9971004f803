// Occlusion queries (gl/src/occlusion_culling.h): the boxes of hierarchy nodes, one
// instance per box, 36 vertices each, generated from the corner table without buffers.
layout(std430, binding = SK_BOXES_BINDING) readonly buffer Boxes { vec4 boxCorners[]; }; // min, max per box
layout(location = SK_BOX_OFFSET_LOCATION) uniform uint boxOffset;

// Corner c has x from bit 0, y from bit 1, z from bit 2 (1: max). Two triangles per face.
const int kCorners[36] = int[36](0, 2, 6, 0, 6, 4,  1, 3, 7, 1, 7, 5,  0, 1, 5, 0, 5, 4,
                                 2, 3, 7, 2, 7, 6,  0, 1, 3, 0, 3, 2,  4, 5, 7, 4, 7, 6);

void main() {
    const uint box = 2u * (boxOffset + uint(gl_InstanceID));
    const vec3 lo = boxCorners[box].xyz, hi = boxCorners[box + 1u].xyz;
    const int c = kCorners[gl_VertexID];
    const vec3 ws = vec3((c & 1) != 0 ? hi.x : lo.x, (c & 2) != 0 ? hi.y : lo.y, (c & 4) != 0 ? hi.z : lo.z);
    gl_Position = clipFromWorld * vec4(ws, 1.0);
}
