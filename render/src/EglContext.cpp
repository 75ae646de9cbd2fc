#include "throng/render/EglContext.h"

#include <cstring>
#include <stdexcept>
#include <string>

#include <glad/gl.h>
// EGL's headers after glad's: they declare no GL functions of their own.
#include <EGL/egl.h>
#include <EGL/eglext.h>

namespace throng {
namespace {

// The extension entry points, looked up once (null when the EGL library lacks them).
struct DeviceFunctions {
    PFNEGLQUERYDEVICESEXTPROC queryDevices = nullptr;
    PFNEGLQUERYDEVICESTRINGEXTPROC queryDeviceString = nullptr;
    PFNEGLGETPLATFORMDISPLAYEXTPROC platformDisplay = nullptr;
};

const DeviceFunctions& functions() {
    static const DeviceFunctions f = [] {
        DeviceFunctions d;
        d.queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
        d.queryDeviceString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
        d.platformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
        return d;
    }();
    return f;
}

bool clientExtension(const char* name) {
    const char* all = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!all) return false;
    const std::string list = std::string(" ") + all + " ";
    return list.find(std::string(" ") + name + " ") != std::string::npos;
}

std::string eglErrorName(EGLint error) {
    switch (error) {
        case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
        case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
        case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
        case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
        case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
        default: return "EGL error " + std::to_string(error);
    }
}

// A context of OpenGL 3.3 core on an initialised `display`, current without a surface; null on failure (`why` says).
EGLContext coreContext(EGLDisplay display, std::string& why) {
    if (!eglBindAPI(EGL_OPENGL_API)) {
        why = "the EGL display offers no desktop OpenGL (" + eglErrorName(eglGetError()) + ")";
        return EGL_NO_CONTEXT;
    }
    const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(display, configAttributes, &config, 1, &count) || count == 0) {
        why = "no EGL configuration renders desktop OpenGL";
        return EGL_NO_CONTEXT;
    }
    const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    const EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttributes);
    if (context == EGL_NO_CONTEXT) {
        why = "no OpenGL 3.3 core context (" + eglErrorName(eglGetError()) + ")";
        return EGL_NO_CONTEXT;
    }
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        why = "the context cannot be made current without a surface (" + eglErrorName(eglGetError()) + ")";
        eglDestroyContext(display, context);
        return EGL_NO_CONTEXT;
    }
    return context;
}

}  // namespace

std::vector<EglContext::DeviceInfo> EglContext::devices() {
    std::vector<DeviceInfo> out;
    const DeviceFunctions& f = functions();
    if (!f.queryDevices || !clientExtension("EGL_EXT_device_enumeration")) return out;
    EGLDeviceEXT list[16];
    EGLint n = 0;
    if (!f.queryDevices(16, list, &n)) return out;
    for (EGLint i = 0; i < n; ++i) {
        DeviceInfo d;
        d.index = int(i);
        const char* ext = f.queryDeviceString ? f.queryDeviceString(list[i], EGL_EXTENSIONS) : nullptr;
        d.extensions = ext ? ext : "";
        d.software = d.extensions.find("EGL_MESA_device_software") != std::string::npos;
        if (d.extensions.find("EGL_EXT_device_drm") != std::string::npos && f.queryDeviceString)
            if (const char* file = f.queryDeviceString(list[i], EGL_DRM_DEVICE_FILE_EXT)) d.drmFile = file;
        if (d.extensions.find("EGL_EXT_device_query_name") != std::string::npos && f.queryDeviceString) {
            if (const char* v = f.queryDeviceString(list[i], EGL_VENDOR)) d.vendor = v;
            if (const char* r = f.queryDeviceString(list[i], EGL_RENDERER_EXT)) d.renderer = r;
        }
        out.push_back(d);
    }
    return out;
}

bool EglContext::hardwareDevicePresent() {
    for (const DeviceInfo& d : devices())
        if (!d.software) return true;
    return false;
}

EglContext::EglContext(int width, int height, Platform platform) : HeadlessContext("EglContext"), platform_(platform) {
    checkSize(width, height);
    const DeviceFunctions& f = functions();
    if (!f.platformDisplay)
        throw std::runtime_error("EglContext: the EGL library offers no eglGetPlatformDisplayEXT (is an EGL driver installed? "
                                 "Debian: libegl1 and libegl-mesa0)");
    std::string why;
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    if (platform == Platform::Device) {
        if (!clientExtension("EGL_EXT_platform_device") || !f.queryDevices)
            throw std::runtime_error("EglContext: EGL has no device platform (EGL_EXT_platform_device)");
        EGLDeviceEXT list[16];
        EGLint n = 0;
        f.queryDevices(16, list, &n);
        const std::vector<DeviceInfo> listed = devices();
        for (EGLint i = 0; i < n && context == EGL_NO_CONTEXT; ++i) {
            if (std::size_t(i) < listed.size() && listed[std::size_t(i)].software) continue;
            display = f.platformDisplay(EGL_PLATFORM_DEVICE_EXT, list[i], nullptr);
            if (display == EGL_NO_DISPLAY || !eglInitialize(display, nullptr, nullptr)) {
                why = "device " + std::to_string(i) + " cannot be initialised";
                continue;
            }
            context = coreContext(display, why);
        }
        if (context == EGL_NO_CONTEXT)
            throw std::runtime_error("EglContext: no EGL device with OpenGL 3.3 core" + (why.empty() ? std::string(" (no hardware device listed)") : " (" + why + ")"));
    } else {
        if (!clientExtension("EGL_MESA_platform_surfaceless"))
            throw std::runtime_error("EglContext: EGL has no surfaceless platform (EGL_MESA_platform_surfaceless: Mesa's EGL driver, "
                                     "Debian libegl-mesa0, is missing)");
        display = f.platformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (display == EGL_NO_DISPLAY || !eglInitialize(display, nullptr, nullptr))
            throw std::runtime_error("EglContext: the surfaceless EGL display cannot be initialised (" + eglErrorName(eglGetError()) + ")");
        context = coreContext(display, why);
        if (context == EGL_NO_CONTEXT) throw std::runtime_error("EglContext: surfaceless: " + why);
    }
    display_ = display;
    context_ = context;
    try {
        loadFunctions(reinterpret_cast<ProcLoader>(&eglGetProcAddress),
                      platform == Platform::Device ? "EGL device (headless)" : "EGL surfaceless (headless)");
        createFramebuffer(width, height);
    } catch (...) {
        destroyFramebuffer();
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display, context);
        throw;
    }
}

EglContext::~EglContext() {
    // GL objects can only be deleted with the context current; destroying the context frees them anyway.
    if (eglGetCurrentContext() == context_ || eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) destroyFramebuffer();
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    // The display is not terminated: EGL hands every context of a platform the same display, and
    // terminating it would end the others' too.
}

void EglContext::makeCurrent() {
    if (eglGetCurrentContext() == context_) return;
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
        throw std::runtime_error("EglContext: eglMakeCurrent failed (" + eglErrorName(eglGetError()) + ")");
}

}  // namespace throng
