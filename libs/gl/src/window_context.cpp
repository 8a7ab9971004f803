#include "shadowkit/gl/window_context.h"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace shadowkit::gl {

core::Result<std::unique_ptr<WindowContext>> WindowContext::create(int width, int height, const std::string& title,
                                                                   const ContextOptions& options) {
    if (!glfwInit())
        return core::environmentError("window: GLFW could not initialise (no display? use the headless commands)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, options.debug ? GLFW_TRUE : GLFW_FALSE);
    GLFWwindow* window = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window) {
        glfwTerminate();
        return core::environmentError("window: no OpenGL 4.5 core context for a window on this display");
    }
    glfwMakeContextCurrent(window);
    auto context = std::unique_ptr<WindowContext>(new WindowContext);
    context->m_window = window;
    context->finishSetup(options, "GLFW window");
    return context;
}

WindowContext::~WindowContext() {
    if (m_window) glfwDestroyWindow(m_window);
    glfwTerminate();
}

} // namespace shadowkit::gl
