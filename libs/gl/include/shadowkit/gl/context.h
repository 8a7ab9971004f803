// OpenGL 4.5 core contexts: headless through EGL, or a GLFW window (window_context.h).
#pragma once

#include "shadowkit/core/result.h"

#include <memory>
#include <string>

namespace shadowkit::gl {

struct ContextOptions {
    // KHR_debug output (one line per message on stderr). Default: on in debug builds, and in
    // any headless context when the environment has SHADOWKIT_GL_DEBUG=1.
#ifdef NDEBUG
    bool debug = false;
#else
    bool debug = true;
#endif
};

class Context {
public:
    // Headless: the EGL device platform on a GPU (NVIDIA), else Mesa's surfaceless
    // platform (llvmpipe on CPU-only machines). The context is current on return.
    static core::Result<std::unique_ptr<Context>> createHeadless(const ContextOptions& options = {});

    virtual ~Context() = default;
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    // "4.5 (Core Profile) Mesa 22.3.6, llvmpipe (LLVM 15.0.6, 256 bits) via EGL surfaceless"
    const std::string& description() const { return m_description; }
    // GL_RENDERER alone: "llvmpipe (LLVM 15.0.6, 256 bits)", "NVIDIA H200/PCIe/SSE2"
    // (gl::resolveCulling reads it).
    const std::string& renderer() const { return m_renderer; }

protected:
    Context() = default;
    // Reads version / renderer strings and installs the debug callback if asked.
    void finishSetup(const ContextOptions& options, const std::string& platform);

private:
    std::string m_description;
    std::string m_renderer;
};

} // namespace shadowkit::gl
