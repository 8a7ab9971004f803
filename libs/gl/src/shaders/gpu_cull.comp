// GPU-driven culling (gl/src/gpu_culling.h): the instances of one pass, or of several passes of
// one kind at once (a frame's virtual pages; gl_WorkGroupID.y the pass), into draw lists and
// indirect commands, with the same rules as the CPU path (gl/src/visibility.cpp), in three
// dispatches so that every list comes out in increasing instance order — the order a full
// draw uses, so culling changes no pixel even where two instances' depths tie:
//   SK_CULL_STAGE 1, one work group per chunk (up to 128 consecutive instances of one batch) and pass:
//     which instances the pass keeps and at which level (and whether each crosses into the next,
//     LodChoice::fadeBand: then it is kept at both), and each one's rank among the kept
//     instances of its chunk and level (a prefix sum in shared memory, 8-bit counters packed
//     four to a uint);
//   SK_CULL_STAGE 2, one invocation per batch, level and pass: the chunks' counts into offsets,
//     and the level's glDrawElementsIndirect command (its instance count: the total);
//   SK_CULL_STAGE 3, one work group per chunk and pass: each kept instance's list entry (batch-local
//     index, and its crossing: visibility.h) to its place, offset + rank, in its batch and
//     level's region of the pass, and a crossing instance's second entry to the next level's.
// Frustum and level of detail are decided in double precision like the CPU's, so the
// lists equal Visibility::collect's (a float test would flip an instance whose box touches a
// plane, or whose projected error sits on a level's bound, about once in 10^7: every frame at
// 100,000 trees); the occlusion test against the depth pyramid is float and conservative.

#if SK_CULL_STAGE != 2
layout(local_size_x = SK_CULL_GROUP) in;
#endif

struct Instance {
    dvec4 minScale; // xyz: the box's minimum, w: the instance's uniform scale
    dvec4 max;      // xyz: the box's maximum
};
struct Batch {
    uint first, count;               // global index of the first instance; instances
    uint cameraLevels, shadowLevels; // levels of each chain, [1, SK_CULL_LEVELS]
    uint firstChunk, chunkCount;
    uint clustered; // 1: its mesh draws by triangle clusters (a terrain: GpuScene::drawsByClusters)
    uint pad1;
};
// A pass: what it keeps and its own level-of-detail projection (the rest of the choice, below,
// is the dispatch's). passes[] is indexed by GpuCulling's pass, as the lists' regions and the
// commands are; a dispatch culls passes firstPass to firstPass + gl_NumWorkGroups.y − 1.
struct Pass {
    dvec4 planes[6]; // half-spaces: inside where dot(xyz, p) + w >= 0 (a clip volume's or a box's)
    dmat4 passClipFromWorld;
    double passUnitsPerNdc, passMaxError;
    int planeCount;
};
struct Level {
    float cameraError, shadowError;          // object metres (scene::LodLevel::objectError)
    uint cameraIndexCount, cameraFirstIndex; // in the mesh's index buffer
    uint shadowIndexCount, shadowFirstIndex;
    uint keepsCoverage; // bit 0: the camera chain's level, bit 1: the shadow chain's (scene::LodLevel::keepsCoverage)
    uint pad1;
};

layout(std430, binding = SK_CULL_CHUNKS_BINDING) readonly buffer Chunks {
    uvec4 chunks[];
}; // batch, first global, count, first batch-local
layout(std430, binding = SK_CULL_BATCHES_BINDING) readonly buffer Batches { Batch batches[]; };
layout(std430, binding = SK_CULL_RANKS_BINDING) buffer Ranks {
    uint ranks[];
}; // [pass * instanceCount + global instance]: fade << 24 | next level's rank << 16 | level << 8 | rank, or ~0u
layout(std430, binding = SK_CULL_CHUNK_SUMS_BINDING) buffer ChunkSums {
    uint chunkSums[];
}; // [(pass * chunkCount + chunk) * SK_CULL_LEVELS + level]: the chunk's count at the level, then its offset
layout(std430, binding = SK_CULL_PASSES_BINDING) readonly buffer Passes { Pass passes[]; };
uniform uint firstPass;
// ranks[] and chunkSums[] hold the dispatch's passes one after another (gl_WorkGroupID.y).
uniform uint instanceCount, chunkCount;

const uint kNotKept = 0xFFFFFFFFu;

#if SK_CULL_STAGE == 1

layout(std430, binding = SK_CULL_INSTANCES_BINDING) readonly buffer Instances { Instance instances[]; };
layout(std430, binding = SK_CULL_LEVELS_BINDING) readonly buffer Levels { Level levels[]; }; // [batch * SK_CULL_LEVELS + level]
layout(std430, binding = SK_CULL_FLAGS_BINDING) buffer Flags {
    uint wasVisible[];
}; // the camera's visible set, frame to frame

// What the pass keeps (GpuCulling::Phase).
const int kAll = 0, kLastVisible = 1, kNewlyVisible = 2, kVisible = 3;
uniform int phase;
// Levels of detail (gl/src/visibility.h, LodChoice; each pass's own projection in passes[]): off
// when lodOn is false.
uniform bool lodOn;
uniform bool shadowChain;
uniform bool cameraBound;
uniform dmat4 cameraClipFromWorld;
uniform double cameraUnitsPerNdc, cameraMaxError;
uniform double coverageScale; // LodChoice::coverageScale: levels that keep coverage may err this many times more
uniform double fadeBand;      // LodChoice::fadeBand
// A virtual page's pass: the batches whose meshes draw by clusters are left to the CPU, which
// draws of them only the clusters meeting the page (GpuCulling::cull's leaveClustered).
uniform bool leaveClustered;
// Occlusion (phases kNewlyVisible and kVisible): the depth pyramid of the camera's pre-pass.
layout(std430, binding = SK_CULL_STAGE_BINDING) readonly buffer Pyramid {
    float pyramid[];
};                                                      // level k: farthest over 2^(k+1) pixels
uniform ivec4 pyramidLevel[SK_CULL_MAX_PYRAMID_LEVELS]; // per level: width, height, offset in pyramid[]
uniform int pyramidLevels;
uniform ivec2 viewport;
uniform mat4 clipFromWorld; // the camera's
uniform vec3 wsEye;
// Shadow passes with receiver masks (receiver_masks.h, markOnGpu): this map's dilated mask.
layout(std430, binding = SK_DILATED_MASK_BINDING) readonly buffer Masks { uint masks[]; };
uniform bool maskOn;
uniform int maskSize, maskBase, maskFlag; // the map's first texel and its flag in masks[]
uniform dmat4 maskClipFromWorld;
uniform bool maskLinear; // the map stores dot(maskLinearDepthFromWorld, (ws, 1)), not z / w
uniform dvec4 maskLinearDepthFromWorld;
const int kMaxMaskTexels = 1024; // a caster's footprint wider than this is kept untested

bool outsideVolume(uint region, dvec3 lo, dvec3 hi) {
    if (!(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z)) return true; // empty (or NaN) boxes
    for (int i = 0; i < passes[region].planeCount; ++i) {
        const dvec4 h = passes[region].planes[i];
        // The corner furthest along the normal ("positive vertex").
        const dvec3 p = dvec3(h.x >= 0.0 ? hi.x : lo.x, h.y >= 0.0 ? hi.y : lo.y, h.z >= 0.0 ? hi.z : lo.z);
        if (!(h.x * p.x + h.y * p.y + h.z * p.z + h.w >= 0.0)) return true;
    }
    return false;
}

// NDC units per world metre at `ws` (visibility.cpp's ndcPerMetre); negative: infinite.
double ndcPerMetre(dmat4 m, dvec3 ws) {
    const dvec4 c = m * dvec4(ws, 1.0);
    if (!(c.w > 1e-9)) return -1.0;
    const dvec2 ndc = c.xy / c.w;
    double largest = 0.0;
    for (int i = 0; i < 3; ++i) largest = max(largest, length((m[i].xy - ndc * m[i].w) / c.w));
    return largest;
}

// The error a level may have, in object metres, by one bound.
double allowedBy(dmat4 m, double unitsPerNdc, double maxError, dvec3 centre, double scale) {
    const double npm = ndcPerMetre(m, centre);
    if (npm < 0.0) return 0.0;
    const double denominator = unitsPerNdc * npm * scale;
    return denominator > 0.0 ? maxError / denominator : 1e300lf;
}

// visibility.cpp's fadeStepsOf: the coarser level's share of the pixels in 128ths (0: none).
uint fadeOf(double allowed, double coarserError) {
    if (!(fadeBand > 0.0) || !(coarserError > 0.0)) return 0u;
    const double share = (allowed / coarserError - (1.0 - fadeBand)) / fadeBand;
    if (!(share > 0.0)) return 0u;
    return uint(min(floor(share * 128.0), 127.0));
}

// The instance's level, and in .y its crossing into the next (fadeOf).
uvec2 levelOf(uint region, uint batch, dvec3 centre, double scale) {
    const uint count = shadowChain ? batches[batch].shadowLevels : batches[batch].cameraLevels;
    if (!lodOn || count < 2u) return uvec2(0u);
    double allowed = allowedBy(passes[region].passClipFromWorld, passes[region].passUnitsPerNdc,
                               passes[region].passMaxError, centre, scale);
    if (cameraBound)
        allowed = min(allowed, allowedBy(cameraClipFromWorld, cameraUnitsPerNdc, cameraMaxError, centre, scale));
    uint level = 0u;
    while (level + 1u < count) {
        const Level next = levels[batch * SK_CULL_LEVELS + level + 1u];
        const bool coverage = (next.keepsCoverage & (shadowChain ? 2u : 1u)) != 0u;
        if (!(double(shadowChain ? next.shadowError : next.cameraError) <=
              (coverage ? allowed * coverageScale : allowed)))
            break;
        ++level;
    }
    if (level + 1u >= count) return uvec2(level, 0u);
    const Level next = levels[batch * SK_CULL_LEVELS + level + 1u];
    if ((next.keepsCoverage & (shadowChain ? 2u : 1u)) == 0u) return uvec2(level, 0u);
    return uvec2(level, fadeOf(allowed * coverageScale, double(shadowChain ? next.shadowError : next.cameraError)));
}

// False only when the box, grown as the CHC++ query boxes are (occlusion_culling.cpp), lies
// wholly behind the pyramid's farthest depth over the pixels it covers.
bool mayBeVisible(vec3 lo, vec3 hi) {
    const vec3 nearest = clamp(wsEye, lo, hi);
    const float margin = 0.01 + 1e-3 * distance(nearest, wsEye);
    lo -= margin;
    hi += margin;
    vec2 ndcMin = vec2(1e30), ndcMax = vec2(-1e30);
    float zMin = 1e30;
    for (int i = 0; i < 8; ++i) {
        const vec3 p = vec3((i & 1) != 0 ? hi.x : lo.x, (i & 2) != 0 ? hi.y : lo.y, (i & 4) != 0 ? hi.z : lo.z);
        const vec4 c = clipFromWorld * vec4(p, 1.0);
        if (!(c.w > 0.0) || c.z < 0.0) return true; // reaches the near plane: no depth to compare
        ndcMin = min(ndcMin, c.xy / c.w);
        ndcMax = max(ndcMax, c.xy / c.w);
        zMin = min(zMin, c.z / c.w); // clip depth [0, 1] (glClipControl) is window depth
    }
    const ivec2 p0 = clamp(ivec2(floor((ndcMin * 0.5 + 0.5) * vec2(viewport))), ivec2(0), viewport - 1);
    const ivec2 p1 = clamp(ivec2(floor((ndcMax * 0.5 + 0.5) * vec2(viewport))), ivec2(0), viewport - 1);
    // The finest level at which the pixels span at most two texels a side: four fetches.
    int level = 0;
    while (level + 1 < pyramidLevels && any(greaterThan((p1 >> (level + 1)) - (p0 >> (level + 1)), ivec2(1)))) ++level;
    const ivec4 at = pyramidLevel[level];
    const ivec2 t0 = p0 >> (level + 1), t1 = p1 >> (level + 1), last = at.xy - 1;
    float farthest = 0.0;
    for (int y = t0.y; y <= t1.y; ++y)
        for (int x = t0.x; x <= t1.x; ++x) {
            const ivec2 t = min(ivec2(x, y), last);
            farthest = max(farthest, pyramid[at.z + t.y * at.x + t.x]);
        }
    return zMin <= farthest;
}

int maskTexelOf(double ndc) { return clamp(int(floor((0.5 * ndc + 0.5) * double(maskSize))), 0, maskSize - 1); }

uint encodeDepth(float d) { // receiver_mask.comp's
    const uint bits = floatBitsToUint(d);
    return (bits & 0x80000000u) != 0u ? ~bits : bits | 0x80000000u;
}

// visibility::ReceiverMask::mayShadow on the GPU: false only when every mask texel under
// the box's footprint holds receivers nearer the light than the box's nearest corner (the
// argument in visibility/src/receiver_mask.cpp). The CPU climbs a max pyramid until the
// footprint spans 4 texels; here the texels are read at full resolution, up to a bound.
bool mayShadow(dvec3 lo, dvec3 hi) {
    if (masks[maskFlag] != 0u) return true;
    dvec2 ndcMin = dvec2(1e300lf), ndcMax = dvec2(-1e300lf);
    double nearest = 1e300lf;
    for (int i = 0; i < 8; ++i) {
        const dvec3 p = dvec3((i & 1) != 0 ? hi.x : lo.x, (i & 2) != 0 ? hi.y : lo.y, (i & 4) != 0 ? hi.z : lo.z);
        const dvec4 clip = maskClipFromWorld * dvec4(p, 1.0);
        if (!(clip.w > 1e-12)) return true;
        ndcMin = min(ndcMin, clip.xy / clip.w);
        ndcMax = max(ndcMax, clip.xy / clip.w);
        nearest = min(nearest, maskLinear ? dot(maskLinearDepthFromWorld, dvec4(p, 1.0)) : clip.z / clip.w);
    }
    if (ndcMax.x < -1.0 || ndcMin.x > 1.0 || ndcMax.y < -1.0 || ndcMin.y > 1.0) return false; // beside the map
    const ivec2 t0 = ivec2(maskTexelOf(ndcMin.x), maskTexelOf(ndcMin.y));
    const ivec2 t1 = ivec2(maskTexelOf(ndcMax.x), maskTexelOf(ndcMax.y));
    if ((t1.x - t0.x + 1) * (t1.y - t0.y + 1) > kMaxMaskTexels) return true;
    // A texel at or beyond the nearest depth, with a float step to spare (the marks are float).
    const uint threshold = encodeDepth(float(nearest)) - 1u;
    for (int y = t0.y; y <= t1.y; ++y)
        for (int x = t0.x; x <= t1.x; ++x)
            if (masks[maskBase + y * maskSize + x] >= threshold) return true;
    return false;
}

// An instance's counters: one per level, 8 bits each (a chunk keeps at most 128 instances a
// level), four to a uint. kWords uints hold SK_CULL_LEVELS of them.
const uint kWords = (SK_CULL_LEVELS + 3u) / 4u;
struct Counters {
    uint word[kWords];
};
shared Counters scan[SK_CULL_GROUP];

uint counterOf(Counters c, uint level) { return c.word[level >> 2] >> (8u * (level & 3u)) & 0xFFu; }

void main() {
    const uvec4 chunk = chunks[gl_WorkGroupID.x];
    const uint pass = gl_WorkGroupID.y;
    const uint local = gl_LocalInvocationID.x;
    const uint global = chunk.y + local;
    Counters mine;
    for (uint w = 0u; w < kWords; ++w) mine.word[w] = 0u;
    uint level = 0u, fade = 0u;
    bool keep = false;
    if (local < chunk.z) {
        const Instance instance = instances[global];
        const dvec3 lo = instance.minScale.xyz, hi = instance.max.xyz;
        const bool inVolume = !outsideVolume(firstPass + pass, lo, hi);
        const bool was = wasVisible[global] != 0u;
        const bool tested = inVolume && (phase == kNewlyVisible || phase == kVisible);
        const bool visible = tested && mayBeVisible(vec3(lo), vec3(hi));
        if (phase == kAll)
            keep = inVolume && (!maskOn || mayShadow(lo, hi));
        else if (phase == kLastVisible)
            keep = inVolume && was;
        else if (phase == kNewlyVisible)
            keep = visible && !was;
        else // what the pyramid does not hide: one drawn in the early phase but hidden now by
             // others drawn there has no pixel the main pass could shade (the pyramid holds its
             // own depth wherever it won), so it is left out this frame, not the next
            keep = visible;
        if (phase == kVisible) wasVisible[global] = visible ? 1u : 0u;
        if (leaveClustered && batches[chunk.x].clustered != 0u) keep = false;
        if (keep) {
            const uvec2 chosen = levelOf(firstPass + pass, chunk.x, 0.5 * (lo + hi), instance.minScale.w);
            level = chosen.x;
            fade = chosen.y;
            mine.word[level >> 2] |= 1u << (8u * (level & 3u));
            if (fade != 0u) // kept at the next level too
                mine.word[(level + 1u) >> 2] |= 1u << (8u * ((level + 1u) & 3u));
        }
    }
    // Inclusive prefix sum over the group (Hillis & Steele): each level's counter stays
    // below 256, so they never carry into each other.
    scan[local] = mine;
    barrier();
    for (uint stride = 1u; stride < SK_CULL_GROUP; stride <<= 1) {
        Counters add;
        for (uint w = 0u; w < kWords; ++w) add.word[w] = local >= stride ? scan[local - stride].word[w] : 0u;
        barrier();
        for (uint w = 0u; w < kWords; ++w) scan[local].word[w] += add.word[w];
        barrier();
    }
    Counters before;
    for (uint w = 0u; w < kWords; ++w) before.word[w] = scan[local].word[w] - mine.word[w];
    if (local < chunk.z)
        ranks[pass * instanceCount + global] = keep ? fade << 24 | (fade != 0u ? counterOf(before, level + 1u) << 16 : 0u) | level << 8 |
                                   counterOf(before, level)
                             : kNotKept;
    if (local == SK_CULL_GROUP - 1u)
        for (uint l = 0u; l < SK_CULL_LEVELS; ++l)
            chunkSums[(pass * chunkCount + gl_WorkGroupID.x) * SK_CULL_LEVELS + l] = counterOf(scan[local], l);
}

#elif SK_CULL_STAGE == 2

layout(local_size_x = 64) in;
layout(std430, binding = SK_CULL_LEVELS_BINDING) readonly buffer Levels { Level levels[]; };
layout(std430, binding = SK_CULL_STAGE_BINDING) writeonly buffer Commands { uint commands[]; }; // 5 uints each
uniform uint batchCount;
uniform bool shadowChain;
uniform uint replicas; // draws per kept instance: a point light's cube faces, layered per instance

void main() {
    const uint pair = gl_GlobalInvocationID.x; // batch * SK_CULL_LEVELS + level
    const uint pass = gl_WorkGroupID.y;
    if (pair >= SK_CULL_LEVELS * batchCount) return;
    const uint b = pair / SK_CULL_LEVELS, l = pair % SK_CULL_LEVELS;
    const Batch batch = batches[b];
    const uint sums = pass * chunkCount * SK_CULL_LEVELS;
    uint running = 0u;
    for (uint c = batch.firstChunk; c < batch.firstChunk + batch.chunkCount; ++c) {
        const uint n = chunkSums[sums + c * SK_CULL_LEVELS + l];
        chunkSums[sums + c * SK_CULL_LEVELS + l] = running;
        running += n;
    }
    const bool exists = l < (shadowChain ? batch.shadowLevels : batch.cameraLevels);
    const Level level = levels[pair];
    const uint at = 5u * ((firstPass + pass) * batchCount * SK_CULL_LEVELS + pair); // the pass's commands, then this
    commands[at + 0u] = exists ? (shadowChain ? level.shadowIndexCount : level.cameraIndexCount) : 0u;
    commands[at + 1u] = exists ? running * replicas : 0u; // instances
    commands[at + 2u] = shadowChain ? level.shadowFirstIndex : level.cameraFirstIndex;
    commands[at + 3u] = 0u; // base vertex
    // Base instance: where the level's entries start in the lists (the pass's region, then
    // GpuCulling::describe's `first` in it), which vertex stages add where they read it
    // (visible.glsl) and ignore where not: commands of several passes then draw together.
    commands[at + 4u] = (firstPass + pass) * SK_CULL_LEVELS * instanceCount + SK_CULL_LEVELS * batch.first +
                        l * batch.count;
}

#else // SK_CULL_STAGE 3

layout(std430, binding = SK_CULL_STAGE_BINDING) writeonly buffer Lists { uint lists[]; };

void main() {
    const uvec4 chunk = chunks[gl_WorkGroupID.x];
    const uint pass = gl_WorkGroupID.y;
    const uint local = gl_LocalInvocationID.x;
    if (local >= chunk.z) return;
    const uint r = ranks[pass * instanceCount + chunk.y + local];
    if (r == kNotKept) return;
    const uint level = r >> 8 & 0xFFu, rank = r & 0xFFu, fade = r >> 24;
    const Batch batch = batches[chunk.x];
    const uint entry = chunk.w + local | fade << 24;
    // The pass's region in lists: SK_CULL_LEVELS slots of batch.count per batch.
    const uint passOffset = (firstPass + pass) * SK_CULL_LEVELS * instanceCount;
    const uint region = passOffset + SK_CULL_LEVELS * batch.first;
    const uint sums = (pass * chunkCount + gl_WorkGroupID.x) * SK_CULL_LEVELS;
    lists[region + level * batch.count + chunkSums[sums + level] + rank] = entry;
    if (fade != 0u) // the coarser level's entry (visibility.h, kFadeIncoming)
        lists[region + (level + 1u) * batch.count + chunkSums[sums + level + 1u] + (r >> 16 & 0xFFu)] =
            entry | 0x80000000u;
}

#endif
