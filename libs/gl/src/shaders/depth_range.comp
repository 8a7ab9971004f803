// Visible depth range (gl/src/depth_range.h): min and max of the camera pre-pass's view
// depths over every drawn pixel (0 is sky). Each work group reduces its 16 x 16 pixels in
// shared memory and adds one atomicMin / atomicMax to the result, so the atomics are
// 1/256 of the pixels. Positive floats order like their bit patterns as uints.
layout(local_size_x = 16, local_size_y = 16) in;

layout(binding = SK_RANGE_DEPTH_UNIT) uniform sampler2D viewDepth; // metres, 0: nothing drawn
layout(std430, binding = SK_RANGE_BINDING) buffer Range { uint nearBits, farBits; };

shared uint groupNear[256], groupFar[256];

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    const uint i = gl_LocalInvocationIndex;
    float z = 0.0;
    if (all(lessThan(pixel, textureSize(viewDepth, 0)))) z = texelFetch(viewDepth, pixel, 0).r;
    const bool drawn = z > 0.0 && !isinf(z) && !isnan(z);
    groupNear[i] = drawn ? floatBitsToUint(z) : 0xFFFFFFFFu;
    groupFar[i] = drawn ? floatBitsToUint(z) : 0u;
    barrier();
    for (uint stride = 128u; stride > 0u; stride >>= 1) {
        if (i < stride) {
            groupNear[i] = min(groupNear[i], groupNear[i + stride]);
            groupFar[i] = max(groupFar[i], groupFar[i + stride]);
        }
        barrier();
    }
    if (i == 0u && groupFar[0] != 0u) {
        atomicMin(nearBits, groupNear[0]);
        atomicMax(farBits, groupFar[0]);
    }
}
