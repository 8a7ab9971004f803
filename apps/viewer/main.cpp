// shadowkit-viewer: the scene in a window, every option of `render` live in a panel, the
// shadow map beside it, the frame's cost, and the error against ray-traced truth on demand.
// Thin: the libraries draw and measure; this file handles the window, input and the panel.
//
// Keys: W A S D move, Q E down / up, right mouse button + drag looks (orbits with O), wheel
// sets the speed (zooms when orbiting), Shift + left drag moves the sun, C the debug camera,
// F frames the whole scene, T evaluates the frame against truth (in the background), P writes
// a screenshot, Ctrl+S saves the options as a --state file, Space plays / pauses the movers,
// H hides the panel, Esc quits.
#include "common.h"
#include "fly_camera.h"
#include "frame_options.h"
#include "panel.h"
#include "truth_job.h"
#include "viewer_frames.h"

#include "shadowkit/core/wireframe.h"
#include "shadowkit/eval/maps.h"
#include "shadowkit/gl/window_context.h"
#include "shadowkit/measure/measurer.h"
#include "shadowkit/scene/animation.h"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <thread>

namespace shadowkit::viewer {
namespace {

int fail(const std::string& message) {
    fmt::print(stderr, "shadowkit-viewer: error: {}\n", app::oneLine(message));
    return app::kExitBadInput;
}
// The command line's exit codes: 3 where this machine cannot do it (no display, no GL 4.5).
int fail(const core::Error& error) {
    fail(error.message);
    return error.kind == core::ErrorKind::Environment ? app::kExitEnvironment : app::kExitBadInput;
}

// An RGBA image shown by ImGui (the shadow map inset, the error map). The viewer's own GL:
// ImGui takes a texture name.
class ImageTexture {
public:
    ~ImageTexture() {
        if (m_id) glDeleteTextures(1, &m_id);
    }
    void upload(const scene::Image& image) {
        if (image.width == 0) return;
        if (m_id) glDeleteTextures(1, &m_id);
        glCreateTextures(GL_TEXTURE_2D, 1, &m_id);
        glTextureStorage2D(m_id, 1, GL_RGBA8, image.width, image.height);
        glTextureSubImage2D(m_id, 0, 0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
        glTextureParameteri(m_id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        m_width = image.width;
        m_height = image.height;
    }
    void draw(float width) const {
        if (!m_id) return;
        ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(m_id)),
                     ImVec2(width, width * static_cast<float>(m_height) / static_cast<float>(m_width)));
    }

private:
    GLuint m_id = 0;
    int m_width = 1, m_height = 1;
};

// The window as drawn so far (panel included), top row first.
scene::Image readWindow(int width, int height) {
    scene::Image image(width, height);
    std::vector<uint8_t> rows(image.rgba.size());
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    const size_t row = static_cast<size_t>(width) * 4;
    for (int y = 0; y < height; ++y)
        std::copy_n(rows.data() + static_cast<size_t>(height - 1 - y) * row, row,
                    image.rgba.data() + static_cast<size_t>(y) * row);
    for (size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
    return image;
}

struct ViewerArgs {
    FrameOptions options;
    int frames = 0; // 0: until closed
    std::string screenshot, windowShot, saveState = "shadowkit-state.json";
    bool truthAtStart = false; // --truth: T on the first frame (with --frames, awaited before the last)
    bool wireframes = false;   // --wireframes: the view frustum, B and the shadow maps' volumes
    bool debugCamera = false;  // --debug-camera: start looking at them from outside (C)
};

// Wireframes for insight: the camera's frustum (white), the focus body B (green) and each
// shadow map's clip volume (orange; warped maps show their warped volume).
std::vector<gl::LineSegment> insightLines(const core::PerspectiveCamera& camera, const core::ShadowSetup& setup) {
    std::vector<gl::LineSegment> lines;
    auto add = [&](const std::vector<core::Edge>& edges, glm::vec3 color) {
        for (const core::Edge& e : edges) lines.push_back({e.first, e.second, color});
    };
    add(core::clipVolumeEdges(camera.clipFromWorld()), glm::vec3(1.0f));
    add(core::bodyEdges(setup.body), glm::vec3(0.2f, 1.0f, 0.3f));
    for (const core::ShadowView& view : setup.views)
        add(core::clipVolumeEdges(view.clipFromWorld), glm::vec3(1.0f, 0.55f, 0.1f));
    return lines;
}

// A place to see the camera's frustum and B from: framing both.
FlyCamera debugCameraFor(const core::PerspectiveCamera& camera, const core::ShadowSetup& setup) {
    core::Aabb box = setup.body.isEmpty() ? core::Aabb{} : setup.body.bounds();
    for (const core::Edge& e : core::clipVolumeEdges(camera.clipFromWorld())) box.extend(e.first), box.extend(e.second);
    FlyCamera debug;
    debug.frame(box, camera.fovYDegrees);
    return debug;
}

// The viewer's state from one frame to the next, and each concern of a frame in a method of
// its own: input, time, the frame itself, the truth job, the panels.
struct Viewer {
    const ViewerArgs& args;
    app::StateOptions state; // the options as the panel edits them (and Ctrl+S saves them)
    scene::Scene& world;
    measure::Measurer& measurer;
    gl::Renderer& renderer;
    GLFWwindow* glfw;
    double fovYDegrees; // F frames the scene with the first view's field of view

    FlyCamera camera;
    // C: the fly controls move this one instead; the set-up stays the frozen camera's.
    FlyCamera debug;
    bool debugView = false, debugPlaced = false, wireframes = false;
    // O: orbit a point in front of the camera instead of flying; the wheel zooms.
    bool orbiting = false;
    double orbitDistance = 20.0;
    core::Vec3 orbitTarget{0.0};
    ViewerFrames frames; // options parsed when they change; lattices held across camera moves
    // The last option change refused (the last good options stay in use) and the last frame's
    // error: each shown until it no longer holds.
    std::string optionsError, frameError;
    bool dirty = true, showPanel = true, playing = false;
    double sceneTime = 0.0, animatedTime = -1.0;
    std::array<float, 120> frameMs{};
    size_t frameIndex = 0;
    int drawnFrames = 0;
    ImageTexture shadowMapImage, pageTableImage, localMapsImage, errorImage, aliasingImage;
    bool hasLocalMaps = false, hasPageTable = false;
    TruthJob truth;
    std::optional<eval::Figures> truthFigures;
    std::vector<std::pair<std::string, eval::Figures>> truthPerLight; // with local lights
    int64_t shadowedRight = 0;              // of the last evaluation: pixels drawn in shadow where truth has shadow
    std::optional<frame::DrawnFrame> drawn; // the last frame, for the panel, the truth and the debug camera
    // The GPU's figures of the newest frame whose figures came back: read late, as an
    // application loop reads them (Renderer::readGpuFiguresLate), so no frame waits for its own.
    std::optional<gl::GpuFigures> gpuFigures;
    std::string message;

    // Keys (the camera unless ImGui has the keyboard): moving, framing, toggles, screenshot,
    // state, truth.
    void keyboard(const ImGuiIO& io, int frame, double seconds) {
        const auto key = [&](int k) { return glfwGetKey(glfw, k) == GLFW_PRESS ? 1.0 : 0.0; };
        const core::Vec3 motion(key(GLFW_KEY_D) - key(GLFW_KEY_A), key(GLFW_KEY_E) - key(GLFW_KEY_Q),
                                key(GLFW_KEY_W) - key(GLFW_KEY_S));
        if (motion != core::Vec3(0.0)) {
            if (debugView)
                debug.move(motion, seconds);
            else
                camera.move(motion, seconds);
        }
        if (ImGui::IsKeyPressed(GLFW_KEY_F, false)) camera.frame(renderer.wsSceneBounds(), fovYDegrees), frames.cut();
        if (ImGui::IsKeyPressed(GLFW_KEY_H, false)) showPanel = !showPanel;
        if (ImGui::IsKeyPressed(GLFW_KEY_O, false)) {
            orbiting = !orbiting;
            orbitTarget = camera.wsEye + orbitDistance * camera.wsDirection();
        }
        if (ImGui::IsKeyPressed(GLFW_KEY_C, false) || (args.debugCamera && frame == 1)) {
            debugView = !debugView;
            wireframes = wireframes || debugView;
            debugPlaced = false;
        }
        if (ImGui::IsKeyPressed(GLFW_KEY_SPACE, false)) playing = !playing;
        if (ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false)) glfwSetWindowShouldClose(glfw, GLFW_TRUE);
        if (ImGui::IsKeyPressed(GLFW_KEY_P, false) && drawn) {
            const std::string file = args.screenshot.empty() ? "shadowkit-viewer.png" : args.screenshot;
            const core::Status s = scene::writePng(renderer.readColor(), file);
            message = s ? "wrote " + file : s.error();
        }
        if (io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_S, false)) {
            const core::Status s = app::saveState(state, args.saveState);
            message = s ? "saved " + args.saveState + " (shadowkit render --state " + args.saveState + ")" : s.error();
        }
        if ((ImGui::IsKeyPressed(GLFW_KEY_T, false) || (args.truthAtStart && frame == 1)) && drawn) {
            const core::Status s = truth.start(measurer, drawn->frame.view.camera, drawn->frame.view.light,
                                               drawn->frame.setup, drawn->frame.settings);
            message = s ? "evaluating against truth ..." : s.error();
        }
    }

    // Mouse (unless ImGui has it): looking, orbiting, the wheel, Shift + drag moves the sun.
    void mouse(const ImGuiIO& io) {
        if (glfwGetMouseButton(glfw, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS &&
            (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f)) {
            if (debugView)
                debug.turn(io.MouseDelta.x, io.MouseDelta.y);
            else if (orbiting)
                camera.orbit(io.MouseDelta.x, io.MouseDelta.y, orbitTarget);
            else
                camera.turn(io.MouseDelta.x, io.MouseDelta.y);
        }
        if (io.MouseWheel != 0.0f) {
            const double factor = std::pow(1.25, static_cast<double>(io.MouseWheel));
            if (orbiting) {
                // Orbit: the wheel moves in and out.
                orbitDistance = std::max(0.5, orbitDistance / factor);
                camera.wsEye = orbitTarget - orbitDistance * camera.wsDirection();
            } else {
                camera.metresPerSecond *= factor;
            }
        }
        // Shift + left drag: the sun (0.25° per pixel), as the panel's angles.
        if (io.KeyShift && glfwGetMouseButton(glfw, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS && drawn &&
            (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f)) {
            const core::Vec3 towards = drawn->frame.view.light.wsTowardsLight();
            const double elevation = glm::degrees(std::asin(std::clamp(towards.y, -1.0, 1.0))) - 0.25 * io.MouseDelta.y;
            const double azimuth = core::azimuthDegreesOf(towards) + 0.25 * io.MouseDelta.x;
            state["sun-elevation"] = {fmt::format("{:.4g}", std::clamp(elevation, 1.0, 89.0))};
            state["sun-azimuth"] = {fmt::format("{:.4g}", std::fmod(azimuth + 360.0, 360.0))};
            state.erase("sun");
            dirty = true;
        }
    }

    void advanceTime(double seconds) {
        // Time: movers, the sun path and the camera path at sceneTime (as `render --time`).
        if (playing) sceneTime += seconds;
        const app::Timeline* timeline = frames.timeline();
        if (timeline && timeline->path && timeline->frames.size() > 1 && sceneTime > timeline->frames.back().time)
            sceneTime = 0.0;
        if (sceneTime != animatedTime) {
            std::vector<uint32_t> moved;
            scene::animate(world, sceneTime, &moved);
            if (auto s = measurer.moveInstances(world, moved); !s) message = s.error();
            animatedTime = sceneTime;
        }
    }

    // The frame itself: the state file's camera, size and time, the options when they changed,
    // then the frame driver; the debug camera and wireframes over it.
    void drawFrame(int frame, int width, int height) {
        // What the state file saves of the frame (Ctrl+S; render --state draws it): camera, window
        // size, time. Typed into the frame below, not parsed: only the panel's options are.
        if (width > 0 && height > 0) {
            state["eye"] = {vec3Text(camera.wsEye)};
            state["dir"] = {vec3Text(camera.wsDirection())};
            state["size"] = {fmt::format("{}x{}", width, height)};
            if (sceneTime != 0.0)
                state["time"] = {fmt::format("{:.6g}", sceneTime)};
            else
                state.erase("time");
        }
        if (dirty) { // an option changed: a cut (held lattices refitted, auto searches afresh)
            const core::Status s = frames.setOptions(state, world, animatedTime);
            optionsError = s ? std::string() : s.error();
            dirty = false;
        }

        // Draw the frame with the libraries, as `render` does.
        if (frames.ready() && width > 0 && height > 0) {
            auto frameDrawn =
                frames.draw(renderer, world, camera.wsEye, camera.wsDirection(), width, height, sceneTime);
            if (frameDrawn) {
                drawn = std::move(frameDrawn).value();
                ++drawnFrames;
                keepGpuFigures(drawn->stats);
                // A camera path leads: the fly camera follows it.
                if (frames.timeline()->path) {
                    const double speed = camera.metresPerSecond;
                    camera = FlyCamera::looking(drawn->frame.view.camera.wsEye, drawn->frame.view.camera.wsDirection);
                    camera.metresPerSecond = speed;
                }
                // The debug camera sees the frozen camera's set-up from outside, farther.
                if (debugView) {
                    if (!debugPlaced)
                        debug = debugCameraFor(drawn->frame.view.camera, drawn->frame.setup), debugPlaced = true;
                    core::PerspectiveCamera seenFrom = drawn->frame.view.camera;
                    seenFrom.wsEye = debug.wsEye;
                    seenFrom.wsDirection = debug.wsDirection();
                    seenFrom.zFar = 4.0 * drawn->frame.view.camera.zFar;
                    seenFrom.zNear = std::max(drawn->frame.view.camera.zNear, 0.5);
                    if (auto s = renderer.render(seenFrom, drawn->frame.view.light, drawn->frame.setup,
                                                 drawn->frame.settings))
                        keepGpuFigures(*s);
                    else
                        message = s.error();
                    if (wireframes)
                        renderer.drawLines(seenFrom, insightLines(drawn->frame.view.camera, drawn->frame.setup));
                } else if (wireframes) {
                    renderer.drawLines(drawn->frame.view.camera,
                                       insightLines(drawn->frame.view.camera, drawn->frame.setup));
                }
                if (frame % 30 == 0) {
                    shadowMapImage.upload(renderer.readShadowMap());
                    const scene::Image table = renderer.readVirtualPageTable();
                    hasPageTable = table.width > 0;
                    pageTableImage.upload(table);
                    const scene::Image local = renderer.readLocalShadowMaps();
                    hasLocalMaps = local.width > 0;
                    localMapsImage.upload(local);
                }
                frameError.clear();
            } else {
                frameError = app::withFlagName(frameDrawn.errorInfo()).message;
            }
        }
    }

    void keepGpuFigures(const gl::FrameStats& stats) {
        if (!stats.gpuFigures.empty()) gpuFigures = stats.gpuFigures.back();
    }

    // The truth job's result, when one arrives.
    void pollTruth(int frame) {
        // --frames with --truth: the last frame waits for the evaluation.
        if (args.frames > 0 && frame == args.frames - 1)
            while (truth.running() && !truth.ready()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
        if (auto result = truth.poll()) {
            if (*result) {
                const TruthResult& r = **result;
                const eval::Comparison& all = r.combined;
                truthFigures = all.figures;
                truthPerLight.clear();
                if (r.lights.size() > 1)
                    for (const auto& [name, comparison] : r.lights)
                        truthPerLight.emplace_back(name, comparison.figures);
                shadowedRight = std::count(all.classes.begin(), all.classes.end(), eval::PixelClass::ShadowCorrect);
                errorImage.upload(eval::errorMapImage(all, r.width, r.height));
                aliasingImage.upload(eval::aliasingMapImage(all, r.width, r.height));
                message = "evaluated against truth";
            } else {
                message = result->error();
            }
        }
    }

    // The options panel with the frame's figures, and the map insets.
    void panels(int width, int height) {
        ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
        ImGui::SetNextWindowSize(ImVec2(340, static_cast<float>(height) - 20.0f), ImGuiCond_FirstUseEver);
        ImGui::Begin("shadowkit");
        if (drawn) {
            gl::FrameStats st = drawn->stats; // with the GPU's figures of the newest frame that has them
            if (gpuFigures) gpuFigures->fill(st);
            ImGui::Text("%s  %dx%d  map %d", core::techniqueName(drawn->frame.setup.technique).data(),
                        drawn->frame.settings.width, drawn->frame.settings.height, drawn->frame.setup.mapSize);
            ImGui::Text("set-up %.3f ms CPU   culling %.1f ms", drawn->frame.setupMilliseconds, st.cullMilliseconds);
            if (gpuFigures)
                ImGui::Text("GPU figures of frame %lld (%lld back)", static_cast<long long>(gpuFigures->frame),
                            static_cast<long long>(st.frame - gpuFigures->frame));
            for (const auto& [name, pass] :
                 {std::pair{"shadow", &st.shadow}, {"local ", &st.local}, {"main  ", &st.main}})
                ImGui::Text("%s %7.2f ms GPU  %6.3f M tris  %zu inst  %zu draws", name, pass->gpuMilliseconds,
                            static_cast<double>(pass->triangles) * 1e-6, pass->instances, pass->drawCalls);
            if (drawn->frame.settings.culling == gl::Culling::Occlusion)
                ImGui::Text("CHC++  %zu nodes visited, %zu queries, %zu waits",
                            static_cast<size_t>(st.occlusion.nodesVisited),
                            static_cast<size_t>(st.occlusion.queriesIssued), static_cast<size_t>(st.occlusion.waits));
            if (drawn->frame.settings.culling == gl::Culling::Gpu)
                ImGui::Text("GPU culling  camera's two-phase pass %.1f ms", st.occlusionMilliseconds);
            if (st.localMaps + st.skippedFaces > 0)
                ImGui::Text("local lights  %d maps, %d cube faces skipped", st.localMaps, st.skippedFaces);
            ImGui::PlotLines("frame ms", frameMs.data(), static_cast<int>(frameMs.size()),
                             static_cast<int>(frameIndex % frameMs.size()), nullptr, 0.0f, FLT_MAX, ImVec2(0, 40));
        }
        if (truth.running()) ImGui::ProgressBar(static_cast<float>(truth.progress()), ImVec2(-1, 0), "truth");
        if (truthFigures)
            ImGui::Text("truth: wrong %.2f %% (shadow %.2f, lit %.2f)  ppt50 %.2f", truthFigures->wrongPct,
                        truthFigures->falseShadowPct, truthFigures->falseLitPct, truthFigures->pixelsPerTexelP50);
        for (const auto& [name, f] : truthPerLight)
            ImGui::Text("  %-9s wrong %.2f %%  ppt50 %.2f", name.c_str(), f.wrongPct, f.pixelsPerTexelP50);
        for (const std::string* error : {&optionsError, &frameError})
            if (!error->empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", error->c_str());
        if (!message.empty()) ImGui::TextWrapped("%s", message.c_str());
        PanelDefaults defaults;
        if (drawn) {
            const core::Vec3 towards = drawn->frame.view.light.wsTowardsLight();
            defaults.sunElevationDegrees = glm::degrees(std::asin(std::clamp(towards.y, -1.0, 1.0)));
            defaults.sunAzimuthDegrees = core::azimuthDegreesOf(towards);
            const core::BiasSettings bias = gl::biasFor(drawn->frame.setup, drawn->frame.settings);
            defaults.biasSlope = bias.slope, defaults.biasConstant = bias.constant,
            defaults.normalOffset = bias.normalOffset, defaults.normalOffsetFootprint = bias.normalOffsetFootprint;
        }
        dirty |= drawOptionsPanel(state, defaults);
        if (ImGui::CollapsingHeader("Time", ImGuiTreeNodeFlags_DefaultOpen)) {
            ImGui::Checkbox("play (Space)", &playing);
            const double end = frames.timeline() && frames.timeline()->path && frames.timeline()->frames.size() > 1
                                   ? frames.timeline()->frames.back().time
                                   : 120.0;
            float t = static_cast<float>(sceneTime);
            if (ImGui::SliderFloat("time (s)", &t, 0.0f, static_cast<float>(end), "%.2f")) sceneTime = t;
            if (frames.timeline() && frames.timeline()->path)
                ImGui::TextUnformatted("camera path: the camera follows it");
        }
        if (ImGui::CollapsingHeader("Wireframes", ImGuiTreeNodeFlags_DefaultOpen)) {
            ImGui::Checkbox("frustum (white), B (green), maps (orange)", &wireframes);
            if (ImGui::Checkbox("debug camera (C)", &debugView))
                debugPlaced = false, wireframes = wireframes || debugView;
        }
        ImGui::End();
        // The insets, on the right: the shadow map(s) and, after T, the error and
        // pixels-per-texel maps of the evaluated frame.
        ImGui::SetNextWindowPos(ImVec2(static_cast<float>(width) - 290.0f, 10.0f), ImGuiCond_FirstUseEver);
        ImGui::Begin("maps", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
        ImGui::TextUnformatted("shadow map (near the light bright)");
        shadowMapImage.draw(260.0f);
        if (hasPageTable) {
            ImGui::TextUnformatted("virtual pages, finest level first:\nshown (level tint), served coarser (white)");
            pageTableImage.draw(260.0f);
        }
        if (hasLocalMaps) {
            ImGui::TextUnformatted("spot maps, cubes unfolded");
            localMapsImage.draw(260.0f);
        }
        if (truthFigures) {
            ImGui::TextUnformatted("error: red false shadow, blue false lit");
            errorImage.draw(260.0f);
            ImGui::TextUnformatted("pixels per texel");
            aliasingImage.draw(260.0f);
        }
        ImGui::End();
    }
};

int run(const ViewerArgs& args, app::StateOptions state) {
    auto sceneData = args.options.scene.load();
    if (!sceneData) return fail(sceneData.errorInfo());
    scene::Scene& world = *sceneData;
    auto first = args.options.view.resolve(world);
    if (!first) return fail(first.errorInfo());
    auto window = gl::WindowContext::create(first->width, first->height, "shadowkit-viewer");
    if (!window) return fail(window.errorInfo());
    auto measurer = measure::Measurer::create(world);
    if (!measurer) return fail(measurer.errorInfo());
    GLFWwindow* glfw = (*window)->window();

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr; // no imgui.ini beside the user's files
    ImGui_ImplGlfw_InitForOpenGL(glfw, true);
    ImGui_ImplOpenGL3_Init("#version 450 core");

    Viewer v{args, std::move(state), world, **measurer, (*measurer)->renderer(), glfw, first->camera.fovYDegrees};
    v.renderer.readGpuFiguresLate(true);
    v.camera = FlyCamera::looking(first->camera.wsEye, first->camera.wsDirection);
    v.wireframes = args.wireframes;
    v.sceneTime = args.options.timeline.time.value_or(0.0);
    auto previous = std::chrono::steady_clock::now();
    const auto loopStart = previous;
    for (int frame = 0; !glfwWindowShouldClose(glfw) && (args.frames == 0 || frame < args.frames); ++frame) {
        glfwPollEvents();
        const auto now = std::chrono::steady_clock::now();
        const double seconds = std::chrono::duration<double>(now - previous).count();
        previous = now;
        v.frameMs[v.frameIndex++ % v.frameMs.size()] = static_cast<float>(seconds * 1e3);

        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        const ImGuiIO& io = ImGui::GetIO();
        if (!io.WantCaptureKeyboard) v.keyboard(io, frame, seconds);
        if (!io.WantCaptureMouse) v.mouse(io);
        v.advanceTime(seconds);
        int width = 0, height = 0;
        glfwGetFramebufferSize(glfw, &width, &height);
        v.drawFrame(frame, width, height);
        v.pollTruth(frame);
        if (v.showPanel) v.panels(width, height);

        ImGui::Render();
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, width, height);
        glClearColor(0, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT);
        v.renderer.present(width, height);
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        if (!args.windowShot.empty() && args.frames > 0 && frame == args.frames - 1)
            if (auto s = scene::writePng(readWindow(width, height), args.windowShot); !s) v.message = s.error();
        glfwSwapBuffers(glfw);
    }
    // --frames: the last frame as `render --state` draws it (no panel), and the options.
    int rc = 0;
    if (!args.screenshot.empty() && args.frames > 0) {
        if (!v.drawn)
            rc = fail("--screenshot: no frame was drawn" + (v.frameError.empty() ? "" : ": " + v.frameError) +
                      (v.optionsError.empty() ? "" : ": " + v.optionsError));
        else if (auto s = scene::writePng(v.renderer.readColor(), args.screenshot); !s)
            rc = fail("--screenshot: " + s.error());
        if (auto s = app::saveState(v.state, args.saveState); !s) rc = fail("--save-state: " + s.error());
    }
    if (v.truthFigures)
        fmt::print("truth: wrong {:.2f} % of {} valid pixels, {} drawn in shadow where truth has shadow\n",
                   v.truthFigures->wrongPct, v.truthFigures->validPx, v.shadowedRight);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - loopStart).count();
    fmt::print("drew {} frames in {:.2f} s: {:.1f} frames/s\n", v.drawnFrames, wall,
               v.drawnFrames / std::max(wall, 1e-9));
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    return rc;
}

} // namespace
} // namespace shadowkit::viewer

int main(int argc, char** argv) {
    using namespace shadowkit;
    viewer::ViewerArgs args;
    CLI::App app{"shadowkit-viewer: the scene in a window with every option of `render` live", "shadowkit-viewer"};
    args.options.addTo(app);
    app.add_option("--frames", args.frames, "draw this many frames, then exit (0: until the window closes)")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--screenshot", args.screenshot,
                   "P writes the frame here; with --frames, the last frame is written on exit");
    app.add_option("--window-shot", args.windowShot, "with --frames: the window, panel included, written on exit");
    app.add_flag("--wireframes", args.wireframes,
                 "draw the view frustum, the focus body B and the shadow maps' volumes");
    app.add_flag("--debug-camera", args.debugCamera, "start with the debug camera (C): the set-up seen from outside");
    app.add_flag("--truth", args.truthAtStart,
                 "evaluate the first frame against truth at once (T); --frames waits for it");
    app.add_option("--save-state", args.saveState, "where Ctrl+S saves the options (with --frames: on exit too)")
        ->capture_default_str();
    auto expanded = app::expandState(std::vector<std::string>(argv + 1, argv + argc));
    if (!expanded) return viewer::fail(expanded.errorInfo());
    app.add_option("--state", "options saved by Ctrl+S (JSON): given flags win");
    const std::vector<std::string> given = *expanded;
    std::reverse(expanded->begin(), expanded->end());
    try {
        app.parse(*expanded);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        fmt::print(stderr, "shadowkit-viewer: error: {} (see shadowkit-viewer --help)\n", app::oneLine(e.what()));
        return 1;
    }
    if (auto s = args.options.technique.check(/*measuresFrames=*/true, /*takesAuto=*/true); !s)
        return viewer::fail(s.errorInfo());
    if (auto s = args.options.render.check(); !s) return viewer::fail(s.errorInfo());
    for (const std::string* file : {&args.screenshot, &args.saveState})
        if (auto s = app::checkWritable("--screenshot/--save-state", *file); !s) return viewer::fail(s.errorInfo());
    return viewer::run(args, viewer::givenOptions(app, given,
                                                  {"frames", "screenshot", "save-state", "state", "window-shot",
                                                   "truth", "wireframes", "debug-camera"}));
}
