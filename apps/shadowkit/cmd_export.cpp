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
    // The name first: a scene of minutes is not built to be refused for its name.
    if (auto s = scene::checkExportName(args.out); !s) return fail("--out: " + s.error());
    if (auto s = checkWritable("--out", args.out); !s) return fail(s.errorInfo());
    auto sceneData = args.scene.load();
    if (!sceneData) return fail(sceneData.errorInfo());
    if (auto s = scene::exportScene(*sceneData, args.out); !s) return fail("--out: " + s.error());
    const std::string format = lowerExtension(args.out);
    if (format == ".obj" && (!sceneData->cameras.empty() || !sceneData->lights.empty()))
        warn(fmt::format("--out {}: an OBJ holds no camera or light: the scene's {} camera{} and {} light{} are left "
                         "out (a .glb keeps them)",
                         args.out, sceneData->cameras.size(), sceneData->cameras.size() == 1 ? "" : "s",
                         sceneData->lights.size(), sceneData->lights.size() == 1 ? "" : "s"));
    if (const size_t moving = sceneData->tracks.size(); format == ".obj" && moving > 0) {
        const char* plural = moving == 1 ? "" : "s";
        const char* verb = moving == 1 ? "s" : "";
        warn(fmt::format("--out {}: an OBJ holds no animation: {}", args.out,
                         args.scene.scene == "forest"
                             ? fmt::format("the forest's {} mover{} stand{} where t = 0 puts them (a .glb keeps them "
                                           "circling)",
                                           moving, plural, verb)
                             : fmt::format("the {} instance{} the file's animations move stand{} as at t = 0 (a .glb "
                                           "keeps them)",
                                           moving, plural, verb)));
    }
    if (const size_t deformed = sceneData->deformations.size(); format == ".obj" && deformed > 0)
        warn(fmt::format("--out {}: an OBJ holds no animation: the {} mesh{} the file's animations deform {} written "
                         "as posed at t = 0 (a .glb keeps {} skin{} and morph targets playing)",
                         args.out, deformed, deformed == 1 ? "" : "es", deformed == 1 ? "is" : "are",
                         deformed == 1 ? "its" : "their", deformed == 1 ? "" : "s"));
    fmt::print("wrote {} ({:.2f} M triangles)\n", args.out, static_cast<double>(sceneData->triangleCount()) * 1e-6);
    return 0;
}

} // namespace

Command addExportCommand(CLI::App& app) {
    auto args = std::make_shared<ExportArgs>();
    CLI::App* cmd = app.add_subcommand("export", "Write a scene as glTF binary (.glb) or Wavefront OBJ (.obj)");
    args->scene.addTo(*cmd);
    // The file's own meshes, a building a mesh, not the tiles a frame draws them as (mesh_merge.cpp):
    // an export hands the scene on, and tiles would lose what the user's tools know of each mesh.
    args->scene.mergeSmallMeshes = false;
    cmd->add_option("--out", args->out, "output file (.glb or .obj)")->required();
    return {cmd, [args] { return runExport(*args); }};
}

} // namespace shadowkit::app
