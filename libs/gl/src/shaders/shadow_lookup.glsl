// The renderer's side of the sun's shadow lookup: the Frame uniforms handed to
// glsl/shadowkit_shadows.glsl (before this file), which holds the lookup itself — hardware
// comparison, linear depth, normal offset, receiver-plane bias, filters, cascade selection
// and blending — so that the renderer and engines share one implementation.
//
// Two variants, by SK_VIRTUAL_MAPS (defined before this file; 0 when not): with virtual maps
// the lookup goes through the page table, without them it is the cascades' alone. One shader
// with a uniform branch between them cost llvmpipe 1.45× the camera pass for every technique
// (it runs both sides), so the renderer builds both and draws with the one the set-up needs.
#ifndef SK_VIRTUAL_MAPS
#define SK_VIRTUAL_MAPS 0
#endif
layout(binding = SK_SHADOW_MAP_UNIT) uniform sampler2DArrayShadow shadowMap; // or the virtual page atlas
layout(binding = SK_PAGE_TABLE_UNIT) uniform usampler2D pageTable;             // virtual maps' page table

float viewDepthOf(vec3 ws) { return dot(ws - wsEye.xyz, wsViewForward.xyz); }

// Where a receiver looks itself up: a simplified surface lies up to `lodError` metres off
// the true one, which the map holds, so it is moved that far towards the light — never
// behind its own surface (no self-shadowing), at most a fraction of a pixel from it (the
// level was chosen so). Exactly `ws` for full meshes and levels that keep coverage (lodError 0:
// gpu_scene.cpp, rangesOf).
vec3 receiverLookup(vec3 ws, float lodError) { return ws + wsTowardsLight.xyz * lodError; }

int cascadeOf(float viewDepth) { return skCascadeOf(viewDepth, mapCount); }

SkVirtualMaps virtualMaps() {
    return SkVirtualMaps(virtualLevels, virtualFirstExponent, virtualFootprintPerMetre, virtualLodBias, virtualPagesPerSide,
                         virtualPageTexels, virtualGuardTexels, virtualSlotsPerRow, virtualAtlasTexels, virtualTexels,
                         virtualBlendBand);
}

// The sun's map serving `ws`: its cascade, or the clipmap level its lookup reads.
int sunMapOf(vec3 ws) {
    const float viewDepth = viewDepthOf(ws);
#if SK_VIRTUAL_MAPS
    int level;
    vec4 atlasFromMap;
    return skVirtualPage(pageTable, virtualMaps(), viewDepth, ws, level, atlasFromMap) ? level : virtualLevels - 1;
#else
    return cascadeOf(viewDepth);
#endif
}

// Texture coordinates of the map serving `ws`, times w (textureFromWorld of the core's
// output conventions: u, v = ndc · 0.5 + 0.5, depth [0, 1]).
vec4 shadowTexture(int map, vec3 ws) { return shadowTextureFromWorld[map] * vec4(ws, 1.0); }

SkShadowOptions shadowOptions() {
    return SkShadowOptions(mapTexels, linearLayout != 0, normalOffsetTexels, receiverPlane != 0, filterKind, filterTaps,
                           poissonRadiusTexels, lightTanHalfAngle, normalOffsetFootprint, offsetGuard != 0);
}

// `dwsdx`, `dwsdy`: screen derivatives of ws, taken by the caller in uniform control flow.
float shadowTerm(vec3 ws, vec3 n, vec3 dwsdx, vec3 dwsdy) {
#if SK_VIRTUAL_MAPS
    return skVirtualShadow(shadowMap, pageTable, virtualMaps(), shadowOptions(), viewDepthOf(ws), ws, n, dwsdx, dwsdy);
#else
    return skCascadedShadow(shadowMap, mapCount, shadowOptions(), viewDepthOf(ws), ws, n, dwsdx, dwsdy);
#endif
}
