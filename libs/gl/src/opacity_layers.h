// Opacity layers for the sun's fixed maps (--foliage-opacity): partial occlusion by alpha-tested
// casters, after deep opacity maps (Yuksel & Keyser 2008, "Deep Opacity Maps", Computer Graphics
// Forum 27(2)). Per texel of each map, the linear depth of the first leaf (R32F) and what the
// leaves let through in four layers measured back from it (RGBA16F);
// glsl/shadowkit_foliage_opacity.glsl's skFoliageTransmittance reads them and multiplies the depth
// map's term, which then holds the opaque casters only (PassPrograms::Batches). Beside them the
// layers prefiltered (RG16F with its mip chain: per texel A = −ln T and A × the leaves' depth),
// from which the lookup reads the mean depth of the leaves around a receiver in one fetch. About
// 17 bytes a texel beside the depth map's 4.
//
// Two passes over the alpha-tested batches of each map's list, with no depth test: the first
// leaf by GL_MIN blending, then each leaf fragment's transmittance by multiplicative blending
// into the layer of its distance behind the first (opacity.frag); then one triangle over each
// map (opacity_prefilter.frag) and the mip chain. Not for virtual pages: the set-up's fixed maps
// (single maps and cascades) only.
#pragma once

#include "gl_object.h"
#include "gpu_scene.h"
#include "pass_lists.h"

#include "shadowkit/core/bias.h"
#include "shadowkit/core/result.h"
#include "shadowkit/core/shadow_setup.h"

#include <memory>
#include <span>

namespace shadowkit::gl {

class OpacityLayers {
public:
    static core::Result<std::unique_ptr<OpacityLayers>> create();

    // The layers for `layers` maps of size² texels, allocated or kept. Out of memory: an error
    // naming map_size.
    core::Status prepare(int size, int layers);
    // Draws every map's layers from the alpha-tested batches of `lists` (one per view of
    // `setup`), writing each view's DepthPass block into `depthPass` (bound at kDepthPassBinding).
    DrawStats draw(const GpuScene& scene, const core::ShadowSetup& setup, const core::BiasSettings& bias,
                   std::span<const PassList> lists, const Buffer& depthPass) const;
    // The layers on kOpacityUnit, the first leaves' depths on kOpacityFirstUnit and the layers
    // prefiltered on kOpacityPrefilteredUnit.
    void bind() const;

private:
    OpacityLayers() = default;
    // Level 0 of m_prefiltered from the layers of every map of `setup`, then its mip chain.
    void prefilter(const core::ShadowSetup& setup) const;
    Program m_first, m_transmittance; // opacity.frag with and without SK_OPACITY_FIRST, materials only
    Program m_prefilter;              // opacity_prefilter.frag
    Texture m_firstDepth, m_layers;
    Texture m_prefiltered; // mipmapped: the leaves' absorbance and its depth moment (opacity_prefilter.frag)
    Framebuffer m_framebuffer;
    VertexArray m_emptyVertexArray;
    int m_size = 0, m_count = 0;
};

} // namespace shadowkit::gl
