// Receiver masks for GPU-driven culling (gl/src/receiver_masks.h, markOnGpu): the marked
// masks dilated by the lookup's reach, as ReceiverMask::finish does on the CPU, one axis per
// dispatch (a separable max filter). The encoding of receiver_mask.comp keeps the order of
// depths, so the max of encoded texels is the encoding of the max (0, "nothing", is the
// least). The first pass also records, after the texels, one flag per map: 1 where a
// receiver lay behind the map's projection centre (0xFFFFFFFF), which keeps every caster.
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = SK_MASK_BINDING) readonly buffer Source { uint source[]; };
layout(std430, binding = SK_DILATED_MASK_BINDING) writeonly buffer Target { uint target[]; };
uniform int maskSize, mapCount, dilation;
uniform ivec2 axis;        // (1, 0): rows; (0, 1): columns
uniform bool firstPass;    // flags from the marks themselves; otherwise copied along

void main() {
    const ivec3 id = ivec3(gl_GlobalInvocationID);
    if (id.x >= maskSize || id.y >= maskSize || id.z >= mapCount) return;
    const int base = id.z * maskSize * maskSize, flags = mapCount * maskSize * maskSize;
    uint farthest = 0u;
    for (int k = -dilation; k <= dilation; ++k) {
        const ivec2 p = id.xy + axis * k;
        if (all(greaterThanEqual(p, ivec2(0))) && all(lessThan(p, ivec2(maskSize))))
            farthest = max(farthest, source[base + p.y * maskSize + p.x]);
    }
    target[base + id.y * maskSize + id.x] = farthest;
    if (id.x == 0 && id.y == 0) {
        bool everything = false;
        if (firstPass)
            for (int t = 0; t < maskSize * maskSize && !everything; ++t) everything = source[base + t] == 0xFFFFFFFFu;
        else
            everything = source[flags + id.z] != 0u;
        target[flags + id.z] = everything ? 1u : 0u;
    }
}
