#include "camera_programs.h"

#include "gl_shaders.h"
#include "program.h"
#include "uniforms.h"

#include <string>

namespace shadowkit::gl {

core::Result<ProgramPair> buildCameraDepthPrePass(std::string_view name) {
    using namespace shaders;
    ProgramPair pair;
    for (const bool material : {false, true}) {
        const std::string_view withMaterial = kMaterialVariant[material];
        auto program = buildProgram(name, {withMaterial, kFrameGlsl, kVisibleGlsl, kMainVert},
                                    {withMaterial, kFrameGlsl, kMaterialGlsl, kCameraDepthFrag});
        if (!program) return program.errorInfo();
        if (auto s = checkUniformBlock(*program, name, "Frame", sizeof(FrameUniforms), frameFields()); !s)
            return s.errorInfo();
        (material ? pair.material : pair.plain) = std::move(program).value();
    }
    return pair;
}

core::Result<CameraPrograms> CameraPrograms::create() {
    CameraPrograms programs;
    if (auto s = programs.prepare(false); !s) return s.errorInfo();
    return programs;
}

core::Status CameraPrograms::prepare(bool virtualMaps) {
    using namespace shaders;
    const std::string_view variant = virtualMaps ? "#define SK_VIRTUAL_MAPS 1\n" : "#define SK_VIRTUAL_MAPS 0\n";
    for (const bool evalPass : {false, true})
        for (const bool material : {false, true}) {
            Program& slot = m_programs[virtualMaps][evalPass][material];
            if (slot.id() != 0) continue;
            const std::string name = std::string(evalPass ? "eval pass" : "main pass") +
                                     (virtualMaps ? ", virtual" : "") + (material ? ", materials" : "");
            const std::string_view withMaterial = kMaterialVariant[material];
            auto program = buildProgram(name, {withMaterial, kFrameGlsl, kVisibleGlsl, kMainVert},
                                        {withMaterial, variant, kFrameGlsl, kMaterialGlsl, kShadowkitShadowsGlsl,
                                         kShadowkitFoliageOpacityGlsl, kShadowLookupGlsl, kLocalLightsGlsl,
                                         evalPass ? kEvalFrag : kMainFrag});
            if (!program) return program.errorInfo();
            if (auto s = checkUniformBlock(*program, name, "Frame", sizeof(FrameUniforms), frameFields()); !s) return s;
            if (auto s =
                    checkUniformBlock(*program, name, "LocalLights", sizeof(LocalLightsUniforms), localLightsFields());
                !s)
                return s;
            // Without virtual maps the block is unused, and a driver may leave it out.
            if (virtualMaps)
                if (auto s = checkUniformBlock(*program, name, "VirtualMaps", sizeof(VirtualMapsUniforms),
                                               virtualMapsFields());
                    !s)
                    return s;
            slot = std::move(program).value();
        }
    return core::Ok{};
}

} // namespace shadowkit::gl
