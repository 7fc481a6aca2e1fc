#include "examples/peer/osmesa_context.h"

#include <GL/osmesa.h>

#include <cstdlib>
#include <string>

#include "raster/core/error.h"

namespace tessera::peer {

OsMesaContext::OsMesaContext(int raster_threads) {
    // OSMesa picks its gallium driver from GALLIUM_DRIVER; the peer is llvmpipe by definition,
    // so softpipe (a slow reference driver) must not be picked up from the environment.
    setenv("GALLIUM_DRIVER", "llvmpipe", 1);
    if (raster_threads > 0) setenv("LP_NUM_THREADS", std::to_string(raster_threads).c_str(), 1);

    const int core_attributes[] = {OSMESA_FORMAT,        OSMESA_RGBA,
                                   OSMESA_DEPTH_BITS,    0,
                                   OSMESA_PROFILE,       OSMESA_CORE_PROFILE,
                                   OSMESA_CONTEXT_MAJOR_VERSION, 3,
                                   OSMESA_CONTEXT_MINOR_VERSION, 3,
                                   0};
    context_ = OSMesaCreateContextAttribs(core_attributes, nullptr);
    core_profile_ = context_ != nullptr;
    if (!context_) context_ = OSMesaCreateContextExt(OSMESA_RGBA, 0, 0, 0, nullptr);
    if (!context_) throw Error("llvmpipe: OSMesa could not create an OpenGL context");
    if (!OSMesaMakeCurrent(context_, window_, GL_UNSIGNED_BYTE, 1, 1)) {
        OSMesaDestroyContext(context_);
        throw Error("llvmpipe: OSMesa could not make its OpenGL context current");
    }
}

OsMesaContext::~OsMesaContext() { OSMesaDestroyContext(context_); }

static std::string gl_string(GLenum name) {
    const auto* text = reinterpret_cast<const char*>(glGetString(name));
    return text ? text : "unknown";
}

std::string OsMesaContext::renderer() const { return gl_string(GL_RENDERER); }
std::string OsMesaContext::version() const { return gl_string(GL_VERSION); }

}  // namespace tessera::peer
