// GoogleTest fixture with one headless OpenGL context for the whole suite (CTest label
// `gl`): creating a context costs more than most rendering tests. Where no context can be
// created (no EGL, no Mesa), every test of the suite is skipped with the reason.
#pragma once

#include "shadowkit/gl/context.h"

#include <gtest/gtest.h>

#include <string>

namespace shadowkit::gl::testing {

class HeadlessGlTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        auto context = Context::createHeadless();
        if (context)
            s_context = std::move(context).value();
        else
            s_unavailable = context.error();
    }
    static void TearDownTestSuite() { s_context.reset(); }
    void SetUp() override {
        if (!s_context) GTEST_SKIP() << "no headless OpenGL 4.5 context here: " << s_unavailable;
    }
    static const Context& context() { return *s_context; }

private:
    static inline std::unique_ptr<Context> s_context;
    static inline std::string s_unavailable;
};

} // namespace shadowkit::gl::testing
