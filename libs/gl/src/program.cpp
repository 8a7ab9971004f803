#include "program.h"

#include "gl_shaders.h"

#include <algorithm>
#include <string>
#include <vector>

namespace shadowkit::gl {
namespace {

int g_withoutDrawParameters = 0;     // live WithoutDrawParameters guards
int g_checkingConservativeDepth = 0; // live CheckingConservativeDepth guards

std::string oneLine(std::string log) {
    while (!log.empty() && (log.back() == '\n' || log.back() == ' ' || log.back() == '\0')) log.pop_back();
    std::replace(log.begin(), log.end(), '\n', ' ');
    return log;
}

core::Result<Shader> compile(GLenum stage, std::initializer_list<std::string_view> sources, std::string_view what) {
    Shader shader(glCreateShader(stage));
    std::vector<const char*> texts = {shaderPrelude().data()};
    std::vector<GLint> lengths = {static_cast<GLint>(shaderPrelude().size())};
    // Directives only, so it may follow the prelude's #defines; the source lines count from 1 again.
    // visible.glsl reads SK_BASE_INSTANCE and main.vert SK_DRAW_ID (not the extension's own macro:
    // a GL defines that for what it supports, enabled or not).
    static constexpr std::string_view kDrawParameters = "#extension GL_ARB_shader_draw_parameters : require\n"
                                                        "#define SK_BASE_INSTANCE uint(gl_BaseInstanceARB)\n"
                                                        "#define SK_DRAW_ID uint(gl_DrawIDARB)\n"
                                                        "#line 1\n";
    if (stage == GL_VERTEX_SHADER && vertexStagesReadDrawParameters()) {
        texts.push_back(kDrawParameters.data());
        lengths.push_back(static_cast<GLint>(kDrawParameters.size()));
    }
    // The depth passes' counters and their count, before the fragment stage's sources (whose lines
    // it numbers from 1 again).
    if (stage == GL_FRAGMENT_SHADER && g_checkingConservativeDepth > 0) {
        texts.push_back(shaders::kConservativeDepthCheckGlsl.data());
        lengths.push_back(static_cast<GLint>(shaders::kConservativeDepthCheckGlsl.size()));
    }
    for (std::string_view s : sources) {
        texts.push_back(s.data());
        lengths.push_back(static_cast<GLint>(s.size()));
    }
    glShaderSource(shader.id(), static_cast<GLsizei>(texts.size()), texts.data(), lengths.data());
    glCompileShader(shader.id());
    GLint ok = 0;
    glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint size = 0;
        glGetShaderiv(shader.id(), GL_INFO_LOG_LENGTH, &size);
        std::string log(static_cast<size_t>(std::max(size, 1)), '\0');
        glGetShaderInfoLog(shader.id(), size, nullptr, log.data());
        return core::environmentError(std::string(what) + ": the GL driver rejected it: " + oneLine(log));
    }
    return shader;
}

} // namespace

namespace {

core::Result<Program> link(std::string_view name, std::initializer_list<const Shader*> shaders) {
    Program program(glCreateProgram());
    for (const Shader* shader : shaders) glAttachShader(program.id(), shader->id());
    glLinkProgram(program.id());
    GLint ok = 0;
    glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint size = 0;
        glGetProgramiv(program.id(), GL_INFO_LOG_LENGTH, &size);
        std::string log(static_cast<size_t>(std::max(size, 1)), '\0');
        glGetProgramInfoLog(program.id(), size, nullptr, log.data());
        return core::environmentError(std::string(name) + ": the GL driver could not link it: " + oneLine(log));
    }
    for (const Shader* shader : shaders) glDetachShader(program.id(), shader->id());
    return program;
}

} // namespace

bool vertexStagesReadDrawParameters() {
    return g_withoutDrawParameters == 0 && epoxy_has_gl_extension("GL_ARB_shader_draw_parameters");
}

WithoutDrawParameters::WithoutDrawParameters() { ++g_withoutDrawParameters; }
WithoutDrawParameters::~WithoutDrawParameters() { --g_withoutDrawParameters; }

CheckingConservativeDepth::CheckingConservativeDepth() { ++g_checkingConservativeDepth; }
CheckingConservativeDepth::~CheckingConservativeDepth() { --g_checkingConservativeDepth; }

core::Result<Program> buildComputeProgram(std::string_view name, std::initializer_list<std::string_view> sources) {
    auto cs = compile(GL_COMPUTE_SHADER, sources, std::string(name) + ": compute shader");
    if (!cs) return cs.errorInfo();
    return link(name, {&*cs});
}

core::Result<Program> buildProgram(std::string_view name, std::initializer_list<std::string_view> vertexSources,
                                   std::initializer_list<std::string_view> fragmentSources) {
    auto vs = compile(GL_VERTEX_SHADER, vertexSources, std::string(name) + ": vertex shader");
    if (!vs) return vs.errorInfo();
    auto fs = compile(GL_FRAGMENT_SHADER, fragmentSources, std::string(name) + ": fragment shader");
    if (!fs) return fs.errorInfo();
    return link(name, {&*vs, &*fs});
}

core::Result<Program> buildProgram(std::string_view name, std::initializer_list<std::string_view> vertexSources,
                                   std::initializer_list<std::string_view> geometrySources,
                                   std::initializer_list<std::string_view> fragmentSources) {
    auto vs = compile(GL_VERTEX_SHADER, vertexSources, std::string(name) + ": vertex shader");
    if (!vs) return vs.errorInfo();
    auto gs = compile(GL_GEOMETRY_SHADER, geometrySources, std::string(name) + ": geometry shader");
    if (!gs) return gs.errorInfo();
    auto fs = compile(GL_FRAGMENT_SHADER, fragmentSources, std::string(name) + ": fragment shader");
    if (!fs) return fs.errorInfo();
    return link(name, {&*vs, &*gs, &*fs});
}

core::Status checkUniformBlock(const Program& program, std::string_view programName, const char* blockName,
                               size_t cppSize, std::span<const UniformField> fields) {
    const GLuint index = glGetUniformBlockIndex(program.id(), blockName);
    if (index == GL_INVALID_INDEX)
        return core::environmentError(std::string(programName) + ": uniform block " + blockName +
                                      " missing from the shader");
    GLint size = 0;
    glGetActiveUniformBlockiv(program.id(), index, GL_UNIFORM_BLOCK_DATA_SIZE, &size);
    if (static_cast<size_t>(size) != cppSize)
        return core::environmentError(std::string(programName) + ": uniform block " + blockName + " is " +
                                      std::to_string(size) + " bytes in GLSL but " + std::to_string(cppSize) +
                                      " in C++");
    for (const UniformField& field : fields) {
        GLuint member = GL_INVALID_INDEX;
        glGetUniformIndices(program.id(), 1, &field.name, &member);
        GLint offset = -1;
        if (member != GL_INVALID_INDEX) glGetActiveUniformsiv(program.id(), 1, &member, GL_UNIFORM_OFFSET, &offset);
        if (member == GL_INVALID_INDEX || static_cast<size_t>(offset) != field.offset)
            return core::environmentError(std::string(programName) + ": uniform " + blockName + "." + field.name +
                                          " is at offset " + std::to_string(offset) + " in GLSL but " +
                                          std::to_string(field.offset) + " in C++");
    }
    return core::Ok{};
}

} // namespace shadowkit::gl
