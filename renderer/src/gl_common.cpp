#include "gl_common.hpp"

#include <string>

#include "renderer/renderer.hpp"

namespace lodopt::renderer::gl {

const Api*& currentApi() {
    thread_local const Api* api = nullptr;
    return api;
}

Api loadApi(const std::function<void*(const char*)>& getProcAddress) {
    Api api;
#define LODOPT_GL_LOAD(name)                                                                           \
    api.name##_ = reinterpret_cast<decltype(api.name##_)>(getProcAddress(#name));                     \
    if (!api.name##_) throw RenderError("the OpenGL context gives no " #name " (OpenGL 4.3 core needed)");
    LODOPT_GL_FUNCTIONS(LODOPT_GL_LOAD)
#undef LODOPT_GL_LOAD
    return api;
}

namespace {

GLuint compileShader(GLenum type, const char* source) {
    GLuint shader = glCreateShader(type);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetShaderInfoLog(shader, sizeof(log), nullptr, log);
        glDeleteShader(shader);
        throw RenderError(std::string("shader compilation failed: ") + log);
    }
    return shader;
}

}  // namespace

void checkGl(const char* where) {
    GLenum error = glGetError();
    if (error == GL_NO_ERROR) return;
    const char* name = error == GL_OUT_OF_MEMORY                   ? "GL_OUT_OF_MEMORY"
                       : error == GL_INVALID_OPERATION             ? "GL_INVALID_OPERATION"
                       : error == GL_INVALID_VALUE                 ? "GL_INVALID_VALUE"
                       : error == GL_INVALID_ENUM                  ? "GL_INVALID_ENUM"
                       : error == GL_INVALID_FRAMEBUFFER_OPERATION ? "GL_INVALID_FRAMEBUFFER_OPERATION"
                                                                   : "unknown GL error";
    throw RenderError(std::string("OpenGL error ") + name + " in " + where);
}

GLuint linkProgram(const char* vertexSource, const char* fragmentSource) {
    GLuint vertex = compileShader(GL_VERTEX_SHADER, vertexSource);
    GLuint fragment = compileShader(GL_FRAGMENT_SHADER, fragmentSource);
    GLuint program = glCreateProgram();
    glAttachShader(program, vertex);
    glAttachShader(program, fragment);
    glLinkProgram(program);
    glDeleteShader(vertex);
    glDeleteShader(fragment);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetProgramInfoLog(program, sizeof(log), nullptr, log);
        glDeleteProgram(program);
        throw RenderError(std::string("shader program link failed: ") + log);
    }
    return program;
}

GLuint uploadTexture(const scenes::Texture& texture, GLint internalFormat) {
    GLuint id = 0;
    glGenTextures(1, &id);
    glBindTexture(GL_TEXTURE_2D, id);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, internalFormat, texture.width, texture.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 texture.rgba.data());
    glGenerateMipmap(GL_TEXTURE_2D);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    checkGl(("texture upload '" + texture.name + "'").c_str());
    return id;
}

}  // namespace lodopt::renderer::gl
