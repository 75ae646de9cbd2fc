#pragma once
// A headless GL context through EGL: OpenGL 3.3 core on a GPU found without any X server (the EGL
// device platform, EGL_EXT_platform_device) or on Mesa's surfaceless platform (software, llvmpipe:
// what this machine and CI have). It draws into a framebuffer object as OsMesaContext does.

#include <string>
#include <vector>

#include "throng/render/HeadlessContext.h"

namespace throng {

/// Off-screen OpenGL core context made through EGL, rendering into an RGBA8 + depth framebuffer object.
class EglContext final : public HeadlessContext {
public:
    /// Where the context comes from.
    enum class Platform {
        Device,       ///< a hardware EGL device (a GPU), the first one that gives OpenGL 3.3 core
        Surfaceless,  ///< Mesa's surfaceless platform (its software rasteriser without a GPU)
    };

    /// One EGL device as the device platform lists it.
    struct DeviceInfo {
        int index = 0;          ///< in eglQueryDevicesEXT's order
        bool software = false;  ///< Mesa's software device (EGL_MESA_device_software)
        std::string drmFile;    ///< its DRM node (/dev/dri/cardN), or empty
        std::string vendor;     ///< the driver's vendor (EGL_EXT_device_query_name), or empty
        std::string renderer;   ///< the device's name (EGL_EXT_device_query_name), or empty
        std::string extensions; ///< the device's extension string
    };

    /// Creates a core-profile context (3.3 or later) on `platform` with a `width` x `height`
    /// framebuffer and makes it current. Throws std::invalid_argument for a bad size and
    /// std::runtime_error saying what is missing (no EGL library or driver, no hardware device, no
    /// OpenGL 3.3 core) otherwise.
    EglContext(int width, int height, Platform platform);
    ~EglContext() override;

    void makeCurrent() override;
    /// The platform it was made on.
    Platform platform() const { return platform_; }

    /// The EGL devices the device platform lists (empty when EGL or the extension is missing).
    static std::vector<DeviceInfo> devices();
    /// Whether a hardware (not software) EGL device is listed.
    static bool hardwareDevicePresent();

private:
    Platform platform_;
    void* display_ = nullptr;  // EGLDisplay, EGLContext: kept opaque so EGL's headers stay private
    void* context_ = nullptr;
};

}  // namespace throng
