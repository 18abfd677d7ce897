// The OpenGL front of the renderer: uploads a scene once, draws combinations into an FBO.
#include "renderer/renderer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/type_ptr.hpp>
#include <limits>
#include <tuple>

#include "frame_timer.hpp"
#include "gl_common.hpp"
#include "pbr_pass.hpp"
#include "shaders.hpp"

namespace lodopt::renderer {
namespace {

// The pixels (top-left origin) where `object` at `level` can put fragments: the rectangle of
// its vertices' projections, grown by 2 pixels (rasterization rules, the vertex shader's own
// float rounding), clipped to the frame. A clipped triangle stays inside the projection of its
// vertices when all lie in front of the eye. Empty when every vertex is outside one clip plane
// (nothing is drawn: each plane is linear in clip coordinates, so the triangles are outside
// too); the whole frame when a vertex is at or behind the eye plane (no finite projection).
PixelRect projectedRect(const scenes::Object& object, int level, const glm::mat4& viewProjection, int width,
                        int height) {
    const glm::mat4 transform = viewProjection * object.transform;
    scenes::ClipPlaneCounts counts;
    bool unbounded = false;
    const float infinity = std::numeric_limits<float>::infinity();
    float minX = infinity, maxX = -infinity, minY = infinity, maxY = -infinity;
    for (const scenes::Mesh& mesh : object.levels[std::size_t(level)].meshes) {
        if (mesh.indices.empty()) continue;  // not uploaded, never drawn
        for (const glm::vec3& position : mesh.positions) {
            const glm::vec4 clip = transform * glm::vec4(position, 1.0f);
            counts.add(clip);
            if (!(clip.w > 1e-6f)) {
                unbounded = true;
                continue;
            }
            const float x = clip.x / clip.w, y = clip.y / clip.w;
            minX = std::min(minX, x);
            maxX = std::max(maxX, x);
            minY = std::min(minY, y);
            maxY = std::max(maxY, y);
        }
    }
    if (counts.points == 0 || counts.allOutsideOnePlane()) return {};
    // Also a NaN or infinite projection (none lies in front of the eye then): the whole frame.
    if (unbounded || !std::isfinite(minX) || !std::isfinite(maxX) || !std::isfinite(minY) || !std::isfinite(maxY)) {
        return {0, 0, width, height};
    }
    // Window coordinates as the viewport transform computes them, clamped before converting.
    auto toPixels = [](float ndc, int size) {
        return std::clamp(double(ndc) * 0.5 * size + 0.5 * size, -4.0, double(size) + 4.0);
    };
    const int x0 = int(std::floor(toPixels(minX, width))) - 2, x1 = int(std::ceil(toPixels(maxX, width))) + 2;
    // OpenGL's window rows count from the bottom.
    const int y0 = height - int(std::ceil(toPixels(maxY, height))) - 2;
    const int y1 = height - int(std::floor(toPixels(minY, height))) + 2;
    return {std::max(x0, 0), std::max(y0, 0), std::min(x1, width), std::min(y1, height)};
}

// The layer's fragment stacks (Layer::stackPixels) out of `fragments` (pixels indexed in
// `bound`): the pixels of layer.rect with two fragments or more, each stack in blending order.
void stackFragments(std::vector<PbrPass::ListedFragment>& fragments, const PixelRect& bound, Layer& layer) {
    std::sort(fragments.begin(), fragments.end(), [](const auto& a, const auto& b) {
        return std::tie(a.pixel, a.draw, a.primitive) < std::tie(b.pixel, b.draw, b.primitive);
    });
    const PixelRect& rect = layer.rect;
    layer.stackStarts.push_back(0);
    for (std::size_t first = 0; first < fragments.size();) {
        std::size_t end = first + 1;
        while (end < fragments.size() && fragments[end].pixel == fragments[first].pixel) ++end;
        const int x = bound.x0 + int(fragments[first].pixel % std::uint32_t(bound.width()));
        const int y = bound.y0 + int(fragments[first].pixel / std::uint32_t(bound.width()));
        if (end - first >= 2 && x >= rect.x0 && x < rect.x1 && y >= rect.y0 && y < rect.y1) {
            layer.stackPixels.push_back(std::uint32_t(y - rect.y0) * std::uint32_t(rect.width()) +
                                        std::uint32_t(x - rect.x0));
            for (std::size_t f = first; f < end; ++f) {
                Layer::BlendFragment stacked;
                stacked.depth = fragments[f].depth;
                std::memcpy(stacked.rgba, fragments[f].rgba, 4);
                layer.stackFragments.push_back(stacked);
            }
            layer.stackStarts.push_back(std::uint32_t(layer.stackFragments.size()));
        }
        first = end;
    }
}

}  // namespace

const char* shadingName(Shading shading) {
    return shading == Shading::Pbr ? "pbr" : "lambert";
}

Shading parseShading(const std::string& name) {
    if (name == "lambert") return Shading::Lambert;
    if (name == "pbr") return Shading::Pbr;
    throw std::invalid_argument("unknown shading '" + name + "' (expected lambert or pbr)");
}

struct Renderer::Impl {
    const scenes::Scene& scene;
    RenderSettings settings;
    std::unique_ptr<Platform> platform;
    gl::Api api;  // this context's GL functions (gl_api.hpp)

    // Makes the context and its GL functions this thread's current ones.
    void activate() {
        platform->makeCurrent();
        gl::currentApi() = &api;
    }
    GLuint program = 0, framebuffer = 0, colorBuffer = 0, depthBuffer = 0;
    GLint uModelViewProjection = -1, uNormalMatrix = -1, uBaseColor = -1, uHasTexture = -1, uToLight = -1,
          uAmbient = -1, uTexture = -1, uTransformUv = -1, uUvTransform = -1, uModel = -1, uFlatNormals = -1;
    std::unique_ptr<PbrPass> pbrPass;  // Shading::Pbr only
    std::vector<GLuint> textures;      // Lambert: per scene texture, read as stored
    gl::GpuMeshes meshes;
    std::vector<std::uint8_t> readbackColor;
    std::vector<float> readbackDepth;
    std::vector<std::uint8_t> layerColor;  // renderLayer's bounded readback
    std::vector<float> layerDepth;
    std::string vendor, rendererName, version;
    std::unique_ptr<FrameTimer> timer;  // made with the context (frame_timer.hpp)

    Impl(const scenes::Scene& s, RenderSettings st) : scene(s), settings(st) {}

    bool isPbr() const { return settings.shading == Shading::Pbr; }

    void createProgram() {
        if (isPbr()) {
            pbrPass = std::make_unique<PbrPass>(scene, settings);
            return;
        }
        program = gl::linkProgram(shaders::kLambertVertex, shaders::kLambertFragment);
        uModelViewProjection = glGetUniformLocation(program, "uModelViewProjection");
        uNormalMatrix = glGetUniformLocation(program, "uNormalMatrix");
        uBaseColor = glGetUniformLocation(program, "uBaseColor");
        uHasTexture = glGetUniformLocation(program, "uHasTexture");
        uToLight = glGetUniformLocation(program, "uToLight");
        uAmbient = glGetUniformLocation(program, "uAmbient");
        uTexture = glGetUniformLocation(program, "uBaseColorTexture");
        uTransformUv = glGetUniformLocation(program, "uTransformUv");
        uUvTransform = glGetUniformLocation(program, "uUvTransform");
        uModel = glGetUniformLocation(program, "uModel");
        uFlatNormals = glGetUniformLocation(program, "uFlatNormals");
    }

    void createFramebuffer() {
        glGenFramebuffers(1, &framebuffer);
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        glGenRenderbuffers(1, &colorBuffer);
        glBindRenderbuffer(GL_RENDERBUFFER, colorBuffer);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, settings.width, settings.height);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colorBuffer);
        glGenRenderbuffers(1, &depthBuffer);
        glBindRenderbuffer(GL_RENDERBUFFER, depthBuffer);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, settings.width, settings.height);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depthBuffer);
        gl::checkGl("framebuffer allocation");
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            throw RenderError("OpenGL framebuffer of " + std::to_string(settings.width) + "x" +
                              std::to_string(settings.height) + " is incomplete");
        }
    }

    // Lambert reads every texture as stored, as it always has; the PBR pass uploads its own.
    void uploadTextures() {
        if (isPbr()) return;
        for (const scenes::Texture& texture : scene.textures) textures.push_back(gl::uploadTexture(texture, GL_RGBA8));
    }

    void uploadMeshes() {
        std::vector<float> interleaved;
        meshes.resize(scene.objects.size());
        for (std::size_t o = 0; o < scene.objects.size(); ++o) {
            const scenes::Object& object = scene.objects[o];
            meshes[o].resize(object.levels.size());
            for (std::size_t l = 0; l < object.levels.size(); ++l) {
                for (const scenes::Mesh& mesh : object.levels[l].meshes) {
                    if (mesh.indices.empty()) continue;
                    gl::GpuMesh gpu;
                    gpu.material = mesh.material;
                    gpu.indexCount = static_cast<GLsizei>(mesh.indices.size());
                    gpu.hasTangents = mesh.tangents.size() == mesh.positions.size();
                    gpu.flatNormals = mesh.flatNormals;
                    // Lambert reads position, normal and UV; PBR every attribute (defaults: white, no tangent).
                    const int floatsPerVertex = isPbr() ? 18 : 8;
                    interleaved.clear();
                    interleaved.reserve(mesh.positions.size() * floatsPerVertex);
                    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
                        const glm::vec3& p = mesh.positions[v];
                        const glm::vec3 n = v < mesh.normals.size() ? mesh.normals[v] : glm::vec3(0.0f, 1.0f, 0.0f);
                        const glm::vec2 uv = v < mesh.uvs.size() ? mesh.uvs[v] : glm::vec2(0.0f);
                        interleaved.insert(interleaved.end(), {p.x, p.y, p.z, n.x, n.y, n.z, uv.x, uv.y});
                        if (!isPbr()) continue;
                        const glm::vec2 uv1 = v < mesh.uvs1.size() ? mesh.uvs1[v] : glm::vec2(0.0f);
                        const glm::vec4 t = v < mesh.tangents.size() ? mesh.tangents[v] : glm::vec4(0.0f);
                        const glm::vec4 c = v < mesh.colors.size() ? mesh.colors[v] : glm::vec4(1.0f);
                        interleaved.insert(interleaved.end(), {uv1.x, uv1.y, t.x, t.y, t.z, t.w, c.r, c.g, c.b, c.a});
                    }
                    glGenVertexArrays(1, &gpu.vertexArray);
                    glBindVertexArray(gpu.vertexArray);
                    glGenBuffers(1, &gpu.vertexBuffer);
                    glBindBuffer(GL_ARRAY_BUFFER, gpu.vertexBuffer);
                    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(interleaved.size() * sizeof(float)), interleaved.data(),
                                 GL_STATIC_DRAW);
                    glGenBuffers(1, &gpu.indexBuffer);
                    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gpu.indexBuffer);
                    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(std::uint32_t)),
                                 mesh.indices.data(), GL_STATIC_DRAW);
                    const GLsizei stride = floatsPerVertex * sizeof(float);
                    auto attribute = [&](GLuint location, GLint components, int offsetFloats) {
                        glEnableVertexAttribArray(location);
                        glVertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, stride,
                                              reinterpret_cast<void*>(std::size_t(offsetFloats) * sizeof(float)));
                    };
                    attribute(shaders::kPosition, 3, 0);
                    attribute(shaders::kNormal, 3, 3);
                    attribute(shaders::kUv0, 2, 6);
                    if (isPbr()) {
                        attribute(shaders::kUv1, 2, 8);
                        attribute(shaders::kTangent, 4, 10);
                        attribute(shaders::kColor, 4, 14);
                    }
                    glBindVertexArray(0);
                    gl::checkGl(("mesh upload of object '" + object.name + "'").c_str());
                    meshes[o][l].push_back(gpu);
                }
            }
        }
    }

    // What draw() clears first: color and depth (a frame), nothing, or the color alone to
    // transparent black (a layer's blended surfaces, over its own opaque depth).
    enum class Clear { ColorAndDepth, Nothing, ColorToTransparent };

    // Draws the given (object, level) pairs; level kNotDrawn skips the object. With `scissor`
    // (top-left origin), clears and draws only inside it: a layer's pixels outside its
    // projected rectangle are never read. `surfaces` and `clearing` split a layer's passes.
    void draw(const scenes::Combination& combination, const scenes::Camera& camera,
              const PixelRect* scissor = nullptr, PbrPass::Surfaces surfaces = PbrPass::Surfaces::All,
              Clear clearing = Clear::ColorAndDepth) {
        const glm::mat4 viewProjection = beginPass(camera, scissor);
        if (clearing == Clear::ColorAndDepth) {
            const glm::vec4& clear = settings.clearColor;
            glClearColor(clear.r, clear.g, clear.b, clear.a);
            glClearDepth(1.0);
            glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        } else if (clearing == Clear::ColorToTransparent) {
            glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
            glClear(GL_COLOR_BUFFER_BIT);
        }
        glUseProgram(program);
        if (isPbr()) {
            pbrPass->draw(combination, camera, viewProjection, meshes, surfaces);
        } else {
            drawLambert(combination, viewProjection);
        }
        endPass("draw");
    }

    // The state every pass starts from; returns the camera's view-projection matrix.
    glm::mat4 beginPass(const scenes::Camera& camera, const PixelRect* scissor) {
        activate();
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        glViewport(0, 0, settings.width, settings.height);
        if (scissor) {
            glEnable(GL_SCISSOR_TEST);
            glScissor(scissor->x0, settings.height - scissor->y1, scissor->width(), scissor->height());
        } else {
            glDisable(GL_SCISSOR_TEST);
        }
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDisable(GL_CULL_FACE);
        glDisable(GL_BLEND);
        glDisable(GL_DITHER);
        return scenes::projectionMatrix(camera, float(settings.width) / float(settings.height)) *
               scenes::viewMatrix(camera);
    }

    void endPass(const char* what) {
        glBindVertexArray(0);
        glDisable(GL_SCISSOR_TEST);
        gl::checkGl(what);
    }

    // The blended fragments of `combination` inside `bound` that pass the depth test against the
    // depth buffer as it is (PbrPass::listBlendedFragments), each one's pixel turned into its
    // row-major index in `bound` (rows top to bottom).
    std::vector<PbrPass::ListedFragment> listBlendedFragments(const scenes::Combination& combination,
                                                              const scenes::Camera& camera, const PixelRect& bound) {
        const glm::mat4 viewProjection = beginPass(camera, &bound);
        std::vector<PbrPass::ListedFragment> fragments =
            pbrPass->listBlendedFragments(combination, camera, viewProjection, meshes);
        endPass("blended fragment list");
        std::size_t kept = 0;
        for (const PbrPass::ListedFragment& fragment : fragments) {
            const int x = int(fragment.pixel & 0xffffu), y = settings.height - 1 - int(fragment.pixel >> 16);
            if (x < bound.x0 || x >= bound.x1 || y < bound.y0 || y >= bound.y1) continue;
            PbrPass::ListedFragment& into = fragments[kept++];
            into = fragment;
            into.pixel = std::uint32_t(y - bound.y0) * std::uint32_t(bound.width()) + std::uint32_t(x - bound.x0);
        }
        fragments.resize(kept);
        return fragments;
    }

    void drawLambert(const scenes::Combination& combination, const glm::mat4& viewProjection) {
        const glm::vec3 toLight = -glm::normalize(settings.lightDirection);
        glUniform3fv(uToLight, 1, glm::value_ptr(toLight));
        glUniform1f(uAmbient, settings.ambient);
        glUniform1i(uTexture, 0);
        glActiveTexture(GL_TEXTURE0);
        for (std::size_t o = 0; o < combination.size(); ++o) {
            const int level = combination[o];
            if (level == scenes::kNotDrawn) continue;
            const glm::mat4& model = scene.objects[o].transform;
            const glm::mat4 mvp = viewProjection * model;
            const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(model)));
            glUniformMatrix4fv(uModelViewProjection, 1, GL_FALSE, glm::value_ptr(mvp));
            glUniformMatrix4fv(uModel, 1, GL_FALSE, glm::value_ptr(model));
            glUniformMatrix3fv(uNormalMatrix, 1, GL_FALSE, glm::value_ptr(normalMatrix));
            for (const gl::GpuMesh& mesh : meshes[o][level]) {
                glm::vec4 color(1.0f);
                int texture = -1;
                bool transformUv = false;
                if (mesh.material >= 0) {
                    const scenes::Material& material = scene.materials[std::size_t(mesh.material)];
                    color = material.baseColorFactor;
                    texture = material.baseColorTexture.texture;
                    transformUv = texture >= 0 && !material.baseColorTexture.transform.isIdentity();
                    if (transformUv) {
                        const glm::mat3 uvTransform = material.baseColorTexture.transform.matrix();
                        glUniformMatrix3fv(uUvTransform, 1, GL_FALSE, glm::value_ptr(uvTransform));
                    }
                }
                glUniform1i(uTransformUv, transformUv ? 1 : 0);
                glUniform1i(uFlatNormals, mesh.flatNormals ? 1 : 0);
                glUniform4fv(uBaseColor, 1, glm::value_ptr(color));
                glUniform1i(uHasTexture, texture >= 0 ? 1 : 0);
                glBindTexture(GL_TEXTURE_2D, texture >= 0 ? textures[texture] : 0);
                glBindVertexArray(mesh.vertexArray);
                glDrawElements(GL_TRIANGLES, mesh.indexCount, GL_UNSIGNED_INT, nullptr);
            }
        }
    }

    // Reads `rect` (top-left origin, inside the frame) of color and depth into `color` and
    // `depth`, rows top to bottom.
    void readBackRect(const PixelRect& rect, std::vector<std::uint8_t>& color, std::vector<float>& depth) {
        const int w = rect.width(), h = rect.height();
        readbackColor.resize(std::size_t(w) * h * 4);
        readbackDepth.resize(std::size_t(w) * h);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadPixels(rect.x0, settings.height - rect.y1, w, h, GL_RGBA, GL_UNSIGNED_BYTE, readbackColor.data());
        glReadPixels(rect.x0, settings.height - rect.y1, w, h, GL_DEPTH_COMPONENT, GL_FLOAT, readbackDepth.data());
        gl::checkGl("glReadPixels");
        color.resize(readbackColor.size());
        depth.resize(readbackDepth.size());
        for (int y = 0; y < h; ++y) {
            const std::size_t from = std::size_t(h - 1 - y) * w, to = std::size_t(y) * w;
            std::memcpy(&color[to * 4], &readbackColor[from * 4], std::size_t(w) * 4);
            std::memcpy(&depth[to], &readbackDepth[from], std::size_t(w) * sizeof(float));
        }
    }

    // Reads the whole frame back, rows top to bottom.
    void readBack(Frame& out) {
        out.width = settings.width;
        out.height = settings.height;
        readBackRect({0, 0, settings.width, settings.height}, out.rgba, out.depth);
    }
};

Renderer::Renderer(const scenes::Scene& scene, RenderSettings settings)
    : Renderer(scene, settings, createPlatform(settings.backend)) {}

Renderer::Renderer(const scenes::Scene& scene, RenderSettings settings, std::unique_ptr<Platform> platform)
    : mImpl(std::make_unique<Impl>(scene, settings)) {
    if (!platform) throw RenderError("renderer: no platform (null Platform given)");
    if (settings.width < 1 || settings.height < 1 || settings.width > 16384 || settings.height > 16384) {
        throw RenderError("render size " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                          " is outside 1..16384");
    }
    scenes::validateScene(scene);
    mImpl->platform = std::move(platform);
    mImpl->platform->makeCurrent();
    mImpl->api = gl::loadApi([this](const char* name) { return mImpl->platform->getProcAddress(name); });
    mImpl->activate();
    auto glString = [](GLenum name) {
        const GLubyte* text = glGetString(name);
        return text ? std::string(reinterpret_cast<const char*>(text)) : std::string("unknown");
    };
    mImpl->vendor = glString(GL_VENDOR);
    mImpl->rendererName = glString(GL_RENDERER);
    mImpl->version = glString(GL_VERSION);
    mImpl->timer = std::make_unique<FrameTimer>(settings.frameClock, mImpl->rendererName);
    mImpl->createProgram();
    mImpl->createFramebuffer();
    mImpl->uploadTextures();
    mImpl->uploadMeshes();
}

Renderer::~Renderer() {
    if (!mImpl || !mImpl->platform) return;
    mImpl->activate();
    for (auto& object : mImpl->meshes) {
        for (auto& level : object) {
            for (gl::GpuMesh& mesh : level) {
                glDeleteBuffers(1, &mesh.vertexBuffer);
                glDeleteBuffers(1, &mesh.indexBuffer);
                glDeleteVertexArrays(1, &mesh.vertexArray);
            }
        }
    }
    mImpl->pbrPass.reset();
    if (!mImpl->textures.empty()) glDeleteTextures(GLsizei(mImpl->textures.size()), mImpl->textures.data());
    glDeleteRenderbuffers(1, &mImpl->colorBuffer);
    glDeleteRenderbuffers(1, &mImpl->depthBuffer);
    glDeleteFramebuffers(1, &mImpl->framebuffer);
    glDeleteProgram(mImpl->program);
    if (mImpl->timer) mImpl->timer->release();
}

const RenderSettings& Renderer::settings() const { return mImpl->settings; }

std::string Renderer::glRendererString() const { return mImpl->vendor + " / " + mImpl->rendererName; }
std::string Renderer::glVersionString() const { return mImpl->version; }
std::string Renderer::platformDescription() const { return mImpl->platform->description(); }

void Renderer::render(const scenes::Combination& combination, const scenes::Camera& camera, Frame& out) {
    scenes::validateCombination(mImpl->scene, combination);
    mImpl->draw(combination, camera);
    mImpl->readBack(out);
}

Frame Renderer::render(const scenes::Combination& combination, const scenes::Camera& camera) {
    Frame frame;
    render(combination, camera, frame);
    return frame;
}

void Renderer::drawAndFinish(const scenes::Combination& combination, const scenes::Camera& camera) {
    scenes::validateCombination(mImpl->scene, combination);
    mImpl->draw(combination, camera);
    glFinish();
}

FrameTimes Renderer::timeFrames(const scenes::Combination& combination, const scenes::Camera& camera, int repeats,
                               int warmup) {
    if (repeats < 1) throw RenderError("timeFrames: repeats must be >= 1, got " + std::to_string(repeats));
    scenes::validateCombination(mImpl->scene, combination);
    mImpl->activate();
    Impl& impl = *mImpl;
    const auto draw = [&] { impl.draw(combination, camera); };
    impl.timer->warmUpOnce(
        [&] {
            Frame scratch;
            draw();
            impl.readBack(scratch);
        },
        draw);
    return impl.timer->time(draw, repeats, warmup);
}

FrameClock Renderer::frameClock() const { return mImpl->timer->clock(); }
bool Renderer::hasTimerQueries() const { return mImpl->timer->hasQuery(); }

Layer Renderer::renderLayer(int object, int level, const scenes::Camera& camera) {
    const scenes::Scene& scene = mImpl->scene;
    if (object < 0 || object >= static_cast<int>(scene.objects.size()) || level < 0 ||
        level >= static_cast<int>(scene.objects[object].levels.size())) {
        throw RenderError("renderLayer: no level " + std::to_string(level) + " of object " + std::to_string(object));
    }
    Layer layer;
    layer.object = object;
    layer.level = level;
    const int width = mImpl->settings.width, height = mImpl->settings.height;
    const glm::mat4 viewProjection =
        scenes::projectionMatrix(camera, float(width) / float(height)) * scenes::viewMatrix(camera);
    // Only the pixels the object can reach are cleared, drawn and read back: most objects of a
    // large scene are small on screen or out of view (the same pixels as a whole-frame render).
    const PixelRect bound = projectedRect(scene.objects[object], level, viewProjection, width, height);
    if (bound.empty()) return layer;
    scenes::Combination alone(scene.objects.size(), scenes::kNotDrawn);
    alone[object] = level;
    std::vector<std::uint8_t>& color = mImpl->layerColor;
    std::vector<float>& depth = mImpl->layerDepth;
    const bool blends = mImpl->isPbr() && mImpl->pbrPass->blends(std::size_t(object), level);
    // A layer with blended surfaces takes three passes over the same pixels: the opaque ones
    // (color and the depth they hide others behind), the blended ones over transparent black in
    // front of those (premultiplied color and coverage), then the blended ones' fragments.
    std::vector<std::uint8_t> blendColor;
    std::vector<float> opaqueDepth, farthest;
    std::vector<PbrPass::ListedFragment> fragments;
    if (blends) {
        mImpl->draw(alone, camera, &bound, PbrPass::Surfaces::Opaque);
        mImpl->readBackRect(bound, color, opaqueDepth);
        mImpl->draw(alone, camera, &bound, PbrPass::Surfaces::Blended, Impl::Clear::ColorToTransparent);
        mImpl->readBackRect(bound, blendColor, depth);
        fragments = mImpl->listBlendedFragments(alone, camera, bound);
        // Coverage: the nearer of the opaque surface and the nearest blended fragment. A listed
        // fragment passed GL_LESS against depth 1 or nearer, so its depth is below 1, and 1
        // marks "none yet" in `farthest`.
        depth = opaqueDepth;
        farthest.assign(depth.size(), 1.0f);
        for (const PbrPass::ListedFragment& fragment : fragments) {
            const std::size_t at = std::size_t(fragment.pixel);  // re-indexed into the bound
            farthest[at] = farthest[at] == 1.0f ? fragment.depth : std::max(farthest[at], fragment.depth);
            depth[at] = std::min(depth[at], fragment.depth);
        }
    } else {
        mImpl->draw(alone, camera, &bound);
        mImpl->readBackRect(bound, color, depth);
    }
    const int boundWidth = bound.width();
    PixelRect rect{bound.x1, bound.y1, bound.x0, bound.y0};
    for (int y = 0; y < bound.height(); ++y) {
        const float* row = &depth[std::size_t(y) * boundWidth];
        for (int x = 0; x < boundWidth; ++x) {
            if (row[x] < 1.0f) {
                rect.x0 = std::min(rect.x0, bound.x0 + x);
                rect.y0 = std::min(rect.y0, bound.y0 + y);
                rect.x1 = std::max(rect.x1, bound.x0 + x + 1);
                rect.y1 = std::max(rect.y1, bound.y0 + y + 1);
                ++layer.coveredPixels;
            }
        }
    }
    if (layer.coveredPixels == 0) return layer;
    layer.rect = rect;
    const int w = rect.width(), h = rect.height();
    // The rows of `rect` out of a bound-sized readback.
    auto crop = [&](const auto& source, std::size_t channels, auto& target) {
        target.resize(std::size_t(w) * h * channels);
        for (int y = 0; y < h; ++y) {
            const std::size_t from = std::size_t(rect.y0 - bound.y0 + y) * boundWidth + std::size_t(rect.x0 - bound.x0);
            std::memcpy(&target[std::size_t(y) * w * channels], &source[from * channels],
                        std::size_t(w) * channels * sizeof(source[0]));
        }
    };
    crop(color, 4, layer.rgba);
    crop(depth, 1, layer.depth);
    if (blends) {
        crop(blendColor, 4, layer.blendRgba);
        crop(opaqueDepth, 1, layer.opaqueDepth);
        crop(farthest, 1, layer.blendFarthest);
        layer.blendDistance = mImpl->pbrPass->blendDistance(std::size_t(object), level, camera);
        stackFragments(fragments, bound, layer);
    }
    layer.rowSpans = coveredRowSpans(layer);
    return layer;
}

}  // namespace lodopt::renderer
