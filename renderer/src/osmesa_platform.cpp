// OSMesa backend: an OpenGL core-profile context rendered in software by llvmpipe.
#include <GL/osmesa.h>

#include <string>
#include <vector>

#include "renderer/renderer.hpp"

namespace lodopt::renderer {
namespace {

class OsMesaPlatform final : public Platform {
public:
    OsMesaPlatform() {
        // 3.3 core is what we need; llvmpipe answers with 4.5 core.
        const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS, 0,
                                  OSMESA_PROFILE, OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 3,
                                  OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
        mContext = OSMesaCreateContextAttribs(attributes, nullptr);
        if (!mContext) {
            throw RenderError("OSMesa: cannot create an OpenGL 3.3 core-profile context (is libosmesa6 installed?)");
        }
        // We draw into our own framebuffer object; the window buffer only has to exist.
        mWindowBuffer.resize(4 * 4);
        makeCurrent();
    }
    ~OsMesaPlatform() override {
        if (mContext) OSMesaDestroyContext(mContext);
    }
    void makeCurrent() override {
        if (OSMesaGetCurrentContext() == mContext) return;
        if (!OSMesaMakeCurrent(mContext, mWindowBuffer.data(), GL_UNSIGNED_BYTE, 2, 2)) {
            throw RenderError("OSMesa: cannot make the context current");
        }
    }
    std::string description() const override { return "OSMesa (Mesa software rasterizer)"; }
    void* getProcAddress(const char* name) const override {
        return reinterpret_cast<void*>(OSMesaGetProcAddress(name));
    }

private:
    OSMesaContext mContext = nullptr;
    std::vector<unsigned char> mWindowBuffer;
};

}  // namespace

std::unique_ptr<Platform> createOsMesaPlatform() {
    return std::make_unique<OsMesaPlatform>();
}

}  // namespace lodopt::renderer
