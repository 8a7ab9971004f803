// Depth-only pass into the shadow map: one instanced draw per mesh batch.
layout(location = 0) in vec3 osPosition;

layout(std430, binding = SK_INSTANCES_BINDING) readonly buffer Instances { mat4 worldFromObject[]; };

// World position for the linear layout: interpolated perspective-correctly, so the
// fragment shader can compute the exact linear depth (see depth.frag).
out vec3 wsPosition;

void main() {
    const vec4 ws = worldFromObject[gl_InstanceID] * vec4(osPosition, 1.0);
    wsPosition = ws.xyz;
    gl_Position = clipFromWorld * ws;
}
