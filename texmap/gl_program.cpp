#include "texmap/gl_program.h"

#include <glad/gl.h>

#include "texmap/gl_context.h"

namespace rtm {

namespace {

GLuint compile(GLenum type, const std::string& source, const std::string& name) {
    GLuint s = glCreateShader(type);
    const char* src = source.c_str();
    glShaderSource(s, 1, &src, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint len = 0;
        glGetShaderiv(s, GL_INFO_LOG_LENGTH, &len);
        std::string log(size_t(len > 1 ? len : 1), '\0');
        glGetShaderInfoLog(s, len, nullptr, log.data());
        glDeleteShader(s);
        throw GlError("cannot compile the " + name + " shader: " + log.c_str());
    }
    return s;
}

}  // namespace

unsigned link_program(const std::string& vertex_source, const std::string& fragment_source, const std::string& name) {
    GLuint vs = compile(GL_VERTEX_SHADER, vertex_source, name);
    GLuint fs = 0;
    try {
        fs = compile(GL_FRAGMENT_SHADER, fragment_source, name);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    GLuint p = glCreateProgram();
    glAttachShader(p, vs);
    glAttachShader(p, fs);
    glLinkProgram(p);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint len = 0;
        glGetProgramiv(p, GL_INFO_LOG_LENGTH, &len);
        std::string log(size_t(len > 1 ? len : 1), '\0');
        glGetProgramInfoLog(p, len, nullptr, log.data());
        glDeleteProgram(p);
        throw GlError("cannot link the " + name + " program: " + log.c_str());
    }
    return p;
}

}  // namespace rtm
