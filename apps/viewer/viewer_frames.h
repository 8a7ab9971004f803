// The viewer's frames, apart from the window: its options held as text (app::StateOptions, the
// `--state` file's form, which the panel edits) are parsed into the typed frame configuration
// only when they change; the camera, image size and time come typed with each frame. The frame
// driver is kept across frames, so held lattices (--stabilize) and auto's tracking survive
// camera moves: only an option change or a cut (F, a jump) starts them afresh.
#pragma once

#include "frame_options.h"

#include "shadowkit/frame/frame_driver.h"
#include "shadowkit/scene/scene.h"

#include <memory>
#include <optional>

namespace shadowkit::viewer {

class ViewerFrames {
public:
    // New options (panel, sun drag, a loaded state): parsed and checked; the next frame is a
    // cut. On error the last good options stay in use; the error names the option. A camera path
    // that frames the scene frames one box throughout, as `render`'s does (scene::framedOverPath:
    // `world` is animated over the path and left at `now`, the time it stands at).
    core::Status setOptions(const app::StateOptions& state, scene::Scene& world, double now = 0.0);
    // The next frame starts afresh (lattices refitted, auto's full search).
    void cut();

    // The options' view at time t (its camera path's camera, else `wsEye` looking along
    // `wsDirection`), width × height pixels, drawn through the frame driver. The eye and
    // direction are taken as the state file writes them (6 significant digits), so that
    // `shadowkit render --state` draws exactly this frame.
    core::Result<frame::DrawnFrame> draw(gl::Renderer& renderer, const scene::Scene& world, const core::Vec3& wsEye,
                                         const core::Vec3& wsDirection, int width, int height, double t);

    bool ready() const { return m_options != nullptr; }
    const app::Timeline* timeline() const { return m_timeline ? &*m_timeline : nullptr; }
    const frame::FrameDriver* driver() const { return m_driver ? &*m_driver : nullptr; }

private:
    std::unique_ptr<FrameOptions> m_options;
    std::optional<app::Timeline> m_timeline;
    std::optional<scene::ResolvedView> m_still; // the options' view, before camera, size and time
    std::optional<frame::FrameDriver> m_driver;
};

// "x,y,z" as the state file holds a vector (6 significant digits).
std::string vec3Text(const core::Vec3& v);

} // namespace shadowkit::viewer
