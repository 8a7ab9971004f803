// GoogleTest fixture with one headless OpenGL context for the whole suite (CTest label
// `gl`): creating a context costs more than most rendering tests.
#pragma once

#include "shadowkit/gl/context.h"

#include <gtest/gtest.h>

namespace shadowkit::gl::testing {

class HeadlessGlTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        auto context = Context::createHeadless();
        ASSERT_TRUE(context) << context.error();
        s_context = std::move(context).value();
    }
    static void TearDownTestSuite() { s_context.reset(); }
    static const Context& context() { return *s_context; }

private:
    static inline std::unique_ptr<Context> s_context;
};

} // namespace shadowkit::gl::testing
