// A GLFW window with an OpenGL 4.5 core context, for the interactive viewer.
// The only file of libs/gl that knows GLFW.
#pragma once

#include "shadowkit/gl/context.h"

struct GLFWwindow;

namespace shadowkit::gl {

class WindowContext final : public Context {
public:
    // Fails with one line when there is no display or no 4.5 driver.
    static core::Result<std::unique_ptr<WindowContext>> create(int width, int height, const std::string& title,
                                                               const ContextOptions& options = {});
    ~WindowContext() override;
    GLFWwindow* window() const { return m_window; }

private:
    WindowContext() = default;
    GLFWwindow* m_window = nullptr;
};

} // namespace shadowkit::gl
