// Moment shadow maps (Peters & Klein 2015; moment_maps.h): the sun's depth maps turned into the
// first four moments of depth, (z, z², z³, z⁴), then blurred, so that one filtered lookup returns
// the moments of the depths over a footprint (the lookup's bound is glsl/shadowkit_shadows.glsl's
// skMomentLit). One dispatch per pass, all layers at once (z = layer).
layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = SK_MOMENTS_SOURCE_UNIT) uniform sampler2DArray source; // depth (mode 0) or moments
layout(rgba32f, binding = SK_MOMENTS_IMAGE_UNIT) uniform writeonly image2DArray target;
layout(location = 0) uniform int mode;    // 0: depth to moments; 1: a blur of the moments along `step`
layout(location = 1) uniform ivec2 step;  // (1, 0) or (0, 1)
layout(location = 2) uniform int radius;  // texels each side; a Gaussian of σ = radius / 2

void main() {
    const ivec3 size = textureSize(source, 0);
    const ivec3 p = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(p, size))) return;
    vec4 result;
    if (mode == 0) {
        const float z = texelFetch(source, p, 0).r;
        const float z2 = z * z;
        result = vec4(z, z2, z2 * z, z2 * z2);
    } else {
        // Separable: each pass weighs exp(−k² / (2σ²)) = exp(−2 k² / radius²); the edge clamps.
        vec4 sum = vec4(0.0);
        float weights = 0.0;
        for (int k = -radius; k <= radius; ++k) {
            const float w = exp(-2.0 * float(k * k) / float(radius * radius));
            const ivec2 q = clamp(p.xy + k * step, ivec2(0), size.xy - 1);
            sum += w * texelFetch(source, ivec3(q, p.z), 0);
            weights += w;
        }
        result = sum / weights;
    }
    imageStore(target, p, result);
}
