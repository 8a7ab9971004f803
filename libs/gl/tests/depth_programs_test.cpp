// The sun's depth programs (sun_pass.h, depth.frag): opaque and alpha-tested casters in the
// hyperbolic layout are drawn by programs that never write gl_FragDepth, so early and
// hierarchical depth tests stay on for every caster fragment; only the linear layout, whose
// depth is computed per fragment, writes it. Checked by program introspection (a written
// gl_FragDepth is an active program output), so a write slipped back in — even
// `gl_FragDepth = gl_FragCoord.z` on a path no uniform takes — fails here on any GL.
// CTest label `gl`.
#include "headless_gl_test.h"

#include "sun_pass.h"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

using namespace shadowkit;

namespace {

class DepthProgramsTest : public gl::testing::HeadlessGlTest {};

bool writesFragmentDepth(GLuint program) {
    return glGetProgramResourceIndex(program, GL_PROGRAM_OUTPUT, "gl_FragDepth") != GL_INVALID_INDEX;
}

} // namespace

TEST_F(DepthProgramsTest, OnlyTheLinearLayoutsDepthProgramsWriteFragmentDepth) {
    auto pass = gl::SunPass::create();
    ASSERT_TRUE(pass) << pass.error();
    for (const core::DepthLayout layout : {core::DepthLayout::Hyperbolic, core::DepthLayout::Linear}) {
        const gl::PassPrograms programs = (*pass)->programsFor(layout);
        const bool linear = layout == core::DepthLayout::Linear;
        ASSERT_NE(programs.plain, 0u);
        ASSERT_NE(programs.material, 0u);
        EXPECT_EQ(writesFragmentDepth(programs.plain), linear) << "opaque casters, layout " << int(layout);
        EXPECT_EQ(writesFragmentDepth(programs.material), linear) << "alpha-tested casters, layout " << int(layout);
    }
}
