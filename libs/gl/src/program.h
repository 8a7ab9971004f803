// Shader programs from embedded GLSL, with compile and link logs as errors, and
// uniform blocks checked against their C++ declaration.
#pragma once

#include "gl_object.h"
#include "uniforms.h"

#include "shadowkit/core/result.h"

#include <initializer_list>
#include <string_view>

namespace shadowkit::gl {

// `name` appears in error messages ("depth pass: vertex shader: 0:12(3): error: ...").
// Each stage is shaderPrelude() followed by the given source strings, concatenated in
// order (shared declarations first).
core::Result<Program> buildProgram(std::string_view name, std::initializer_list<std::string_view> vertexSources,
                                   std::initializer_list<std::string_view> fragmentSources);

// With a geometry stage between them, likewise.
core::Result<Program> buildProgram(std::string_view name, std::initializer_list<std::string_view> vertexSources,
                                   std::initializer_list<std::string_view> geometrySources,
                                   std::initializer_list<std::string_view> fragmentSources);

// A compute program, likewise.
core::Result<Program> buildComputeProgram(std::string_view name, std::initializer_list<std::string_view> sources);

// Whether vertex stages read the draw parameters: the draw's base instance and its index in a
// multi-draw (gl_BaseInstanceARB, gl_DrawIDARB: GL_ARB_shader_draw_parameters, core in GL 4.6;
// Mesa's llvmpipe and NVIDIA's driver have it). Where they do, each vertex stage is built with the
// extension; visible.glsl adds the base instance to a list entry's place, so a GPU-culled list's
// indirect commands say where each level's entries start, and main.vert takes its level's lookup
// offset by the draw's index: one glMultiDrawElementsIndirect draws the levels of a batch
// (GpuScene::draw). Where not, each level is a draw of its own, its place in the instanceOffset
// uniform.
bool vertexStagesReadDrawParameters();
// While one lives, programs are built, and scenes made, as for a driver without the extension (the
// fallback's tests). Programs built while it lives must be drawn by scenes made while it lives.
class WithoutDrawParameters {
public:
    WithoutDrawParameters();
    ~WithoutDrawParameters();
    WithoutDrawParameters(const WithoutDrawParameters&) = delete;
    WithoutDrawParameters& operator=(const WithoutDrawParameters&) = delete;
};
// While one lives, fragment stages are built with conservative_depth_check.glsl before them: the
// depth passes that write their depth (the sun's linear layout, depth.frag; the local lights',
// local_depth.frag) count, in the atomic counters at kConservativeDepthCheckBinding, their fragments and those whose
// written depth lies in front of the rasterised one — a broken layout(depth_greater) promise, which
// a GPU's early depth test would turn into holes in the map — and how close the bound is. For tests.
class CheckingConservativeDepth {
public:
    CheckingConservativeDepth();
    ~CheckingConservativeDepth();
    CheckingConservativeDepth(const CheckingConservativeDepth&) = delete;
    CheckingConservativeDepth& operator=(const CheckingConservativeDepth&) = delete;
};

// Fails unless the block exists, its std140 size equals the C++ struct's size and every
// listed member sits at the C++ offset (GL_UNIFORM_OFFSET), so a field added, moved or
// retyped on one side only is caught when the program is built, not read as garbage.
core::Status checkUniformBlock(const Program& program, std::string_view programName, const char* blockName,
                               size_t cppSize, std::span<const UniformField> fields);

} // namespace shadowkit::gl
