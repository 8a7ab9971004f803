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

// Fails unless the block exists, its std140 size equals the C++ struct's size and every
// listed member sits at the C++ offset (GL_UNIFORM_OFFSET), so a field added, moved or
// retyped on one side only is caught when the program is built, not read as garbage.
core::Status checkUniformBlock(const Program& program, std::string_view programName, const char* blockName,
                               size_t cppSize, std::span<const UniformField> fields);

} // namespace shadowkit::gl
