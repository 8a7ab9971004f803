// Headless EGL contexts.
//
// Order: the EGL device platform with a hardware device first (for drivers without Mesa's
// surfaceless platform), then Mesa's surfaceless platform: llvmpipe on CPU-only machines, and
// NVIDIA's 580 driver on an H100 answered through it too (docs/performance.md, On a real GPU). Both create a 4.5 core
// context without a config or surface (EGL_KHR_no_config_context, EGL_KHR_surfaceless_context) and render into FBOs.
#include "shadowkit/gl/context.h"

#include "debug_output.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace shadowkit::gl {
namespace {

bool hasExtension(const char* list, const char* name) {
    if (!list) return false;
    const size_t len = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += len)
        if ((p == list || p[-1] == ' ') && (p[len] == ' ' || p[len] == '\0')) return true;
    return false;
}

class EglContext final : public Context {
public:
    ~EglContext() override {
        if (m_display == EGL_NO_DISPLAY) return;
        eglMakeCurrent(m_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (m_context != EGL_NO_CONTEXT) eglDestroyContext(m_display, m_context);
        eglTerminate(m_display);
    }

    // Tries one display; leaves *this empty on failure and says why in `failures`.
    bool tryDisplay(EGLDisplay display, const ContextOptions& options, const char* platform) {
        auto failed = [&](const std::string& why) {
            failures += std::string(failures.empty() ? "" : "; ") + platform + ": " + why;
            return false;
        };
        if (display == EGL_NO_DISPLAY) return failed("no display");
        EGLint major = 0, minor = 0;
        if (!eglInitialize(display, &major, &minor)) return failed("the display does not initialise");
        const char* ext = eglQueryString(display, EGL_EXTENSIONS);
        if (!hasExtension(ext, "EGL_KHR_no_config_context") || !hasExtension(ext, "EGL_KHR_surfaceless_context") ||
            !eglBindAPI(EGL_OPENGL_API)) {
            eglTerminate(display);
            return failed(
                "no desktop OpenGL without a surface (EGL_KHR_no_config_context, EGL_KHR_surfaceless_context)");
        }
        const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                  4,
                                  EGL_CONTEXT_MINOR_VERSION,
                                  5,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                  EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                  EGL_CONTEXT_OPENGL_DEBUG,
                                  options.debug ? EGL_TRUE : EGL_FALSE,
                                  EGL_NONE};
        const EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
        if (context == EGL_NO_CONTEXT || !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
            const bool created = context != EGL_NO_CONTEXT;
            if (created) eglDestroyContext(display, context);
            eglTerminate(display);
            return failed(created ? "the OpenGL 4.5 context cannot be made current"
                                  : "the driver offers no OpenGL 4.5 core context");
        }
        m_display = display;
        m_context = context;
        finishSetup(options, platform);
        return true;
    }

    std::string failures; // why each display tried did not give a context

private:
    EGLDisplay m_display = EGL_NO_DISPLAY;
    EGLContext m_context = EGL_NO_CONTEXT;
};

} // namespace

core::Result<std::unique_ptr<Context>> Context::createHeadless(const ContextOptions& asked) {
    // SHADOWKIT_GL_DEBUG=1 turns the driver's messages on in any build: what a real driver
    // rejects that llvmpipe accepts shows up as a line on stderr.
    ContextOptions options = asked;
    if (const char* env = std::getenv("SHADOWKIT_GL_DEBUG"); env && *env && std::strcmp(env, "0") != 0)
        options.debug = true;
    auto context = std::unique_ptr<EglContext>(new EglContext);
    const char* clientExt = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);

    if (hasExtension(clientExt, "EGL_EXT_device_enumeration") && hasExtension(clientExt, "EGL_EXT_platform_device")) {
        EGLDeviceEXT devices[16];
        EGLint count = 0;
        if (eglQueryDevicesEXT(16, devices, &count)) {
            for (EGLint i = 0; i < count; ++i) {
                // Mesa lists llvmpipe as a "software" device; the surfaceless path below is
                // the tested route for it.
                if (hasExtension(eglQueryDeviceStringEXT(devices[i], EGL_EXTENSIONS), "EGL_MESA_device_software"))
                    continue;
                if (context->tryDisplay(eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr), options,
                                        "EGL device"))
                    return std::unique_ptr<Context>(std::move(context));
            }
        }
    }
    if (hasExtension(clientExt, "EGL_MESA_platform_surfaceless") &&
        context->tryDisplay(eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
                            options, "EGL surfaceless"))
        return std::unique_ptr<Context>(std::move(context));

    if (context->failures.empty())
        context->failures = clientExt ? "neither a GPU device nor Mesa's surfaceless platform is offered"
                                      : "no EGL implementation answers (libEGL found no vendor library)";
    return core::environmentError("OpenGL: no headless OpenGL 4.5 core context (" + context->failures +
                                  "); on Debian install libegl1 libgl1-mesa-dri, or run where a GPU driver is present");
}

void Context::finishSetup(const ContextOptions& options, const std::string& platform) {
    const auto str = [](GLenum name) {
        const auto* s = reinterpret_cast<const char*>(glGetString(name));
        return std::string(s ? s : "?");
    };
    m_renderer = str(GL_RENDERER);
    m_description = str(GL_VERSION) + ", " + m_renderer + " via " + platform;
    if (options.debug) installDebugOutput();
}

} // namespace shadowkit::gl
