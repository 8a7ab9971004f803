// Octahedral impostors' cards (scene.h, ImpostorCard; octahedral_impostor.h, after Brucks 2018):
// a level of four vertices, the corners osCentre + osRadius · (sx, sy, sx·sy), that a shadow
// pass's vertex stage turns to face its light, showing the frame of the grid cell the light's
// direction falls in. Both maps are core/octahedral.h's, and the frame's basis and texels
// octahedral_impostor.cpp's, written again here: a frame chosen or placed differently from its
// bake would cast a tree seen from elsewhere (OctahedralImpostorDrawTest checks they agree).
layout(location = SK_IMPOSTOR_SPHERE_LOCATION) uniform vec4 skImpostorSphere; // xyz: osCentre; w: osRadius
// x: frames a side, 0 when the draw's level is no impostor; y: texels a frame's side.
layout(location = SK_IMPOSTOR_GRID_LOCATION) uniform ivec2 skImpostorGrid;

// core::hemiOctahedralFromDirection: the upper hemisphere onto [0, 1]²; below the horizon, its
// azimuth on the horizon.
vec2 skHemiOctahedral(vec3 d) {
    if (d.y < 0.0) {
        d.y = 0.0;
        if (d.x == 0.0 && d.z == 0.0) d.x = 1.0;
    }
    const float l1 = abs(d.x) + d.y + abs(d.z);
    if (!(l1 > 0.0)) return vec2(0.5);
    const float x = d.x / l1, z = d.z / l1;
    return clamp(vec2(0.5 * (x + z) + 0.5, 0.5 * (x - z) + 0.5), 0.0, 1.0);
}

// core::directionFromHemiOctahedral.
vec3 skDirectionFromHemiOctahedral(vec2 p) {
    const vec2 s = 2.0 * clamp(p, 0.0, 1.0) - 1.0;
    const float x = 0.5 * (s.x + s.y), z = 0.5 * (s.x - s.y);
    return normalize(vec3(x, max(0.0, 1.0 - abs(x) - abs(z)), z));
}

// The corner `osPosition` of the card turned to face a viewer at `wsViewer` (xyz: a direction
// towards it, w 0; or its position, w 1), placed by `worldFromObject`, in object space; its
// texture coordinates in the frame in `uv`.
vec3 skImpostorCorner(vec3 osPosition, mat4 worldFromObject, vec4 wsViewer, out vec2 uv) {
    const int n = skImpostorGrid.x, t = skImpostorGrid.y;
    const vec3 c = skImpostorSphere.xyz;
    const float r = skImpostorSphere.w;
    const vec4 osViewer = inverse(worldFromObject) * wsViewer;
    const vec3 osToViewer = osViewer.xyz - osViewer.w * c;
    const ivec2 cell = clamp(ivec2(skHemiOctahedral(osToViewer) * float(n)), ivec2(0), ivec2(n - 1));
    // The frame's direction and in-plane basis (octahedral_impostor.cpp, frameBasis).
    const vec3 d = skDirectionFromHemiOctahedral((vec2(cell) + 0.5) / float(n));
    const vec3 tangent = normalize(cross(abs(d.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0), d));
    const vec3 bitangent = cross(d, tangent);
    const vec2 corner = step(c.xy, osPosition.xy); // (sx, sy) as 0 or 1
    // The frame's inner texels, within its open ring of one (kFrameBorderTexels).
    uv = (vec2(cell * t) + 1.0 + corner * float(t - 2)) / float(n * t);
    const vec2 planar = (2.0 * corner - 1.0) * r;
    return c + planar.x * tangent + planar.y * bitangent;
}
