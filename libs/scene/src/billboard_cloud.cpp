// Billboard clouds (billboard_cloud.h; Décoret et al. 2003).
#include "shadowkit/scene/billboard_cloud.h"

#include "coverage_raster.h"

#include "shadowkit/core/conventions.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace shadowkit::scene {
namespace {

constexpr int kBorderTexels = 2; // open texels round each plane, so its mips and bilinear lookups stay its own

// The planes' orientations: the three axes and the four cube diagonals. Any unit normal lies
// within 36.2° of one of them (an axis and a diagonal are 54.7° apart; the worst normals lie
// between an axis and two diagonals), so turning a card into its plane changes little.
const std::array<glm::vec3, 7>& orientations() {
    static const std::array<glm::vec3, 7> all = [] {
        const float d = 1.0f / std::sqrt(3.0f);
        return std::array<glm::vec3, 7>{glm::vec3(1, 0, 0), glm::vec3(0, 1, 0),  glm::vec3(0, 0, 1),
                                        glm::vec3(d, d, d), glm::vec3(d, d, -d), glm::vec3(d, -d, d),
                                        glm::vec3(-d, d, d)};
    }();
    return all;
}

// The rotation taking unit `from` onto unit `to` about their common perpendicular
// (Rodrigues' formula), as a matrix. `from` ≈ −`to` cannot happen here: normals are flipped to
// the orientation's side first.
glm::mat3 rotationBetween(glm::vec3 from, glm::vec3 to) {
    const glm::vec3 axis = glm::cross(from, to);
    const float s = glm::length(axis), c = glm::dot(from, to);
    if (s < 1e-7f) return glm::mat3(1.0f);
    const glm::vec3 k = axis / s;
    const glm::mat3 cross(0, k.z, -k.y, -k.z, 0, k.x, k.y, -k.x, 0); // column-major [k]×
    return glm::mat3(1.0f) + s * cross + (1.0f - c) * (cross * cross);
}

// One triangle of a source.
struct Triangle {
    const CloudSource* source;
    size_t first; // offset of its three indices in source->indices
    glm::vec3 position(int corner) const {
        return source->mesh->vertices[source->indices[first + size_t(corner)]].position;
    }
    const Vertex& vertex(int corner) const { return source->mesh->vertices[source->indices[first + size_t(corner)]]; }
};

// A set of triangles moved together onto one plane: a card (its triangles share vertices and
// a plane), or a single triangle of anything else.
struct Item {
    std::vector<Triangle> triangles;
    glm::vec3 centre{0.0f};
    glm::mat3 turn{1.0f}; // about `centre`, into the orientation
    int orientation = 0;
    float area = 0.0f;
    float flatness = 1.0f; // |Σ area · normal| / Σ area: 1 when the triangles share a plane
};

struct Plane {
    int orientation = 0;
    float offset = 0.0f; // along the orientation's normal, object metres
    std::vector<size_t> items;
    glm::vec2 lo{INFINITY}, hi{-INFINITY};   // in-plane bounds, object metres
    int x = 0, y = 0, width = 0, height = 0; // texels of the target, border included
};

// An in-plane basis for each orientation: tangent and bitangent, with the normal right-handed.
struct PlaneBasis {
    glm::vec3 tangent, bitangent;
};
const std::array<PlaneBasis, 7>& planeBases() {
    static const std::array<PlaneBasis, 7> all = [] {
        std::array<PlaneBasis, 7> bases;
        for (size_t o = 0; o < bases.size(); ++o) {
            const glm::vec3 n = orientations()[o];
            const glm::vec3 helper = std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
            const glm::vec3 tangent = glm::normalize(glm::cross(helper, n));
            bases[o] = {tangent, glm::cross(n, tangent)};
        }
        return bases;
    }();
    return all;
}

// Where an item's corner lands: turned about the item's centre, then along the plane's normal onto it.
glm::vec3 movedOnto(const Plane& plane, const Item& item, glm::vec3 position) {
    const glm::vec3 axis = orientations()[size_t(plane.orientation)];
    const glm::vec3 turned = item.centre + item.turn * (position - item.centre);
    return turned + (plane.offset - glm::dot(turned, axis)) * axis;
}
// A point of the plane in its basis, object metres.
glm::vec2 inPlane(const Plane& plane, glm::vec3 p) {
    const PlaneBasis& basis = planeBases()[size_t(plane.orientation)];
    return {glm::dot(p, basis.tangent), glm::dot(p, basis.bitangent)};
}

size_t findRoot(std::vector<uint32_t>& parent, size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
}

// The item of triangles moved together: its area-weighted centre and normal, the orientation
// that normal is closest to (either side) and the turn into it; nullopt when it covers nothing.
std::optional<Item> itemOf(std::vector<Triangle> triangles) {
    glm::vec3 normalSum(0.0f), centreSum(0.0f); // area-weighted: |normalSum| = area when flat
    float area = 0.0f;
    for (const Triangle& t : triangles) {
        const glm::vec3 a = t.position(0), b = t.position(1), c = t.position(2);
        const glm::vec3 twice = glm::cross(b - a, c - a);
        const float twiceArea = glm::length(twice);
        normalSum += 0.5f * twice, area += 0.5f * twiceArea;
        centreSum += 0.5f * twiceArea * (a + b + c) / 3.0f;
    }
    if (!(area > 0.0f)) return std::nullopt;
    Item item{std::move(triangles), centreSum / area, glm::mat3(1.0f), 0, area, glm::length(normalSum) / area};
    if (!(item.flatness > 0.0f)) return item; // normals that cancel: split by the caller, never oriented
    const glm::vec3 normal = glm::normalize(normalSum);
    float best = -1.0f;
    for (int o = 0; o < int(orientations().size()); ++o) {
        const float alignment = std::abs(glm::dot(normal, orientations()[size_t(o)]));
        if (alignment > best) best = alignment, item.orientation = o;
    }
    const glm::vec3 axis = orientations()[size_t(item.orientation)];
    item.turn = rotationBetween(glm::dot(normal, axis) >= 0.0f ? normal : -normal, axis);
    return item;
}

// The items of the sources: connected, planar triangles of an alpha-tested source (cards) as
// one, every other triangle alone.
std::vector<Item> itemsOf(std::span<const CloudSource> sources) {
    std::vector<Item> items;
    for (const CloudSource& source : sources) {
        const Mesh& mesh = *source.mesh;
        const size_t triangles = source.indices.size() / 3;
        std::vector<uint32_t> parent(mesh.vertices.size());
        std::iota(parent.begin(), parent.end(), 0u);
        if (source.texture)
            for (size_t t = 0; t < triangles; ++t)
                for (int k = 1; k < 3; ++k) {
                    const size_t a = findRoot(parent, source.indices[3 * t]);
                    const size_t b = findRoot(parent, source.indices[3 * t + size_t(k)]);
                    if (a != b) parent[b] = static_cast<uint32_t>(a);
                }
        std::vector<std::vector<Triangle>> groups;
        std::vector<int> groupOfRoot(mesh.vertices.size(), -1);
        for (size_t t = 0; t < triangles; ++t) {
            const Triangle triangle{&source, 3 * t};
            if (!source.texture) {
                groups.push_back({triangle});
                continue;
            }
            const size_t root = findRoot(parent, source.indices[3 * t]);
            if (groupOfRoot[root] < 0) {
                groupOfRoot[root] = static_cast<int>(groups.size());
                groups.emplace_back();
            }
            groups[size_t(groupOfRoot[root])].push_back(triangle);
        }
        for (std::vector<Triangle>& group : groups) {
            std::optional<Item> item = itemOf(group);
            if (!item) continue;           // degenerate: covers nothing
            if (item->flatness >= 0.98f) { // one triangle, or a card
                items.push_back(std::move(*item));
                continue;
            }
            for (const Triangle& t : group) // not flat: each triangle alone
                if (std::optional<Item> one = itemOf({t})) items.push_back(std::move(*one));
        }
    }
    return items;
}

// Packs the planes' rectangles into the region in shelves, tallest first, at `texelsPerMetre`.
bool pack(std::vector<Plane>& planes, const ImageRegion& region, float texelsPerMetre) {
    std::vector<size_t> order(planes.size());
    std::iota(order.begin(), order.end(), size_t{0});
    for (Plane& p : planes) {
        p.width = int(std::ceil((p.hi.x - p.lo.x) * texelsPerMetre)) + 2 * kBorderTexels;
        p.height = int(std::ceil((p.hi.y - p.lo.y) * texelsPerMetre)) + 2 * kBorderTexels;
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return planes[a].height > planes[b].height; });
    int x = 0, y = 0, shelf = 0;
    for (const size_t i : order) {
        Plane& p = planes[i];
        if (p.width > region.width) return false;
        if (x + p.width > region.width) x = 0, y += shelf, shelf = 0;
        if (y + p.height > region.height) return false;
        p.x = region.x + x, p.y = region.y + y;
        x += p.width, shelf = std::max(shelf, p.height);
    }
    return true;
}

// Bakes `plane` into its rectangle of `target` at `texelsPerMetre` (coverage_raster.h): each
// sample covered once, by the first of the plane's items that covers it. Writes inside the
// rectangle's interior alone and reads nothing another plane writes, so planes bake in parallel.
// Returns how many texels it keeps (alpha 255).
size_t bakePlane(const Plane& plane, std::span<const Item> items, float texelsPerMetre,
                 const coverage::KeptTexels& keptOf, Image& target) {
    coverage::SampleGrid grid(plane.width, plane.height);
    auto toTexel = [&](glm::vec2 uv) { return (uv - plane.lo) * texelsPerMetre + float(kBorderTexels); };
    for (const size_t i : plane.items)
        for (const Triangle& t : items[i].triangles) {
            std::array<glm::vec2, 3> q;
            for (int c = 0; c < 3; ++c)
                q[size_t(c)] = toTexel(inPlane(plane, movedOnto(plane, items[i], t.position(c))));
            coverage::rasterise(grid, q, *t.source, {&t.vertex(0), &t.vertex(1), &t.vertex(2)}, keptOf);
        }
    return coverage::writeDithered(grid, kBorderTexels, target, plane.x, plane.y);
}

} // namespace

BillboardCloud bakeBillboardCloud(std::span<const CloudSource> sources, Image& target, ImageRegion region,
                                  const BillboardCloudOptions& options) {
    SK_ASSERT(region.x >= 0 && region.y >= 0 && region.width > 0 && region.height > 0 &&
                  region.x + region.width <= target.width && region.y + region.height <= target.height,
              "bakeBillboardCloud(): the region lies outside the target");
    SK_ASSERT(options.slabsPerOrientation >= 1 && options.slabsPerOrientation <= 64,
              "bakeBillboardCloud(): slabsPerOrientation out of [1, 64]");
    BillboardCloud cloud;
    std::vector<Item> items = itemsOf(sources);
    if (items.empty()) return cloud;

    // Slabs: each orientation's extent over every source vertex, cut evenly.
    const auto& axes = orientations();
    std::array<float, 7> lo, hi;
    lo.fill(INFINITY), hi.fill(-INFINITY);
    for (const Item& item : items)
        for (const Triangle& t : item.triangles)
            for (int c = 0; c < 3; ++c)
                for (size_t o = 0; o < axes.size(); ++o) {
                    const float d = glm::dot(t.position(c), axes[o]);
                    lo[o] = std::min(lo[o], d), hi[o] = std::max(hi[o], d);
                }
    const int slabs = options.slabsPerOrientation;
    std::vector<int> planeOf(axes.size() * size_t(slabs), -1);
    std::vector<Plane> planes;
    std::vector<int> itemPlane(items.size());
    for (size_t i = 0; i < items.size(); ++i) {
        const Item& item = items[i];
        const auto o = size_t(item.orientation);
        const float thickness = std::max(hi[o] - lo[o], 1e-6f) / float(slabs);
        const int slab = std::clamp(int((glm::dot(item.centre, axes[o]) - lo[o]) / thickness), 0, slabs - 1);
        int& p = planeOf[o * size_t(slabs) + size_t(slab)];
        if (p < 0) {
            p = static_cast<int>(planes.size());
            planes.push_back({item.orientation, lo[o] + (float(slab) + 0.5f) * thickness, {}});
        }
        planes[size_t(p)].items.push_back(i);
        itemPlane[i] = p;
    }

    double movedArea = 0.0, totalArea = 0.0, planeArea = 0.0;
    for (size_t i = 0; i < items.size(); ++i) {
        Plane& plane = planes[size_t(itemPlane[i])];
        double shift = 0.0;
        for (const Triangle& t : items[i].triangles)
            for (int c = 0; c < 3; ++c) {
                const glm::vec3 p = movedOnto(plane, items[i], t.position(c));
                const glm::vec2 uv = inPlane(plane, p);
                plane.lo = glm::min(plane.lo, uv), plane.hi = glm::max(plane.hi, uv);
                shift += glm::length(p - t.position(c));
            }
        movedArea += items[i].area * shift / double(3 * items[i].triangles.size());
        totalArea += items[i].area;
    }
    for (const Plane& p : planes) planeArea += double(p.hi.x - p.lo.x) * double(p.hi.y - p.lo.y);

    // The largest density that packs: from the area bound down in 5 % steps.
    float texelsPerMetre =
        float(std::sqrt(0.85 * double(region.width) * double(region.height) / std::max(planeArea, 1e-12)));
    while (!pack(planes, region, texelsPerMetre)) texelsPerMetre *= 0.95f;
    cloud.texelsPerMetre = texelsPerMetre;
    cloud.planes = static_cast<int>(planes.size());
    cloud.objectError = float(movedArea / totalArea + 0.5 / double(texelsPerMetre));

    // Clear the region: open texels a leaf's green (bilinear lookups at a plane's edge mix towards green), alpha 0.
    for (int y = region.y; y < region.y + region.height; ++y)
        for (int x = region.x; x < region.x + region.width; ++x) {
            uint8_t* p = target.pixel(x, y);
            p[0] = 50, p[1] = 100, p[2] = 30, p[3] = 0;
        }

    // Bake. A plane's texels are its own (packed apart, border included), and everything a plane
    // reads is shared and read-only, so the planes bake in parallel, each to the same bytes as alone.
    const coverage::KeptTexels keptOf = coverage::keptTexelsOf(sources, options.alphaCutoff);
    std::vector<size_t> opaqueOf(planes.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, planes.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
        for (size_t p = range.begin(); p != range.end(); ++p)
            opaqueOf[p] = bakePlane(planes[p], items, texelsPerMetre, keptOf, target);
    });

    size_t opaque = 0, interior = 0;
    for (size_t p = 0; p < planes.size(); ++p) {
        const Plane& plane = planes[p];
        const int w = plane.width, h = plane.height;
        opaque += opaqueOf[p];
        interior += size_t(std::max(0, w - 2 * kBorderTexels)) * size_t(std::max(0, h - 2 * kBorderTexels));
        // The plane's quad spans its interior texels exactly.
        const glm::vec3 n = axes[size_t(plane.orientation)];
        const PlaneBasis& basis = planeBases()[size_t(plane.orientation)];
        const glm::vec2 span = glm::vec2(float(w - 2 * kBorderTexels), float(h - 2 * kBorderTexels)) / texelsPerMetre;
        const auto first = static_cast<uint32_t>(cloud.vertices.size());
        for (int corner = 0; corner < 4; ++corner) {
            const glm::vec2 f(float(corner & 1), float(corner >> 1));
            const glm::vec2 planar = plane.lo + f * span;
            const glm::vec2 texel = glm::vec2(plane.x + kBorderTexels, plane.y + kBorderTexels) +
                                    f * glm::vec2(float(w - 2 * kBorderTexels), float(h - 2 * kBorderTexels));
            cloud.vertices.push_back({plane.offset * n + planar.x * basis.tangent + planar.y * basis.bitangent, n,
                                      glm::vec3(1.0f), texel / glm::vec2(float(target.width), float(target.height))});
        }
        cloud.indices.insert(cloud.indices.end(), {first, first + 1, first + 3, first, first + 3, first + 2});
    }
    cloud.coverage = interior > 0 ? double(opaque) / double(interior) : 0.0;
    return cloud;
}

} // namespace shadowkit::scene
