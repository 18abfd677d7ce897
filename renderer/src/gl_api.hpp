// The OpenGL functions the renderer calls, loaded from the current Platform at run time
// (Platform::getProcAddress) instead of linked: OSMesa exports its own entry points, a GPU's
// driver is reached through EGL, and one process may hold both. Each renderer keeps its table
// and makes it the thread's current one whenever it makes its context current (Renderer's
// activate); the gl* names below then call through it, so the passes' code reads as plain GL.
// Private to the renderer; include after <GL/gl.h> and <GL/glext.h> (gl_common.hpp does).
#pragma once

#include <functional>

#define LODOPT_GL_FUNCTIONS(X)                                                                                         \
    X(glActiveTexture)                                                                                                 \
    X(glAttachShader) X(glBeginQuery) X(glBindBuffer) X(glBindBufferBase) X(glBindFramebuffer) X(                      \
        glBindRenderbuffer) X(glBindSampler) X(glBindTexture) X(glBindVertexArray) X(glBlendFuncSeparate)              \
        X(glBufferData) X(glBufferSubData) X(glCheckFramebufferStatus) X(glClear) X(glClearColor) X(glClearDepth) X(   \
            glColorMask) X(glCompileShader) X(glCreateProgram) X(glCreateShader) X(glCullFace) X(glDeleteBuffers)      \
            X(glDeleteFramebuffers) X(glDeleteQueries) X(glDeleteProgram) X(glDeleteRenderbuffers) X(glDeleteSamplers) \
                X(glDeleteShader) X(glDeleteTextures) X(glDeleteVertexArrays) X(glDepthFunc) X(glDepthMask)            \
                    X(glDisable) X(glDrawElements) X(glEnable) X(glEndQuery) X(glEnableVertexAttribArray) X(glFinish)  \
                        X(glFramebufferRenderbuffer) X(glFrontFace) X(glGenBuffers) X(glGenFramebuffers)               \
                            X(glGenRenderbuffers) X(glGenQueries) X(glGenSamplers) X(glGenTextures)                    \
                                X(glGenVertexArrays) X(glGenerateMipmap) X(glGetBufferSubData) X(glGetError)           \
                                    X(glGetProgramInfoLog) X(glGetProgramiv) X(glGetQueryiv) X(glGetQueryObjectui64v)  \
                                        X(glGetShaderInfoLog) X(glGetShaderiv) X(glGetString) X(glGetUniformLocation)  \
                                            X(glLinkProgram) X(glMemoryBarrier) X(glPixelStorei) X(glReadPixels)       \
                                                X(glRenderbufferStorage) X(glSamplerParameteri) X(glScissor)           \
                                                    X(glShaderSource) X(glTexImage2D) X(glTexParameteri)               \
                                                        X(glUniform1f) X(glUniform1i) X(glUniform1iv) X(glUniform1ui)  \
                                                            X(glUniform3fv) X(glUniform4fv) X(glUniformMatrix3fv)      \
                                                                X(glUniformMatrix4fv) X(glUseProgram)                  \
                                                                    X(glVertexAttribPointer) X(glViewport)

namespace lodopt::renderer::gl {

struct Api {
#define LODOPT_GL_MEMBER(name) decltype(&::name) name##_ = nullptr;
    LODOPT_GL_FUNCTIONS(LODOPT_GL_MEMBER)
#undef LODOPT_GL_MEMBER
};

// Fills every entry from `getProcAddress`; throws RenderError naming the first function the
// platform does not give.
Api loadApi(const std::function<void*(const char*)>& getProcAddress);

// The table the gl* calls of this thread go through (null before any renderer activated one).
const Api*& currentApi();

}  // namespace lodopt::renderer::gl

#define LODOPT_GL_CALL(name) (::lodopt::renderer::gl::currentApi()->name##_)
#define glActiveTexture LODOPT_GL_CALL(glActiveTexture)
#define glAttachShader LODOPT_GL_CALL(glAttachShader)
#define glBindBuffer LODOPT_GL_CALL(glBindBuffer)
#define glBindBufferBase LODOPT_GL_CALL(glBindBufferBase)
#define glBindFramebuffer LODOPT_GL_CALL(glBindFramebuffer)
#define glBindRenderbuffer LODOPT_GL_CALL(glBindRenderbuffer)
#define glBindSampler LODOPT_GL_CALL(glBindSampler)
#define glBindTexture LODOPT_GL_CALL(glBindTexture)
#define glBindVertexArray LODOPT_GL_CALL(glBindVertexArray)
#define glBlendFuncSeparate LODOPT_GL_CALL(glBlendFuncSeparate)
#define glBufferData LODOPT_GL_CALL(glBufferData)
#define glBufferSubData LODOPT_GL_CALL(glBufferSubData)
#define glCheckFramebufferStatus LODOPT_GL_CALL(glCheckFramebufferStatus)
#define glClear LODOPT_GL_CALL(glClear)
#define glClearColor LODOPT_GL_CALL(glClearColor)
#define glClearDepth LODOPT_GL_CALL(glClearDepth)
#define glColorMask LODOPT_GL_CALL(glColorMask)
#define glCompileShader LODOPT_GL_CALL(glCompileShader)
#define glCreateProgram LODOPT_GL_CALL(glCreateProgram)
#define glCreateShader LODOPT_GL_CALL(glCreateShader)
#define glCullFace LODOPT_GL_CALL(glCullFace)
#define glDeleteBuffers LODOPT_GL_CALL(glDeleteBuffers)
#define glDeleteFramebuffers LODOPT_GL_CALL(glDeleteFramebuffers)
#define glDeleteProgram LODOPT_GL_CALL(glDeleteProgram)
#define glDeleteRenderbuffers LODOPT_GL_CALL(glDeleteRenderbuffers)
#define glDeleteSamplers LODOPT_GL_CALL(glDeleteSamplers)
#define glDeleteShader LODOPT_GL_CALL(glDeleteShader)
#define glDeleteTextures LODOPT_GL_CALL(glDeleteTextures)
#define glDeleteVertexArrays LODOPT_GL_CALL(glDeleteVertexArrays)
#define glDepthFunc LODOPT_GL_CALL(glDepthFunc)
#define glDepthMask LODOPT_GL_CALL(glDepthMask)
#define glDisable LODOPT_GL_CALL(glDisable)
#define glDrawElements LODOPT_GL_CALL(glDrawElements)
#define glEnable LODOPT_GL_CALL(glEnable)
#define glEnableVertexAttribArray LODOPT_GL_CALL(glEnableVertexAttribArray)
#define glFinish LODOPT_GL_CALL(glFinish)
#define glFramebufferRenderbuffer LODOPT_GL_CALL(glFramebufferRenderbuffer)
#define glFrontFace LODOPT_GL_CALL(glFrontFace)
#define glGenBuffers LODOPT_GL_CALL(glGenBuffers)
#define glGenFramebuffers LODOPT_GL_CALL(glGenFramebuffers)
#define glGenRenderbuffers LODOPT_GL_CALL(glGenRenderbuffers)
#define glGenSamplers LODOPT_GL_CALL(glGenSamplers)
#define glGenTextures LODOPT_GL_CALL(glGenTextures)
#define glGenVertexArrays LODOPT_GL_CALL(glGenVertexArrays)
#define glGenerateMipmap LODOPT_GL_CALL(glGenerateMipmap)
#define glGetBufferSubData LODOPT_GL_CALL(glGetBufferSubData)
#define glGetError LODOPT_GL_CALL(glGetError)
#define glGetProgramInfoLog LODOPT_GL_CALL(glGetProgramInfoLog)
#define glGetProgramiv LODOPT_GL_CALL(glGetProgramiv)
#define glGetShaderInfoLog LODOPT_GL_CALL(glGetShaderInfoLog)
#define glGetShaderiv LODOPT_GL_CALL(glGetShaderiv)
#define glGetString LODOPT_GL_CALL(glGetString)
#define glGetUniformLocation LODOPT_GL_CALL(glGetUniformLocation)
#define glLinkProgram LODOPT_GL_CALL(glLinkProgram)
#define glMemoryBarrier LODOPT_GL_CALL(glMemoryBarrier)
#define glPixelStorei LODOPT_GL_CALL(glPixelStorei)
#define glReadPixels LODOPT_GL_CALL(glReadPixels)
#define glRenderbufferStorage LODOPT_GL_CALL(glRenderbufferStorage)
#define glSamplerParameteri LODOPT_GL_CALL(glSamplerParameteri)
#define glScissor LODOPT_GL_CALL(glScissor)
#define glShaderSource LODOPT_GL_CALL(glShaderSource)
#define glTexImage2D LODOPT_GL_CALL(glTexImage2D)
#define glTexParameteri LODOPT_GL_CALL(glTexParameteri)
#define glUniform1f LODOPT_GL_CALL(glUniform1f)
#define glUniform1i LODOPT_GL_CALL(glUniform1i)
#define glUniform1iv LODOPT_GL_CALL(glUniform1iv)
#define glUniform1ui LODOPT_GL_CALL(glUniform1ui)
#define glUniform3fv LODOPT_GL_CALL(glUniform3fv)
#define glUniform4fv LODOPT_GL_CALL(glUniform4fv)
#define glUniformMatrix3fv LODOPT_GL_CALL(glUniformMatrix3fv)
#define glUniformMatrix4fv LODOPT_GL_CALL(glUniformMatrix4fv)
#define glUseProgram LODOPT_GL_CALL(glUseProgram)
#define glVertexAttribPointer LODOPT_GL_CALL(glVertexAttribPointer)
#define glViewport LODOPT_GL_CALL(glViewport)
#define glBeginQuery LODOPT_GL_CALL(glBeginQuery)
#define glDeleteQueries LODOPT_GL_CALL(glDeleteQueries)
#define glEndQuery LODOPT_GL_CALL(glEndQuery)
#define glGenQueries LODOPT_GL_CALL(glGenQueries)
#define glGetQueryiv LODOPT_GL_CALL(glGetQueryiv)
#define glGetQueryObjectui64v LODOPT_GL_CALL(glGetQueryObjectui64v)
