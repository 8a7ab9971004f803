// Spot and point lights' uniforms and maps, as the camera passes read them (local_shadows.h), and
// their names for the installed lookup, glsl/shadowkit_local_shadows.glsl, which follows this file;
// local_lights.glsl, after it, lights with them. Included after frame.glsl. The C++ side is
// LocalLightsUniforms in uniforms.h. Maps store distance / range; the biases are applied in metres
// by the lookup (a local light's texel grows with distance, so a constant in texels would be wrong
// everywhere else).
layout(std140, binding = SK_LOCAL_LIGHTS_BINDING) uniform LocalLights {
    vec4 pointPositionRange[SK_MAX_LOCAL_LIGHTS];
    vec4 pointRadianceTexel[SK_MAX_LOCAL_LIGHTS]; // rgb, w: texel size per metre of distance
    vec4 spotPositionRange[SK_MAX_LOCAL_LIGHTS];
    vec4 spotAxisCosHalf[SK_MAX_LOCAL_LIGHTS];
    vec4 spotRadianceTexel[SK_MAX_LOCAL_LIGHTS];
    mat4 spotTextureFromWorld[SK_MAX_LOCAL_LIGHTS]; // (u, v) = xy / w of the spot map
    int pointCount;
    int spotCount;
    int evalLight; // eval pass: -1 the sun, else points first, then spots
    int sunLights;
    float localSlopeBiasTexels;
    float localNormalOffsetTexels;
    float localConstantBiasMetres;
    float localMapTexels; // texels per side of every spot map and cube face
    vec4 lightRadius[SK_MAX_LOCAL_LIGHTS]; // x: point light i's radius, y: spot light i's (metres; PCSS)
};

layout(binding = SK_SPOT_MAP_UNIT) uniform sampler2DArrayShadow spotMaps;
layout(binding = SK_POINT_MAP_UNIT) uniform samplerCubeArrayShadow pointMaps;
// The same maps' stored distances / range, for PCSS's blocker search.
layout(binding = SK_SPOT_DEPTH_UNIT) uniform sampler2DArray spotDepths;
layout(binding = SK_POINT_DEPTH_UNIT) uniform samplerCubeArray pointDepths;
#define SK_SPOT_MAPS spotMaps
#define SK_SPOT_DEPTHS spotDepths
#define SK_POINT_MAPS pointMaps
#define SK_POINT_DEPTHS pointDepths
