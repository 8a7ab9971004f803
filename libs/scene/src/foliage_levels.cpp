#include "shadowkit/scene/foliage_levels.h"

#include "shadowkit/core/conventions.h"
#include "shadowkit/scene/mesh_builder.h"
#include "shadowkit/scene/octahedral_impostor.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace shadowkit::scene {

std::vector<BakedCloud> bakeCloudChain(std::span<const CloudSource> sources, float alphaCutoff, int finestSlabs) {
    SK_ASSERT(finestSlabs >= 4 && finestSlabs <= 64, "bakeCloudChain(): finestSlabs out of [4, 64]");
    // Finer to coarser down to kCoarsestSlabs: each halves the planes (the slabs' spacing
    // doubles, so the error grows 1.3–1.9×: the turn's share does not) and gets a quarter of the
    // texels. The levels are baked apart (in parallel, as their planes are), then kept in order.
    std::vector<int> slabs;
    for (int n = finestSlabs; n >= kCoarsestSlabs; n /= 2) slabs.push_back(n);
    std::vector<BakedCloud> levels(slabs.size());
    tbb::parallel_for(size_t{0}, levels.size(), [&](size_t i) {
        BakedCloud& level = levels[i];
        const int width = 64 * slabs[i], height = 32 * slabs[i];
        level.texture.image = Image(width, height);
        level.texture.wrapS = level.texture.wrapT = TextureWrap::ClampToEdge;
        level.cloud = bakeBillboardCloud(sources, level.texture.image, {0, 0, width, height},
                                         {.slabsPerOrientation = slabs[i], .alphaCutoff = alphaCutoff});
    });
    std::vector<BakedCloud> chain;
    for (BakedCloud& level : levels) {
        if (level.cloud.planes == 0) break; // nothing to cover
        if (!chain.empty() && !(level.cloud.objectError > chain.back().cloud.objectError)) continue;
        chain.push_back(std::move(level));
    }
    return chain;
}

void appendCloudLevels(Mesh& mesh, std::span<const BakedCloud> clouds, int32_t firstTextureIndex) {
    for (size_t i = 0; i < clouds.size(); ++i) {
        const BillboardCloud& cloud = clouds[i].cloud;
        AuthoredLod level{{}, cloud.objectError, true, firstTextureIndex + int32_t(i)};
        const auto base = static_cast<uint32_t>(mesh.vertices.size());
        mesh.vertices.insert(mesh.vertices.end(), cloud.vertices.begin(), cloud.vertices.end());
        for (const uint32_t index : cloud.indices) level.indices.push_back(base + index);
        orderQuadsHighestFirst(mesh.vertices, level.indices);
        mesh.authoredLods.push_back(std::move(level));
    }
    mesh.computeBounds();
}

std::optional<Texture> appendImpostorLevel(Mesh& mesh, std::span<const CloudSource> sources, float alphaCutoff,
                                           int32_t textureIndex) {
    SK_ASSERT(!mesh.authoredLods.empty(), "appendImpostorLevel(): the mesh has no cloud to stand in for");
    const OctahedralImpostorOptions options{.alphaCutoff = alphaCutoff};
    const int side = options.framesPerSide * options.texelsPerFrame;
    Texture texture;
    texture.image = Image(side, side);
    texture.wrapS = texture.wrapT = TextureWrap::ClampToEdge;
    const OctahedralImpostor impostor = bakeOctahedralImpostor(sources, texture.image, {0, 0, side, side}, options);
    if (!(impostor.coverage > 0.0)) return std::nullopt;

    mesh.authoredLods.back().passes = LodPasses::Camera;
    float before = 0.0f; // the error of the shadow chain's level before the impostor's
    for (const AuthoredLod& level : mesh.authoredLods)
        if (level.passes != LodPasses::Camera) before = level.objectError;
    AuthoredLod level{{},
                      std::max(impostor.objectError, before),
                      true,
                      textureIndex,
                      LodPasses::Shadows,
                      {impostor.osCentre, impostor.osRadius, impostor.framesPerSide, impostor.texelsPerFrame}};
    // The corners osCentre + osRadius · (sx, sy, sx·sy): the vertex stages read (sx, sy), and the
    // third keeps the sphere's box in the mesh's bounds, which a turned card reaches.
    const auto base = static_cast<uint32_t>(mesh.vertices.size());
    for (int k = 0; k < 4; ++k) {
        const float sx = float(2 * (k & 1) - 1), sy = float(2 * (k >> 1) - 1);
        mesh.vertices.push_back({impostor.osCentre + impostor.osRadius * glm::vec3(sx, sy, sx * sy),
                                 glm::vec3(0.0f, 0.0f, 1.0f), glm::vec3(1.0f),
                                 glm::vec2(0.5f * (sx + 1.0f), 0.5f * (sy + 1.0f))});
    }
    level.indices = {base, base + 1, base + 3, base, base + 3, base + 2};
    mesh.authoredLods.push_back(std::move(level));
    mesh.computeBounds();
    return texture;
}

int addFoliageClouds(Scene& scene, const FoliageCloudOptions& options) {
    int given = 0;
    for (uint32_t m = 0; m < scene.meshes.size(); ++m) {
        Mesh& mesh = scene.meshes[m];
        const Material* material = scene.materialOf(mesh);
        // A deformed mesh's clouds would stand in its first pose while its cards move.
        if (!material || !material->alphaTested() || !mesh.authoredLods.empty() || scene.deforms(m)) continue;
        if (mesh.triangleCount() < options.minTriangles || mesh.triangleCount() > options.maxTriangles) continue;
        // Clear glass covers nothing, and has nothing to bake: no pass draws it (material.h).
        if (coversNothing(*material, scene.textures)) continue;
        const Texture* texture =
            material->baseColorTexture >= 0 && size_t(material->baseColorTexture) < scene.textures.size()
                ? &scene.textures[size_t(material->baseColorTexture)]
                : nullptr;
        const CloudSource source{&mesh,
                                 mesh.indices,
                                 texture ? &texture->image : nullptr,
                                 texture ? texture->wrapS : TextureWrap::ClampToEdge,
                                 texture ? texture->wrapT : TextureWrap::ClampToEdge,
                                 material->baseColorFactor.a};
        std::vector<BakedCloud> chain =
            bakeCloudChain(std::span(&source, 1), material->alphaCutoff, kLoadedFinestSlabs);
        if (chain.empty()) continue;
        appendCloudLevels(mesh, chain, int32_t(scene.textures.size()));
        for (BakedCloud& cloud : chain) scene.textures.push_back(std::move(cloud.texture));
        ++given;
    }
    return given;
}

} // namespace shadowkit::scene
