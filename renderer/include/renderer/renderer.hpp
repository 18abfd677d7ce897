// Headless, deterministic rendering of LOD combinations.
//
// The Renderer is the front: it owns GPU copies of every level of every object of one scene
// and draws any Combination from any Camera into an offscreen framebuffer (RGBA8 color +
// float depth). The backend is a Platform (OSMesa's llvmpipe by default: OpenGL 4.5 core in
// software, no GPU, no display). Shading is the papers' Lambert + ambient on the base color, or
// glTF metallic-roughness PBR (RenderSettings::shading); no MSAA, dithering off, so the same
// inputs give bit-identical pixels.
//
// Layers: renderLayer(i, k) draws object i at level k alone; composite() rebuilds a frame
// from one layer per object by nearest depth. Because the rasterizer is deterministic, a
// composite equals the full render except where two objects' surfaces have exactly equal
// depth (the full render keeps the first drawn, the composite the lower object index).
// Blended surfaces are laid over the opaque composite back to front with the blend unit's own
// 8-bit arithmetic: a layer holds its blended surfaces pre-blended over transparent black
// (premultiplied color and coverage) and, where several of its fragments cover a pixel, their
// stack, blended fragment by fragment where another object's opaque surface passes between
// them (docs/renderer.md "Layers and blending" states what is exact and the bound).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "scenes/scene.hpp"

namespace lodopt::renderer {

// Rendering failures (no context, out of memory, a GL error): a runtime error, exit code 1.
class RenderError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// How surfaces are lit (docs/renderer.md "Shading"). Pbr is the default: what an engine shows.
enum class Shading : std::uint8_t {
    // The papers' shading: base color x (ambient + (1 - ambient) max(n.l, 0)), two-sided, no
    // other material property; byte-identical to lodopt's figures measured with it.
    Lambert,
    // glTF 2.0 metallic-roughness as an engine draws it: every material property, alpha modes,
    // back-face culling, the light rig below, PBR Neutral tone mapping, sRGB output.
    Pbr,
};
inline constexpr Shading kDefaultShading = Shading::Pbr;
// "lambert" / "pbr"; parseShading throws std::invalid_argument on anything else.
const char* shadingName(Shading shading);
Shading parseShading(const std::string& name);

// Which platform a Renderer built from settings alone draws on: OSMesa (the default: the images
// the metrics score are llvmpipe's, deterministic) or EGL (the user's GPU; docs/renderer.md).
enum class Backend { OsMesa, Egl };

// What a frame's time is read from (docs/renderer.md "Timing"). Wall: the steady clock around
// draw + glFinish, what the CPU waits for the frame. GpuTimer: a GL_TIME_ELAPSED query around
// the draw, the GPU's own time for it. Auto: GpuTimer where the driver's timer has counter bits
// and draws on a GPU; Wall on software rasterizers (llvmpipe's timer ends when the draw is
// queued, before its threads rasterize: 0.01-0.06 ms for 3-15 ms frames) and where it has none.
enum class FrameClock { Auto, Wall, GpuTimer };
const char* frameClockName(FrameClock clock);        // "auto", "wall", "gpu"
FrameClock parseFrameClock(const std::string& name);  // throws RenderError for another name
// llvmpipe, softpipe, SwiftShader, Mesa's "Software Rasterizer": GL_RENDERER names a CPU rasterizer.
bool isSoftwareRasterizer(const std::string& glRenderer);

// One batch of timed draws of one frame, each draw's time in milliseconds. Every lodopt command
// that times a frame (calibrate, render --time, schedule --render, bench) takes it from here.
struct FrameTimes {
    FrameClock clock = FrameClock::Wall;  // resolved: which list is the frame's time
    std::vector<double> wallMs;           // steady clock around draw + glFinish
    std::vector<double> gpuMs;            // GL_TIME_ELAPSED of the draw; empty without timer queries
    std::vector<double> cpuMs;            // process CPU time (every thread) over the same span
    const std::vector<double>& frameMs() const { return clock == FrameClock::GpuTimer ? gpuMs : wallMs; }
    // The median of frameMs(), the mean of the middle two for an even count: the frame time every
    // device profile predicts (docs/timemodel.md "What a profile predicts"). 0 with no draw.
    double median() const;
    double least() const;  // of frameMs(); 0 with no draw
};

struct RenderSettings {
    int width = 512;   // pixels, 1..16384
    int height = 512;  // pixels, 1..16384
    Shading shading = kDefaultShading;
    glm::vec3 lightDirection{-0.4f, -1.0f, -0.3f};  // world space, towards the scene
    float ambient = 0.3f;                           // Lambert: 0..1 share of unlit color
    // PBR light rig: the key light's irradiance on a surface facing it (linear, white), and a
    // hemisphere ambient (irradiance from straight up / straight down, blended by n.y; diffuse
    // only, no image-based specular).
    float keyIlluminance = 2.5f;
    glm::vec3 skyIrradiance{1.0f};
    glm::vec3 groundIrradiance{0.3f};
    // Sky; exact multiples of 1/255 so the cleared bytes are (158, 194, 230, 255) everywhere.
    glm::vec4 clearColor{158.0f / 255.0f, 194.0f / 255.0f, 230.0f / 255.0f, 1.0f};
    Backend backend = Backend::OsMesa;  // the platform Renderer(scene, settings) creates
    FrameClock frameClock = FrameClock::Auto;  // what timeFrames reads a frame's time from
};

// A rendered image: RGBA8 rows top to bottom, and window-space depth in [0, 1] per pixel
// (1 = nothing drawn), same layout.
struct Frame {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;
    std::vector<float> depth;
};

// Pixel rectangle [x0, x1) x [y0, y1), top-left origin. Empty when x0 >= x1 or y0 >= y1.
struct PixelRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool empty() const { return x0 >= x1 || y0 >= y1; }
    int width() const { return empty() ? 0 : x1 - x0; }
    int height() const { return empty() ? 0 : y1 - y0; }
};

// One row's columns [x0, x1); empty when x0 >= x1.
struct RowSpan {
    int x0 = 0, x1 = 0;
    bool empty() const { return x0 >= x1; }
};

// One object at one level rendered alone, cropped to the pixels it covers.
struct Layer {
    int object = -1;
    int level = -1;
    PixelRect rect;                  // covered pixels' bounding rectangle in the frame
    std::vector<std::uint8_t> rgba;  // rect.width() * rect.height() * 4
    std::vector<float> depth;        // rect.width() * rect.height(), 1 = not covered
    std::uint64_t coveredPixels = 0;
    // Per row of `rect`, the columns from the first to the last covered pixel (frame
    // coordinates; coveredRowSpans). Compositing skips the rest of the row. Empty: not known,
    // whole rows are composited (the same result, slower).
    std::vector<RowSpan> rowSpans;

    // Blended surfaces (glTF alphaMode BLEND under Shading::Pbr); all empty when the level has
    // none. Then `depth` is the nearest depth of any of its fragments (what the layer covers),
    // `opaqueDepth` that of its opaque and masked surfaces alone (what it hides others behind:
    // blended surfaces write no depth), `rgba` the opaque surfaces' color, and `blendRgba` the
    // blended surfaces drawn over transparent black in front of the object's own opaque ones:
    // color premultiplied by coverage, coverage in alpha. `blendDistance` is the full render's
    // back-to-front key (farther first, ties to the lower object index).
    std::vector<std::uint8_t> blendRgba;
    std::vector<float> opaqueDepth;
    float blendDistance = 0.0f;
    // Per pixel of `rect`, the farthest blended fragment's depth (1 = none). Where it differs
    // from the nearest (`depth`), several fragments cover the pixel and an opaque surface of
    // another object may pass between them; then the composite blends the ones in front of it
    // from the pixel's fragment stack: each fragment's depth and color as the shader wrote
    // it, in draw order.
    std::vector<float> blendFarthest;
    struct BlendFragment {
        float depth = 1.0f;
        std::uint8_t rgba[4] = {};
        bool operator==(const BlendFragment&) const = default;
    };
    std::vector<std::uint32_t> stackPixels;  // ascending pixel indices (row-major in `rect`)
    std::vector<std::uint32_t> stackStarts;  // stackPixels.size() + 1 offsets into stackFragments
    std::vector<BlendFragment> stackFragments;
    bool blends() const { return !blendRgba.empty(); }
    // Per pixel of `rect`, the depth behind which this layer hides other objects (1 = none).
    const std::vector<float>& occluderDepth() const { return blends() ? opaqueDepth : depth; }
};

// Backend behind the Renderer (Filament-style): creates and makes current a GL context with
// OpenGL 3.3 core or later. A Renderer owns its platform; tests and other backends inject one.
class Platform {
public:
    virtual ~Platform() = default;
    virtual void makeCurrent() = 0;
    virtual std::string description() const = 0;  // e.g. "OSMesa 22.3.6 llvmpipe"
    // The OpenGL function `name` of this platform's context (null when it has none): the
    // renderer calls GL through a table loaded from here, not through linked symbols.
    virtual void* getProcAddress(const char* name) const = 0;
};
// OSMesa with an OpenGL 3.3+ core-profile context. Throws RenderError when it cannot.
std::unique_ptr<Platform> createOsMesaPlatform();
// EGL without a window: a GPU's driver through EGL_EXT_platform_device (NVIDIA, AMD, Intel;
// Mesa's software device too), else Mesa's surfaceless platform; an OpenGL 4.3+ core-profile
// context. Throws RenderError saying what is missing (libEGL, a device, OpenGL 4.3 core).
std::unique_ptr<Platform> createEglPlatform();

const char* backendName(Backend backend);                // "osmesa", "egl"
Backend parseBackend(const std::string& name);           // throws RenderError for another name
std::unique_ptr<Platform> createPlatform(Backend backend);

class Renderer {
public:
    // Uploads every level of every object. `scene` must outlive the renderer. The first form
    // renders on createPlatform(settings.backend); the second on `platform` (not null: RenderError).
    Renderer(const scenes::Scene& scene, RenderSettings settings = {});
    Renderer(const scenes::Scene& scene, RenderSettings settings, std::unique_ptr<Platform> platform);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    const RenderSettings& settings() const;
    // GL_VENDOR / GL_RENDERER / GL_VERSION of the context.
    std::string glRendererString() const;
    std::string glVersionString() const;
    std::string platformDescription() const;  // Platform::description()

    // Draws `combination` (validated) from `camera` into `out` (resized as needed).
    void render(const scenes::Combination& combination, const scenes::Camera& camera, Frame& out);
    Frame render(const scenes::Combination& combination, const scenes::Camera& camera);
    // Draws without reading pixels back, then glFinish: for timing only.
    void drawAndFinish(const scenes::Combination& combination, const scenes::Camera& camera);
    // `warmup` untimed draws, then `repeats` (>= 1) timed ones, each draw + glFinish: wall time,
    // process CPU time and, where the driver has timer queries, GL_TIME_ELAPSED, all recorded;
    // FrameTimes::clock says which is the frame's time (settings().frameClock resolved).
    FrameTimes timeFrames(const scenes::Combination& combination, const scenes::Camera& camera, int repeats,
                          int warmup);
    // settings().frameClock resolved for this context (never Auto).
    FrameClock frameClock() const;
    // Whether the context has GL_TIME_ELAPSED queries with counter bits (gpuMs is recorded).
    bool hasTimerQueries() const;

    Layer renderLayer(int object, int level, const scenes::Camera& camera);

private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

// Composites one layer per drawn object (nullptr = not drawn) into `out` by nearest depth,
// ties to the lower object index; background is `clearColor`; then the blended layers back to
// front where their nearest fragment is in front of the opaque composite. `out` is resized as
// needed; its depth is the opaque surfaces' (as the full render's).
void composite(const std::vector<const Layer*>& layers, int width, int height, glm::vec4 clearColor, Frame& out);
// Recomposites only `rect` of `out` (which already holds a composite of the same size).
void compositeRect(const std::vector<const Layer*>& layers, PixelRect rect, glm::vec4 clearColor, Frame& out);
// Per row of `layer.rect`, top to bottom, the columns from its first to its last covered
// pixel (depth < 1), in frame coordinates: where a level change of that layer can act.
std::vector<RowSpan> coveredRowSpans(const Layer& layer);

// How compositeSpansChanges reports changed pixels: per band of `bandRows` rows, one tight
// rectangle per cluster of changed columns, clusters at least `splitGap` unchanged columns
// apart reported apart (each rectangle costs its consumer a fixed overhead plus a margin).
struct ChangeGrid {
    int bandRows = 8;   // 1..32
    int splitGap = 32;  // >= 1
};
// Recomposites rows [top, top + spans.size()) of `out`, row top + i over spans[i] (clipped to
// the frame), like compositeRect, and says where the color changed so that callers can skip
// the pixels that did not: the rows are cut into bands of grid.bandRows from `top`; for each
// band in which some pixel's RGBA differs from what `out` held before, the tight bounding
// rectangle of each cluster of changed columns (see ChangeGrid) is appended to `changed`, bands
// top to bottom, clusters left to right. Together they cover every pixel whose color changed.
// Depth is written as compositeRect writes it, but a depth-only change is not reported.
// Reusable buffers of compositeSpansChanges, so that a caller in a loop (the fast evaluation
// path, once per candidate) allocates nothing after the first call.
struct CompositeScratch {
    std::vector<const Layer*> reaching;  // the layers that reach the recomposited rows
    std::vector<const Layer*> blended;   // those of them that blend, back to front
    std::vector<std::uint32_t> columns;  // per frame column, the current band's changed rows
};
void compositeSpansChanges(const std::vector<const Layer*>& layers, int top, std::span<const RowSpan> spans,
                           glm::vec4 clearColor, ChangeGrid grid, Frame& out, std::vector<PixelRect>& changed,
                           CompositeScratch& scratch);
// The same with buffers of its own.
void compositeSpansChanges(const std::vector<const Layer*>& layers, int top, std::span<const RowSpan> spans,
                           glm::vec4 clearColor, ChangeGrid grid, Frame& out, std::vector<PixelRect>& changed);
// compositeSpansChanges over a whole rectangle.
void compositeRectChanges(const std::vector<const Layer*>& layers, PixelRect rect, glm::vec4 clearColor, ChangeGrid grid,
                          Frame& out, std::vector<PixelRect>& changed);

// The clear color as the renderer writes it (RGBA8).
void clearColorBytes(glm::vec4 clearColor, std::uint8_t out[4]);

// Image files, written atomically (docs/renderer.md "Image files"). Color: the type from the
// extension, .png (RGBA; also without extension), .jpg/.jpeg (RGB, quality 95) or .ppm (RGB).
// Depth: .exr (one float channel "Z") or .pfm. Another extension throws RenderError before
// anything is written; the ...TypeError functions say so without writing (empty: supported),
// for a command to refuse its arguments before it starts.
void writeColorImage(const std::string& path, const Frame& frame);
void writeDepthImage(const std::string& path, const Frame& frame);
std::string colorImageTypeError(const std::string& path);
std::string depthImageTypeError(const std::string& path);
// Reads an 8-bit image: PNG (any bit depth, palette, interlace), JPEG (gray or RGB) or binary
// PNM (P5, P6), told apart by their first bytes; 16-bit samples are scaled to 8 bits.
// `channels` is 1 (gray; gray + alpha drops the alpha), 3 or 4 as stored. Throws RenderError.
struct LoadedImage {
    int width = 0, height = 0, channels = 0;
    std::vector<std::uint8_t> pixels;
};
LoadedImage readImage(const std::string& path);

}  // namespace lodopt::renderer
