#include "throng/render/GlContext.h"

#include <stdexcept>

#include <glad/gl.h>

namespace throng {

GlContext::GlContext() : gl_(std::make_unique<GladGLContext>()) {}

GlContext::~GlContext() = default;

GlContext::DrawTarget GlContext::drawTarget() const {
    if (redirect_) return *redirect_;
    return {framebuffer(), originX(), originY(), width(), height()};
}

void GlContext::loadFunctions(ProcLoader loader, const std::string& kind) {
    *gl_ = GladGLContext{};
    const int version = gladLoadGLContext(gl_.get(), loader);
    if (version == 0 || !gl_->GetString)
        throw std::runtime_error(kind + ": could not load the OpenGL functions (glad found no usable context)");
    const int major = GLAD_VERSION_MAJOR(version), minor = GLAD_VERSION_MINOR(version);
    const auto str = [this](GLenum name) {
        const GLubyte* s = gl_->GetString(name);
        return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
    };
    if (major < 3 || (major == 3 && minor < 3))
        throw std::runtime_error(kind + ": OpenGL 3.3 core is required, the context gives " + str(GL_VERSION));
    kind_ = kind, vendor_ = str(GL_VENDOR), renderer_ = str(GL_RENDERER), version_ = str(GL_VERSION);
    description_ = kind + ": " + version_ + ", " + renderer_;
}

}  // namespace throng
