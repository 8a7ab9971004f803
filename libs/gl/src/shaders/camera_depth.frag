// Camera depth pre-pass (occlusion culling): depth for the queries, and the view depth of
// every pixel for the receiver mask and the visible depth range.
in vec3 wsPosition;
layout(location = 0) out float viewDepth;

void main() { viewDepth = dot(wsPosition - wsEye.xyz, wsViewForward.xyz); }
