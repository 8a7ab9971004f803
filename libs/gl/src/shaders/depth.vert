#version 450 core
// Depth-only pass into the shadow map: one instanced draw per mesh batch.
layout(location = 0) in vec3 osPosition;

layout(std430, binding = 0) readonly buffer Instances { mat4 worldFromObject[]; };

layout(std140, binding = 1) uniform DepthPass {
    mat4 clipFromWorld; // the shadow view's light clip space
};

void main() {
    gl_Position = clipFromWorld * (worldFromObject[gl_InstanceID] * vec4(osPosition, 1.0));
}
