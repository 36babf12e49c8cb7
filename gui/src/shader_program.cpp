#include "shader_program.hpp"

#include <algorithm>
#include <string>

namespace anascan::gui::detail {
namespace {

std::string shader_log(GLuint shader) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    return log;
}

Expected<GLuint> compile(GLenum stage, std::string_view source, const char* stage_name) {
    const GLuint shader = glCreateShader(stage);
    const GLchar* text = source.data();
    const auto length = static_cast<GLint>(source.size());
    glShaderSource(shader, 1, &text, &length);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
        std::string log = shader_log(shader);
        glDeleteShader(shader);
        return fail(ErrorCode::kUnsupported,
                    std::string("point renderer: ") + stage_name + " shader: " + log);
    }
    return shader;
}

}  // namespace

Expected<GLuint> build_program(std::string_view vertex_source, std::string_view fragment_source) {
    auto vertex = compile(GL_VERTEX_SHADER, vertex_source, "vertex");
    if (!vertex) return fail(vertex.error());
    auto fragment = compile(GL_FRAGMENT_SHADER, fragment_source, "fragment");
    if (!fragment) {
        glDeleteShader(*vertex);
        return fail(fragment.error());
    }
    const GLuint program = glCreateProgram();
    glAttachShader(program, *vertex);
    glAttachShader(program, *fragment);
    glLinkProgram(program);
    glDeleteShader(*vertex);  // flagged; freed with the program
    glDeleteShader(*fragment);
    GLint ok = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE) {
        GLint length = 0;
        glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
        std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
        glGetProgramInfoLog(program, length, nullptr, log.data());
        glDeleteProgram(program);
        return fail(ErrorCode::kUnsupported, "point renderer: link: " + log);
    }
    return program;
}

}  // namespace anascan::gui::detail
