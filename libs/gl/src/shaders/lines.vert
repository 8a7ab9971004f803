// Insight wireframes: world-space segments with a colour each, over the frame.
layout(location = 0) in vec3 wsPosition;
layout(location = 1) in vec3 color;
layout(location = 0) uniform mat4 clipFromWorld;

out vec3 vColor;

void main() {
    vColor = color;
    gl_Position = clipFromWorld * vec4(wsPosition, 1.0);
}
