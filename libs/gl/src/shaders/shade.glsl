// The main pass's colour of a surface point (main.frag; eval.frag's shaded variant, which draws
// the frame and the evaluation's buffers in one pass): diffuse sun + local lights + ambient +
// exponential distance fog, the sun masked by its shadow term; or, with aliasingOverlay, the
// pixels per texel of the map serving the pixel.

// Split colouring (Dimitrov 2007, Figure 3-2): red, green, blue, yellow, ...
const vec3 kCascadeTint[8] = vec3[](vec3(1.0, 0.35, 0.35), vec3(0.35, 1.0, 0.35), vec3(0.4, 0.5, 1.0),
    vec3(1.0, 1.0, 0.3), vec3(1.0, 0.4, 1.0), vec3(0.3, 1.0, 1.0), vec3(1.0, 0.7, 0.3), vec3(0.8, 0.8, 0.8));

// eval::aliasingMapImage's ramp (dark blue → green → yellow) over log2 pixels per texel in
// [-6, 6]: the same picture as `eval --aliasing-map`, live.
vec3 aliasingColor(float pixelsPerTexel) {
    const vec3 stops[5] = vec3[](vec3(68, 1, 84), vec3(59, 82, 139), vec3(33, 145, 140), vec3(94, 201, 98), vec3(253, 231, 37));
    const float t = clamp((log2(max(pixelsPerTexel, 1e-9)) + 6.0) / 12.0, 0.0, 1.0) * 4.0;
    const int i = min(3, int(t));
    return mix(stops[i], stops[i + 1], t - float(i)) / 255.0;
}

// Largest singular value of d(pixel)/d(texel) = 1 / smallest singular value of the
// Jacobian d(texel)/d(pixel) (core::pixelsPerTexel).
float pixelsPerTexel(vec2 dTexelDx, vec2 dTexelDy) {
    const float s = dot(dTexelDx, dTexelDx) + dot(dTexelDy, dTexelDy);
    const float det = dTexelDx.x * dTexelDy.y - dTexelDx.y * dTexelDy.x;
    const float smallest = sqrt(max(0.0, 0.5 * (s - sqrt(max(0.0, s * s - 4.0 * det * det)))));
    return smallest > 0.0 ? 1.0 / smallest : 1e9;
}

// The aliasing overlay's colour at `wsPosition`: the texel of the map serving this pixel,
// differentiated per pixel (call in uniform control flow).
vec4 aliasingOverlayColor(vec3 wsPosition) {
    const vec4 t = shadowTexture(sunMapOf(wsPosition), wsPosition);
    const vec2 texel = t.xy / t.w * mapTexels;
    return vec4(aliasingColor(pixelsPerTexel(dFdxFine(texel), dFdyFine(texel))), 1.0);
}

// The shaded colour of a point of `albedo` at `wsPosition`, gamma-encoded: `n` the side seen,
// `nDotL` max(n·l, 0), `lit` the sun's shadow term where it counts (0 where the sun does not
// light the point).
vec4 shadedColor(vec3 albedo, vec3 wsPosition, vec3 n, float nDotL, float lit) {
    if (cascadeColors != 0) albedo *= kCascadeTint[sunMapOf(wsPosition) % 8];
    vec3 color = albedo * (ambientRadiance.rgb + sunRadiance.rgb * nDotL * lit + localLighting(wsPosition, n));
    const float fog = exp(-fogColorDensity.a * distance(wsPosition, wsEye.xyz));
    color = mix(fogColorDensity.rgb, color, fog);
    return vec4(pow(clamp(color, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}
