#version 450 core
// Hyperbolic layout: depth comes from the fixed-function stage and polygon offset
// supplies the bias. Linear layout (TSM paper; seed 000 §4.2): the stored depth is the
// distance along the light, computed here per fragment. Writing it per vertex instead
// (z = d·w) would be interpolated linearly in the *warped* map, which is wrong inside
// every large triangle and shows as acne; per fragment it is exact, and the bias is
// applied by hand since polygon offset does not act on gl_FragDepth.
in vec3 wsPosition;

layout(std140, binding = 1) uniform DepthPass {
    mat4 clipFromWorld;
    vec4 linearDepthFromWorld;
    vec4 depthLayout;
    vec4 bias;
};

void main() {
    if (depthLayout.x > 0.5) {
        const float d = dot(linearDepthFromWorld, vec4(wsPosition, 1.0));
        const float slope = max(abs(dFdx(d)), abs(dFdy(d))); // glPolygonOffset's "m"
        gl_FragDepth = d + bias.x * slope + bias.y;
    } else {
        gl_FragDepth = gl_FragCoord.z;
    }
}
