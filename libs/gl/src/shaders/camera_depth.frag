// Camera depth pre-pass (occlusion culling): depth for the queries, and the view depth of
// every pixel for the receiver mask and the visible depth range.
in vec3 wsPosition;
layout(location = 0) out float viewDepth;

void main() {
    const vec4 baseColor = skSurfaceBaseColor();
    viewDepth = dot(wsPosition - wsEye.xyz, wsViewForward.xyz);
    SK_DISCARD_UNCOVERED(baseColor); // a leaf card's holes occlude nothing (occlusion culling, receiver masks)
}
