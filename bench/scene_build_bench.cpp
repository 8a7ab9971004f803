// What the leafy forest costs to build before its first frame: each species' billboard clouds,
// baked on the CPU when the forest is made (billboard_cloud.h), and the coverage-keeping mip
// chain of every alpha-tested texture — the leaf atlas and each cloud's own —, built when a
// renderer uploads them (texture_mips.h). Each iteration takes the next species or texture in
// turn, so no two consecutive iterations share their input; nothing is cached between them.
#include "shadowkit/scene/foliage_levels.h"
#include "shadowkit/scene/leafy_trees.h"
#include "shadowkit/scene/texture_mips.h"

#include <benchmark/benchmark.h>

#include <vector>

namespace {

using namespace shadowkit;

// Every alpha-tested texture of the leafy forest: the atlas, then the clouds' of each species
// (13 in all).
const std::vector<scene::Image>& leafyTextures() {
    static const std::vector<scene::Image> all = [] {
        const scene::Texture atlas = scene::makeLeafAtlas();
        std::vector<scene::Image> images{atlas.image};
        for (int k = 0; k < scene::kTreeSpeciesCount; ++k) {
            scene::LeafyTree tree = scene::makeLeafyTree(static_cast<scene::TreeSpecies>(k), 1);
            for (const scene::BakedCloud& cloud : scene::addFarLevels(tree, atlas.image, 1))
                images.push_back(cloud.texture.image);
        }
        return images;
    }();
    return all;
}

// One texture's chain at glTF's default cutoff, the textures in turn.
void mipChains(benchmark::State& state) {
    const std::vector<scene::Image>& textures = leafyTextures();
    size_t next = 0;
    int64_t texels = 0;
    for (auto _ : state) {
        const scene::Image& image = textures[next++ % textures.size()];
        benchmark::DoNotOptimize(scene::buildMipChain(image, 0.5f));
        texels += int64_t(image.width) * image.height;
    }
    state.counters["texels/s"] = benchmark::Counter(double(texels), benchmark::Counter::kIsRate);
}
// Whole rounds of the 13 textures (the atlas, 4 clouds × 3 species), so every repetition times the same set.
BENCHMARK(mipChains)->Name("mips/leafy-textures")->Iterations(26)->Unit(benchmark::kMillisecond);

// All 13 chains as a renderer builds them on upload (forEachMipChain: every core, in batches),
// wall-clock time for the whole set; against 13 × mips/leafy-textures, what the cores save.
void mipChainsTogether(benchmark::State& state) {
    const std::vector<scene::Image>& textures = leafyTextures();
    std::vector<scene::MipChainRequest> requests;
    for (const scene::Image& image : textures) requests.push_back({&image, 0.5f, true});
    for (auto _ : state) {
        size_t levels = 0;
        scene::forEachMipChain(requests,
                               [&](size_t, const std::vector<scene::Image>& below) { levels += below.size(); });
        benchmark::DoNotOptimize(levels);
    }
}
BENCHMARK(mipChainsTogether)
    ->Name("mips/leafy-textures-together")
    ->Iterations(4)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// One species' four clouds from its full tree, the species in turn (the tree made outside the timing).
void farLevels(benchmark::State& state) {
    const scene::Texture atlas = scene::makeLeafAtlas();
    std::vector<scene::LeafyTree> trees;
    for (int k = 0; k < scene::kTreeSpeciesCount; ++k)
        trees.push_back(scene::makeLeafyTree(static_cast<scene::TreeSpecies>(k), 1));
    size_t next = 0;
    for (auto _ : state) {
        state.PauseTiming();
        scene::LeafyTree tree = trees[next++ % trees.size()];
        state.ResumeTiming();
        benchmark::DoNotOptimize(scene::addFarLevels(tree, atlas.image, 1));
    }
}
// Wall-clock time: the planes bake on every core (the CPU column sums the threads).
BENCHMARK(farLevels)->Name("clouds/species")->Iterations(6)->UseRealTime()->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();
