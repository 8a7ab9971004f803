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
    if (auto s = build(virtualMaps, 0); !s) return s;
    return build(virtualMaps, 1);
}

core::Status CameraPrograms::prepareShadedEval(bool virtualMaps) { return build(virtualMaps, 2); }

core::Status CameraPrograms::build(bool virtualMaps, int pass) {
    using namespace shaders;
    const std::string_view variant = virtualMaps ? "#define SK_VIRTUAL_MAPS 1\n" : "#define SK_VIRTUAL_MAPS 0\n";
    const std::string_view shaded = pass == 2 ? "#define SK_EVAL_SHADED 1\n" : "#define SK_EVAL_SHADED 0\n";
    static constexpr const char* kNames[3] = {"main pass", "eval pass", "shaded eval pass"};
    for (const bool material : {false, true}) {
        Program& slot = m_programs[virtualMaps][pass][material];
        if (slot.id() != 0) continue;
        const std::string name =
            std::string(kNames[pass]) + (virtualMaps ? ", virtual" : "") + (material ? ", materials" : "");
        const std::string_view withMaterial = kMaterialVariant[material];
        auto program =
            buildProgram(name, {withMaterial, kFrameGlsl, kVisibleGlsl, kMainVert},
                         {withMaterial, variant, shaded, kFrameGlsl, kMaterialGlsl, kShadowkitShadowsGlsl,
                          kShadowkitFoliageOpacityGlsl, kShadowLookupGlsl, kLocalLightMapsGlsl,
                          kShadowkitLocalShadowsGlsl, kLocalLightsGlsl, kShadeGlsl, pass == 0 ? kMainFrag : kEvalFrag});
        if (!program) return program.errorInfo();
        if (auto s = checkUniformBlock(*program, name, "Frame", sizeof(FrameUniforms), frameFields()); !s) return s;
        if (auto s = checkUniformBlock(*program, name, "LocalLights", sizeof(LocalLightsUniforms), localLightsFields());
            !s)
            return s;
        // Without virtual maps the block is unused, and a driver may leave it out.
        if (virtualMaps)
            if (auto s =
                    checkUniformBlock(*program, name, "VirtualMaps", sizeof(VirtualMapsUniforms), virtualMapsFields());
                !s)
                return s;
        slot = std::move(program).value();
    }
    return core::Ok{};
}

} // namespace shadowkit::gl
