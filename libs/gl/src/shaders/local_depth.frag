// Stores the distance to the light over its range (seed 003: linear distance, the same unit
// on every face), exact per fragment. No bias here: the lookup applies it in metres.
in vec3 wsPosition;

void main() {
    const vec4 baseColor = skSurfaceBaseColor();
    gl_FragDepth = distance(wsPosition, wsLightInvRange.xyz) * wsLightInvRange.w;
    SK_DISCARD_UNCOVERED(baseColor);
}
