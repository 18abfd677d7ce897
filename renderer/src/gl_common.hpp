// OpenGL helpers both shadings' passes share. Private to the renderer.
#pragma once

#include <GL/gl.h>
#include <GL/glext.h>

#include "gl_api.hpp"

#include "scenes/scene.hpp"

namespace lodopt::renderer::gl {

// Throws RenderError naming `where` when GL has recorded an error.
void checkGl(const char* where);
// Compiles and links a program; throws RenderError with the driver's log.
GLuint linkProgram(const char* vertexSource, const char* fragmentSource);
// An RGBA8 texture (`internalFormat` GL_RGBA8 or GL_SRGB8_ALPHA8) with mipmaps, repeat and
// trilinear filtering.
GLuint uploadTexture(const scenes::Texture& texture, GLint internalFormat);

// One uploaded Mesh: its vertex array, buffers and material.
struct GpuMesh {
    GLuint vertexArray = 0, vertexBuffer = 0, indexBuffer = 0;
    GLsizei indexCount = 0;
    int material = -1;
    bool hasTangents = false;  // PBR: a normal map needs a tangent frame
    bool flatNormals = false;  // scenes::Mesh::flatNormals: each triangle's own normal
};
// [object][level][mesh], as Scene::objects.
using GpuMeshes = std::vector<std::vector<std::vector<GpuMesh>>>;

}  // namespace lodopt::renderer::gl
