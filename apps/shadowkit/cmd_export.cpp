// shadowkit export: a scene as .glb or .obj in world coordinates (scene_io.h).
#include "commands.h"
#include "options.h"

#include "shadowkit/scene/scene_io.h"

#include <fmt/format.h>

namespace shadowkit::app {
namespace {

struct ExportArgs {
    SceneOptions scene;
    std::string out;
};

int runExport(const ExportArgs& args) {
    auto sceneData = args.scene.load();
    if (!sceneData) return fail(sceneData.errorInfo());
    if (auto s = scene::exportScene(*sceneData, args.out); !s) return fail("--out: " + s.error());
    fmt::print("wrote {} ({:.2f} M triangles)\n", args.out, static_cast<double>(sceneData->triangleCount()) * 1e-6);
    return 0;
}

} // namespace

Command addExportCommand(CLI::App& app) {
    auto args = std::make_shared<ExportArgs>();
    CLI::App* cmd = app.add_subcommand("export", "Write a scene as glTF binary (.glb) or Wavefront OBJ (.obj)");
    args->scene.addTo(*cmd);
    cmd->add_option("--out", args->out, "output file (.glb or .obj)")->required();
    return {cmd, [args] { return runExport(*args); }};
}

} // namespace shadowkit::app
