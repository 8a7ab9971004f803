#include "depth_views.h"

#include "gl_shaders.h"
#include "program.h"

#include <string_view>

namespace shadowkit::gl {

core::Result<ProgramPair> buildDepthViewPrograms(ViewTarget target) {
    ProgramPair programs;
    if (!vertexStagesReadDrawParameters() || !epoxy_has_gl_extension("GL_ARB_shader_viewport_layer_array"))
        return programs;
    using namespace shaders;
    constexpr std::string_view kExtension = "#extension GL_ARB_shader_viewport_layer_array : require\n";
    const std::string_view views =
        target == ViewTarget::Layer ? "#define SK_PAGES 1\n#define SK_VIEW_LAYERS 1\n" : "#define SK_PAGES 1\n";
    constexpr std::string_view kViewDither = "flat in vec2 vDitherOrigin;\n#define SK_DITHER_ORIGIN vDitherOrigin\n";
    const char* what = target == ViewTarget::Layer ? "fixed maps' depth pass" : "virtual pages' depth pass";
    for (const bool material : {false, true}) {
        const std::string_view with = kMaterialVariant[material];
        const std::string name = std::string(what) + (material ? ", materials" : "");
        auto depth =
            buildProgram(name, {kExtension, with, views, kDepthPassGlsl, kVisibleGlsl, kImpostorGlsl, kDepthVert},
                         {with, kViewDither, kDepthPassGlsl, kMaterialGlsl, kDepthFrag});
        if (!depth) return depth.errorInfo();
        if (auto s = checkUniformBlock(*depth, name, "DepthPass", sizeof(DepthPassUniforms), depthPassFields()); !s)
            return s.errorInfo();
        (material ? programs.material : programs.plain) = std::move(depth).value();
    }
    return programs;
}

void setViewBases(const PassPrograms& programs, size_t firstView, int firstTarget, ViewOfDraw viewOfDraw) {
    for (const GLuint program : {programs.plain, programs.material}) {
        if (!program) continue;
        glProgramUniform1ui(program, kPageBaseLocation, static_cast<GLuint>(firstView));
        glProgramUniform1i(program, kViewportBaseLocation, firstTarget);
        glProgramUniform1ui(program, kPagePerDrawLocation, static_cast<GLuint>(viewOfDraw));
    }
}

void uploadViewBlocks(std::span<const PageBlock> blocks, Buffer& buffer, size_t& capacity) {
    if (capacity < blocks.size()) {
        buffer = createBuffer(nullptr, blocks.size() * sizeof(PageBlock));
        capacity = blocks.size();
    }
    uploadToBuffer(buffer.id(), 0, GLsizeiptr(blocks.size() * sizeof(PageBlock)), blocks.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPagesBinding, buffer.id());
}

} // namespace shadowkit::gl
