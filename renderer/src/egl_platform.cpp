// EGL backend: an OpenGL core-profile context without a window, on the machine's GPU driver when
// it offers one (EGL_EXT_platform_device: NVIDIA, AMD and Intel drivers; Mesa lists its software
// device there too), else on Mesa's surfaceless platform. The renderer draws into its own
// framebuffer object, so the context needs no surface beyond a 1x1 pbuffer (none with
// EGL_KHR_surfaceless_context).
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <string>
#include <vector>

#include "renderer/renderer.hpp"

namespace lodopt::renderer {
namespace {

std::string eglErrorText(const char* what) {
    char code[16];
    std::snprintf(code, sizeof(code), "0x%04X", unsigned(eglGetError()));
    return std::string("EGL: ") + what + " (error " + code + ")";
}

bool hasExtension(const char* list, const char* name) {
    if (!list) return false;
    const std::string text = std::string(" ") + list + " ";
    return text.find(std::string(" ") + name + " ") != std::string::npos;
}

// The displays to try, in order: every EGL device, then Mesa's surfaceless platform.
std::vector<EGLDisplay> candidateDisplays() {
    std::vector<EGLDisplay> displays;
    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    auto getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!getPlatformDisplay) return displays;
    auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    if (queryDevices && hasExtension(clientExtensions, "EGL_EXT_platform_device")) {
        EGLint count = 0;
        if (queryDevices(0, nullptr, &count) && count > 0) {
            std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
            if (queryDevices(count, devices.data(), &count)) {
                for (EGLint i = 0; i < count; ++i) {
                    const EGLDisplay display = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[std::size_t(i)], nullptr);
                    if (display != EGL_NO_DISPLAY) displays.push_back(display);
                }
            }
        }
    }
    if (hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless")) {
        const EGLDisplay display = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (display != EGL_NO_DISPLAY) displays.push_back(display);
    }
    return displays;
}

class EglPlatform final : public Platform {
public:
    EglPlatform() {
        std::string why = "no EGL device and no surfaceless platform (is libegl-mesa0, or the GPU's EGL driver, "
                          "installed?)";
        for (EGLDisplay display : candidateDisplays()) {
            if (tryDisplay(display, why)) return;
        }
        throw RenderError("EGL: cannot create an OpenGL 4.3 core-profile context: " + why);
    }
    // The display is not terminated: eglGetPlatformDisplay gives every caller the same one, so
    // terminating it would end the other renderers' contexts; it lives until the process exits
    // (and so does the driver it loaded, whose exit-time allocations lsan.supp then names).
    ~EglPlatform() override {
        if (mDisplay == EGL_NO_DISPLAY) return;
        if (eglGetCurrentContext() == mContext) eglMakeCurrent(mDisplay, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (mContext != EGL_NO_CONTEXT) eglDestroyContext(mDisplay, mContext);
        if (mSurface != EGL_NO_SURFACE) eglDestroySurface(mDisplay, mSurface);
    }
    void makeCurrent() override {
        if (eglGetCurrentContext() == mContext) return;
        if (!eglMakeCurrent(mDisplay, mSurface, mSurface, mContext)) {
            throw RenderError(eglErrorText("cannot make the context current"));
        }
    }
    std::string description() const override { return mDescription; }
    void* getProcAddress(const char* name) const override {
        return reinterpret_cast<void*>(eglGetProcAddress(name));
    }

private:
    // Sets up `display` (left initialized when it fails: see the destructor); `why` gets the reason.
    bool tryDisplay(EGLDisplay display, std::string& why) {
        EGLint major = 0, minor = 0;
        if (!eglInitialize(display, &major, &minor)) {
            why = eglErrorText("eglInitialize failed");
            return false;
        }
        const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
        const bool surfaceless = hasExtension(extensions, "EGL_KHR_surfaceless_context");
        const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE,
                                           surfaceless ? 0 : EGL_PBUFFER_BIT, EGL_NONE};
        EGLConfig config = nullptr;
        EGLint configs = 0;
        const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 3,
                                            EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                            EGL_NONE};
        if (!eglBindAPI(EGL_OPENGL_API) || !eglChooseConfig(display, configAttributes, &config, 1, &configs) ||
            configs < 1) {
            why = eglErrorText("no OpenGL config");
            return false;
        }
        const EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttributes);
        if (context == EGL_NO_CONTEXT) {
            why = eglErrorText("no OpenGL 4.3 core-profile context");
            return false;
        }
        EGLSurface surface = EGL_NO_SURFACE;
        if (!surfaceless) {
            const EGLint pbufferAttributes[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
            surface = eglCreatePbufferSurface(display, config, pbufferAttributes);
            if (surface == EGL_NO_SURFACE) {
                why = eglErrorText("no pbuffer surface");
                eglDestroyContext(display, context);
                return false;
            }
        }
        if (!eglMakeCurrent(display, surface, surface, context)) {
            why = eglErrorText("cannot make the context current");
            if (surface != EGL_NO_SURFACE) eglDestroySurface(display, surface);
            eglDestroyContext(display, context);
            return false;
        }
        mDisplay = display;
        mContext = context;
        mSurface = surface;
        const char* vendor = eglQueryString(display, EGL_VENDOR);
        mDescription = "EGL " + std::to_string(major) + "." + std::to_string(minor) + " (" +
                       (vendor ? vendor : "unknown vendor") + (surfaceless ? ", surfaceless" : ", pbuffer") + ")";
        return true;
    }

    EGLDisplay mDisplay = EGL_NO_DISPLAY;
    EGLContext mContext = EGL_NO_CONTEXT;
    EGLSurface mSurface = EGL_NO_SURFACE;
    std::string mDescription;
};

}  // namespace

std::unique_ptr<Platform> createEglPlatform() {
    return std::make_unique<EglPlatform>();
}

}  // namespace lodopt::renderer
