// Octahedral impostors (octahedral_impostor.h; Brucks 2018).
#include "shadowkit/scene/octahedral_impostor.h"

#include "coverage_raster.h"

#include "shadowkit/core/conventions.h"
#include "shadowkit/core/octahedral.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace shadowkit::scene {
namespace {

// An open texel round each frame: its bilinear lookups and first mips stay its own.
constexpr int kFrameBorderTexels = 1;

// A frame's in-plane basis: tangent and bitangent, with its direction right-handed (as the
// clouds' planes: an up helper, the x axis near the zenith).
struct FrameBasis {
    glm::vec3 direction, tangent, bitangent;
};
FrameBasis frameBasis(int framesPerSide, int frame) {
    const glm::vec3 d = impostorFrameDirection(framesPerSide, frame);
    const glm::vec3 helper = std::abs(d.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 tangent = glm::normalize(glm::cross(helper, d));
    return {d, tangent, glm::cross(d, tangent)};
}

// The largest angle between a direction and the middle of its cell: over 17 × 17 points of
// each cell, its edges and corners included (the corners are the farthest: for 6 frames a side
// this gives 22.21°, as a lattice of 1,801² points of the whole square does).
float largestTurn(int framesPerSide) {
    constexpr int kSteps = 16;
    float largest = 0.0f;
    for (int frame = 0; frame < framesPerSide * framesPerSide; ++frame) {
        const glm::vec3 middle = impostorFrameDirection(framesPerSide, frame);
        const glm::vec2 cell(float(frame % framesPerSide), float(frame / framesPerSide));
        for (int a = 0; a <= kSteps; ++a)
            for (int b = 0; b <= kSteps; ++b) {
                const glm::vec2 uv = (cell + glm::vec2(float(a), float(b)) / float(kSteps)) / float(framesPerSide);
                const float c = glm::dot(core::directionFromHemiOctahedral(uv), middle);
                largest = std::max(largest, std::acos(std::clamp(c, -1.0f, 1.0f)));
            }
    }
    return largest;
}

} // namespace

int impostorFrame(int framesPerSide, glm::vec3 osToViewer) {
    const glm::vec2 uv = core::hemiOctahedralFromDirection(osToViewer) * float(framesPerSide);
    const int i = std::clamp(int(uv.x), 0, framesPerSide - 1), j = std::clamp(int(uv.y), 0, framesPerSide - 1);
    return j * framesPerSide + i;
}

glm::vec3 impostorFrameDirection(int framesPerSide, int frame) {
    const glm::vec2 cell(float(frame % framesPerSide), float(frame / framesPerSide));
    return core::directionFromHemiOctahedral((cell + 0.5f) / float(framesPerSide));
}

OctahedralImpostor bakeOctahedralImpostor(std::span<const CloudSource> sources, Image& target, ImageRegion region,
                                          const OctahedralImpostorOptions& options) {
    const int n = options.framesPerSide, t = options.texelsPerFrame;
    SK_ASSERT(n >= 1 && n <= 64 && t >= 8 && t <= 2048, "bakeOctahedralImpostor(): options out of range");
    SK_ASSERT(region.x >= 0 && region.y >= 0 && region.width == n * t && region.height == n * t &&
                  region.x + region.width <= target.width && region.y + region.height <= target.height,
              "bakeOctahedralImpostor(): the region is not framesPerSide · texelsPerFrame square inside the target");
    OctahedralImpostor impostor;
    impostor.framesPerSide = n, impostor.texelsPerFrame = t;

    // The sphere: the vertices' bounding box's middle, and the farthest vertex from it.
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const CloudSource& source : sources)
        for (const uint32_t v : source.indices) {
            lo = glm::min(lo, source.mesh->vertices[v].position), hi = glm::max(hi, source.mesh->vertices[v].position);
        }
    for (int y = region.y; y < region.y + region.height; ++y)
        for (int x = region.x; x < region.x + region.width; ++x) {
            uint8_t* p = target.pixel(x, y);
            p[0] = 50, p[1] = 100, p[2] = 30, p[3] = 0; // open texels a leaf's green, as the clouds'
        }
    if (!(lo.x <= hi.x)) return impostor;
    const glm::vec3 c = 0.5f * (lo + hi);
    float r = 0.0f;
    for (const CloudSource& source : sources)
        for (const uint32_t v : source.indices) r = std::max(r, glm::length(source.mesh->vertices[v].position - c));
    r = std::max(r, 1e-6f);
    impostor.osCentre = c, impostor.osRadius = r;

    const int inner = t - 2 * kFrameBorderTexels;
    const float texelsPerMetre = float(inner) / (2.0f * r);
    impostor.maxTurn = largestTurn(n);
    impostor.objectError = r * std::sin(impostor.maxTurn) + 0.5f / texelsPerMetre;

    // Each frame: the triangles nearest its viewer first (the first to cover a sample gives it
    // its colour), drawn into the frame's own texels.
    struct SourceTriangle {
        const CloudSource* source;
        size_t first;
    };
    std::vector<SourceTriangle> triangles;
    for (const CloudSource& source : sources)
        for (size_t k = 0; k + 2 < source.indices.size(); k += 3) triangles.push_back({&source, k});
    const coverage::KeptTexels keptOf = coverage::keptTexelsOf(sources, options.alphaCutoff);
    std::vector<size_t> keptOfFrame(size_t(n * n));
    tbb::parallel_for(tbb::blocked_range<int>(0, n * n, 1), [&](const tbb::blocked_range<int>& frames) {
        for (int frame = frames.begin(); frame != frames.end(); ++frame) {
            const FrameBasis basis = frameBasis(n, frame);
            auto corner = [&](const SourceTriangle& s, int k) -> const Vertex& {
                return s.source->mesh->vertices[s.source->indices[s.first + size_t(k)]];
            };
            auto depth = [&](const SourceTriangle& s) {
                return glm::dot(corner(s, 0).position + corner(s, 1).position + corner(s, 2).position, basis.direction);
            };
            std::vector<size_t> order(triangles.size());
            std::iota(order.begin(), order.end(), size_t{0});
            std::vector<float> depths(triangles.size());
            for (size_t k = 0; k < triangles.size(); ++k) depths[k] = depth(triangles[k]);
            std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return depths[a] > depths[b]; });
            coverage::SampleGrid grid(t, t);
            for (const size_t k : order) {
                const SourceTriangle& s = triangles[k];
                std::array<glm::vec2, 3> q;
                for (int v = 0; v < 3; ++v) {
                    const glm::vec3 p = corner(s, v).position - c;
                    q[size_t(v)] =
                        (glm::vec2(glm::dot(p, basis.tangent), glm::dot(p, basis.bitangent)) + r) * texelsPerMetre +
                        float(kFrameBorderTexels);
                }
                coverage::rasterise(grid, q, *s.source, {&corner(s, 0), &corner(s, 1), &corner(s, 2)}, keptOf);
            }
            keptOfFrame[size_t(frame)] = coverage::writeDithered(
                grid, kFrameBorderTexels, target, region.x + (frame % n) * t, region.y + (frame / n) * t);
        }
    });

    for (int frame = 0; frame < n * n; ++frame) {
        const FrameBasis basis = frameBasis(n, frame);
        const glm::vec2 origin(float(region.x + (frame % n) * t + kFrameBorderTexels),
                               float(region.y + (frame / n) * t + kFrameBorderTexels));
        const auto first = static_cast<uint32_t>(impostor.vertices.size());
        for (int k = 0; k < 4; ++k) {
            const glm::vec2 f(float(k & 1), float(k >> 1));
            const glm::vec2 planar = (2.0f * f - 1.0f) * r;
            const glm::vec2 texel = origin + f * float(inner);
            impostor.vertices.push_back({c + planar.x * basis.tangent + planar.y * basis.bitangent, basis.direction,
                                         glm::vec3(1.0f),
                                         texel / glm::vec2(float(target.width), float(target.height))});
        }
        impostor.indices.insert(impostor.indices.end(), {first, first + 1, first + 3, first, first + 3, first + 2});
    }
    const size_t kept = std::accumulate(keptOfFrame.begin(), keptOfFrame.end(), size_t{0});
    impostor.coverage = double(kept) / (double(n * n) * double(inner) * double(inner));
    return impostor;
}

} // namespace shadowkit::scene
