// Receiver masks for shadow caster culling (gl/src/receiver_masks.h): every pixel of the
// camera's depth pre-pass is a visible receiver point; it marks, in each shadow map's mask,
// the farthest depth (in the map's stored metric) of the receivers under each mask texel.
// Depths go through an order-preserving float -> uint encoding so atomicMax takes the
// farthest; 0 is "nothing", 0xFFFFFFFF "behind the projection centre: keep every caster".
layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = SK_RECEIVER_DEPTH_UNIT) uniform sampler2D viewDepth; // metres, 0: sky
layout(std430, binding = SK_MASK_BINDING) buffer Masks { uint maskTexels[]; };

layout(std140, binding = SK_RECEIVER_MASK_BINDING) uniform ReceiverMask {
    mat4 worldFromClip;  // camera
    vec4 wsEye;          // xyz
    vec4 wsViewForward;  // xyz, unit
    mat4 mapClipFromWorld[SK_MAX_CASCADES];
    vec4 mapLinearDepthFromWorld[SK_MAX_CASCADES];
    int mapCount;
    int linearLayout;
    int maskSize;
    int pad0;
};

uint encodeDepth(float d) {
    const uint bits = floatBitsToUint(d);
    return (bits & 0x80000000u) != 0u ? ~bits : bits | 0x80000000u;
}

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    const ivec2 size = textureSize(viewDepth, 0);
    if (any(greaterThanEqual(pixel, size))) return;
    const float z = texelFetch(viewDepth, pixel, 0).r;
    if (z <= 0.0) return;
    // The pixel centre's ray, scaled to its view depth: exact to float precision, unlike
    // unprojecting a hyperbolic depth-buffer value.
    const vec2 ndc = (vec2(pixel) + 0.5) / vec2(size) * 2.0 - 1.0;
    const vec4 farPoint = worldFromClip * vec4(ndc, 1.0, 1.0);
    const vec3 ray = farPoint.xyz / farPoint.w - wsEye.xyz;
    const vec3 ws = wsEye.xyz + ray * (z / dot(ray, wsViewForward.xyz));
    for (int m = 0; m < mapCount; ++m) {
        const uint base = uint(m * maskSize * maskSize);
        const vec4 clip = mapClipFromWorld[m] * vec4(ws, 1.0);
        if (!(clip.w > 1e-12)) {
            atomicMax(maskTexels[base], 0xFFFFFFFFu);
            continue;
        }
        const ivec2 t = clamp(ivec2(floor((clip.xy / clip.w * 0.5 + 0.5) * float(maskSize))), ivec2(0), ivec2(maskSize - 1));
        const float d = linearLayout != 0 ? dot(mapLinearDepthFromWorld[m], vec4(ws, 1.0)) : clip.z / clip.w;
        atomicMax(maskTexels[base + uint(t.y * maskSize + t.x)], encodeDepth(d));
    }
}
