// The instances a pass draws, for the vertex stages (gl/src/visibility.h, PassList): one entry
// per instance and level of detail, the instance's index in its batch in the low 24 bits. An
// instance crossing into a coarser level (LodChoice::fadeBand) has an entry in both levels'
// lists, with the coarser level's share of the pixels in bits 24–30 (128ths) and bit 31 set in
// the coarser level's entry; material.glsl's fragment stages keep each level's share.
layout(std430, binding = SK_VISIBLE_BINDING) readonly buffer Visible { uint visibleInstances[]; };
layout(location = SK_INSTANCE_OFFSET_LOCATION) uniform uint instanceOffset;

// A GPU-culled list's indirect command carries where its level's entries start as its base
// instance, which vertex stages read where the driver lets them (program.h,
// vertexStagesReadDrawParameters, defines SK_BASE_INSTANCE): one multi-draw then draws several
// levels. Direct draws have 0; so has a vertex stage that cannot read it, drawn one level a draw.
#ifndef SK_BASE_INSTANCE
#define SK_BASE_INSTANCE 0u
#endif

uint skVisibleEntry(uint k) { return visibleInstances[instanceOffset + SK_BASE_INSTANCE + k]; }
uint skInstanceOf(uint entry) { return entry & 0xFFFFFFu; }

// The most an instance's transform `m` stretches a length: √λ_max(AᵀA) of its linear part A,
// bounded by Gershgorin's largest row sum of AᵀA — exact for a rotation with any scales along its
// axes, a bound when sheared too (the longest axis alone is not one then). For the depth passes'
// bounds (depth_pass.glsl, local_depth.glsl), which take an object-space edge into the world.
float skLargestStretch(mat4 m) {
    const float g01 = abs(dot(m[0].xyz, m[1].xyz)), g02 = abs(dot(m[0].xyz, m[2].xyz)), g12 = abs(dot(m[1].xyz, m[2].xyz));
    return sqrt(max(max(dot(m[0].xyz, m[0].xyz) + g01 + g02, dot(m[1].xyz, m[1].xyz) + g01 + g12),
                    dot(m[2].xyz, m[2].xyz) + g02 + g12));
}

#ifdef SK_MATERIAL
#ifndef SK_CROSSING_OUT // a geometry stage between passes it on under another name (local_depth.geom)
#define SK_CROSSING_OUT vCrossing
#endif
flat out uint SK_CROSSING_OUT; // the entry's top byte (material.glsl)
#define SK_PASS_CROSSING(entry) SK_CROSSING_OUT = (entry) >> 24
#else
#define SK_PASS_CROSSING(entry)
#endif
