// What the GL side says when the machine, not the input, is at fault: a shader the driver
// rejects and a program it cannot link are one-line environment errors naming the program
// (the command line exits 3 for them). No context at all, an older OpenGL and an allocation
// the driver refuses are simulated from outside in the CLI tests (gl-environment).
#include "headless_gl_test.h"

#include "program.h"

#include <gtest/gtest.h>

using namespace shadowkit;

namespace {
// Sources follow the renderer's prelude (#version and its #defines), as every stage does.
class FailurePathsTest : public gl::testing::HeadlessGlTest {};

constexpr std::string_view kVertex = "void main() { gl_Position = vec4(0.0); }\n";
constexpr std::string_view kBrokenFragment = "out vec4 c;\nvoid main() { c = undeclared; }\n";
constexpr std::string_view kFragment = "out vec4 c;\nvoid main() { c = vec4(1.0); }\n";
} // namespace

TEST_F(FailurePathsTest, AShaderTheDriverRejectsIsAnEnvironmentErrorNamingTheProgram) {
    const auto broken = gl::buildProgram("test program", {kVertex}, {kBrokenFragment});
    ASSERT_FALSE(broken);
    EXPECT_EQ(broken.errorInfo().kind, core::ErrorKind::Environment);
    EXPECT_NE(broken.error().find("test program"), std::string::npos) << broken.error();
    EXPECT_NE(broken.error().find("rejected"), std::string::npos) << broken.error();
    EXPECT_EQ(broken.error().find('\n'), std::string::npos) << broken.error();
    EXPECT_TRUE(gl::buildProgram("test program", {kVertex}, {kFragment})); // the same program, well formed
}
