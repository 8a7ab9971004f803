// The limits benchmark's geometry, from gl_VertexID alone (no buffers): depth_limits.cpp.
// Depths lie in (0, 1), inside the clip volume under either glClipControl depth mode.
//   mode 0, fill: quad k (six vertices) covers the map at depth 1 − (k + 1) / (layers + 1), so
//          drawn in order each is nearer than the last and writes every texel.
//   mode 1, grid: cell c of a cells × cells grid over the map, two triangles, all at depth 0.5.
//   mode 2, large: triangle t covers half the map (below its diagonal), at depth
//          1 − (t + 1) / (count + 1): each nearer than the last.
uniform int mode;
uniform int count; // layers (fill), cells per side (grid), triangles (large)

const vec2 kQuad[6] = vec2[](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));

void main() {
    const int corner = gl_VertexID % 6;
    if (mode == 0) {
        const int layer = gl_VertexID / 6;
        gl_Position = vec4(kQuad[corner] * 2.0 - 1.0, 1.0 - float(layer + 1) / float(count + 1), 1.0);
    } else if (mode == 1) {
        const int cell = gl_VertexID / 6;
        const vec2 at = vec2(cell % count, cell / count) + kQuad[corner];
        gl_Position = vec4(at / float(count) * 2.0 - 1.0, 0.5, 1.0);
    } else {
        const int triangle = gl_VertexID / 3;
        gl_Position = vec4(kQuad[gl_VertexID % 3] * 2.0 - 1.0, 1.0 - float(triangle + 1) / float(count + 1), 1.0);
    }
}
