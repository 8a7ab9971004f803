// One mip level of the prefiltered opacity layers over part of a layer (opacity_layers.h): each
// texel the mean of the four beneath it in the level below, read from a view of that level alone
// (so the level written is never one the shader reads). A virtual page's slot takes its levels
// this way, so a frame that draws a few pages filters those, not the whole atlas's 16 M texels as
// glGenerateTextureMipmap would (along `flythrough` on llvmpipe, about eleven pages a frame: the
// frame's CPU side 567–574 → 473–492 ms; docs/materials.md). A texel past an odd level's last
// row or column is left out, as a box filter of a level half the size (rounded down) leaves it.
layout(binding = SK_OPACITY_PREFILTERED_UNIT) uniform sampler2DArray finer;
layout(location = SK_OPACITY_LAYER_LOCATION) uniform int mapLayer;
layout(location = 0) out vec2 mean;

void main() {
    const ivec2 corner = 2 * ivec2(gl_FragCoord.xy);
    const ivec2 last = textureSize(finer, 0).xy - 1;
    vec2 sum = vec2(0.0);
    for (int i = 0; i < 4; ++i)
        sum += texelFetch(finer, ivec3(min(corner + ivec2(i & 1, i >> 1), last), mapLayer), 0).rg;
    mean = 0.25 * sum;
}
