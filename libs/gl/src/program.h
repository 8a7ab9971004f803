// Shader programs from embedded GLSL, with compile and link logs as errors, and
// uniform blocks checked against their C++ declaration.
#pragma once

#include "gl_object.h"

#include "shadowkit/core/result.h"

#include <initializer_list>
#include <string_view>

namespace shadowkit::gl {

// `name` appears in error messages ("depth pass: vertex shader: 0:12(3): error: ...").
// Each stage may be several source strings, concatenated in order (shared declarations first).
core::Result<Program> buildProgram(std::string_view name, std::initializer_list<std::string_view> vertexSources,
                                   std::initializer_list<std::string_view> fragmentSources);

// Fails unless the block exists and its std140 size equals the C++ struct's size, so a
// field added on one side only is caught when the program is built, not as garbage.
core::Status checkUniformBlock(const Program& program, std::string_view programName, const char* blockName,
                               size_t cppSize);

} // namespace shadowkit::gl
