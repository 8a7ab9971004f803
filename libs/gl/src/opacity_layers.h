// Opacity layers for the sun's fixed maps and virtual pages (--foliage-opacity): partial occlusion
// by alpha-tested casters, after deep opacity maps (Yuksel & Keyser 2008, "Deep Opacity Maps",
// Computer Graphics Forum 27(2)). Per texel of each map, the linear depth of the first leaf
// (R32F) and what the leaves let through in four layers measured back from it (RGBA16F);
// glsl/shadowkit_foliage_opacity.glsl's skFoliageTransmittance reads them and multiplies the depth
// map's term, which then holds the opaque casters only (PassPrograms::Batches). Beside them the
// layers prefiltered (RG16F with its mip chain: per texel A = −ln T and A × the leaves' depth),
// from which the lookup reads the mean depth of the leaves around a receiver in one fetch. About
// 17 bytes a texel beside the depth map's 4, and 4 in one layer for the first draw's depth test.
//
// Two passes over the alpha-tested batches of each map's list: the first leaf, depth-tested so
// that a leaf behind one already drawn is rejected before it is shaded (the lists come nearest
// the sun first) and GL_MIN-blended; then, with no depth test, each leaf fragment's transmittance
// by multiplicative blending into the layer of its distance behind the first (opacity.frag) —
// every leaf counts there; then one triangle over each map (opacity_prefilter.frag) and the mip
// chain. Each of the two draws goes over every view before the other starts, so that one
// occlusion query counts it whole (bench's `leaves` line). For the set-up's fixed maps (single
// maps and cascades) the textures are layers of the maps' size, one a map, and the driver builds
// the chain; for virtual maps they are laid out as the page atlas, one layer, each page drawn is
// drawn into its slot, guard band and all — a page's layers are drawn when its depth is, so a
// cached page keeps both — and the chain is filtered over the drawn slots alone
// (opacity_downsample.frag), up to the guard band's width.
#pragma once

#include "gl_object.h"
#include "gpu_scene.h"
#include "pass_lists.h"
#include "pass_samples.h"

#include "shadowkit/core/bias.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/shadow_setup.h"

#include <glm/glm.hpp>

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace shadowkit::gl {

// One map's layers to draw: where they go in the textures, and the map's light space.
struct OpacityView {
    int layer = 0;                        // of the textures
    glm::ivec3 viewport{0};               // x, y, side, in texels of the layer
    core::Mat4 clipFromWorld{1.0};        // the map's light clip space
    core::Vec4 linearDepthFromWorld{0.0}; // row: [0, 1] over the map's depth range
    bool clustersInView = false;          // a large mesh draws only its clusters inside the view (pages)
};
// The fixed maps of `setup` (size² texels each), one a layer.
std::vector<OpacityView> opacityViewsOf(const core::ShadowSetup& setup, int size);

class OpacityLayers {
public:
    static core::Result<std::unique_ptr<OpacityLayers>> create();

    // Whether the textures are `layers` layers of width × height with `mipLevels` prefiltered levels.
    bool holds(int width, int height, int layers, int mipLevels) const;
    // The textures for `layers` layers of width × height texels, allocated or kept; the prefiltered
    // layers with `mipLevels` levels (at most a full chain). Out of memory: an error naming `field`.
    core::Status prepare(int width, int height, int layers, int mipLevels, const std::string& field);
    // Draws the layers of every view of the sun towards `wsTowardsSun` from the alpha-tested
    // batches of its casters, writing each view's DepthPass block into `depthPass` (bound at
    // kDepthPassBinding); casters before a map's near plane clamped to it with `depthClamp`, as
    // the depth pass does.
    DrawStats draw(const GpuScene& scene, const core::BiasSettings& bias, const core::Vec3& wsTowardsSun,
                   std::span<const OpacityView> views, const CasterLists& casters, const Buffer& depthPass,
                   bool depthClamp);
    // The last draw()'s work, each counted over all its views: the first leaf's samples, which its
    // depth test passed (about one a texel the leaves cover when they come nearest the sun first),
    // and the transmittance's, every leaf fragment (no depth test). A frame that draws no layers
    // calls resetCounts(), so that it counts none.
    const PassSamples& firstLeafSamples() const { return m_firstSamples; }
    const PassSamples& leafSamples() const { return m_leafSamples; }
    void resetCounts() { m_firstSamples.reset(), m_leafSamples.reset(); }
    // The textures' size in bytes, mips included.
    int64_t bytes() const;
    // The layers on kOpacityUnit, the first leaves' depths on kOpacityFirstUnit and the layers
    // prefiltered on kOpacityPrefilteredUnit.
    void bind() const;

private:
    OpacityLayers() = default;
    // Each view's texels of m_prefiltered's level 0 from its layers, then the mip chain: the
    // driver's over whole layers, else downsample()'s over the views' rectangles.
    void prefilter(std::span<const OpacityView> views) const;
    // m_prefiltered's levels 1 … over each view's rectangle alone, level by level.
    void downsample(std::span<const OpacityView> views) const;
    Program m_first, m_transmittance;  // opacity.frag with and without SK_OPACITY_FIRST, materials only
    Program m_prefilter;               // opacity_prefilter.frag
    Program m_downsample;              // opacity_downsample.frag
    std::vector<Texture> m_levelViews; // m_prefiltered's levels but the last, each alone: downsample()'s sources
    Texture m_firstDepth, m_layers;
    Texture m_prefiltered; // mipmapped: the leaves' absorbance and its depth moment (opacity_prefilter.frag)
    Texture m_nearestLeaf; // D32F, one layer: the first leaf's draw's depth test, every view in turn
    Framebuffer m_framebuffer;
    Framebuffer m_firstFramebuffer; // the first leaf's depth with m_nearestLeaf for its depth test
    PassSamples m_firstSamples, m_leafSamples;
    VertexArray m_emptyVertexArray;
    int m_width = 0, m_height = 0, m_count = 0, m_mipLevels = 0;
};

} // namespace shadowkit::gl
