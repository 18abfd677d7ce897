// Choosing a platform by backend name (renderer.hpp).
#include "renderer/renderer.hpp"

namespace lodopt::renderer {

const char* backendName(Backend backend) {
    return backend == Backend::Egl ? "egl" : "osmesa";
}

Backend parseBackend(const std::string& name) {
    if (name == "osmesa") return Backend::OsMesa;
    if (name == "egl") return Backend::Egl;
    throw RenderError("unknown backend '" + name + "' (osmesa or egl)");
}

std::unique_ptr<Platform> createPlatform(Backend backend) {
    return backend == Backend::Egl ? createEglPlatform() : createOsMesaPlatform();
}


}  // namespace lodopt::renderer
