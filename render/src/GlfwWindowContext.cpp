#include "throng/render/GlfwWindowContext.h"

#include <mutex>
#include <stdexcept>

#include <glad/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace throng {
namespace {

// GLFW is process-global: it is initialised with the first window and terminated with the last.
std::mutex glfwMutex;
int glfwUsers = 0;
std::string glfwLastError;  // guarded by glfwMutex while a window is being created

void recordError(int code, const char* description) {
    glfwLastError = std::string(description ? description : "unknown error") + " (GLFW error " +
                    std::to_string(code) + ")";
}

std::string takeError() {
    std::string e = glfwLastError.empty() ? std::string("no reason given") : glfwLastError;
    glfwLastError.clear();
    return e;
}

void checkSize(int width, int height, const char* where) {
    if (width <= 0 || height <= 0)
        throw std::invalid_argument(std::string(where) + ": size " + std::to_string(width) + " x " +
                                    std::to_string(height) + " must be positive");
}

}  // namespace

GlfwWindowContext::GlfwWindowContext(int width, int height, const std::string& title, bool visible, bool vsync) {
    checkSize(width, height, "GlfwWindowContext");
    std::lock_guard lock(glfwMutex);
    glfwSetErrorCallback(&recordError);
    if (glfwUsers == 0 && !glfwInit())
        throw std::runtime_error("GlfwWindowContext: glfwInit failed: " + takeError());
    ++glfwUsers;
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_DEPTH_BITS, 24);
    glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) {
        const std::string reason = takeError();
        if (--glfwUsers == 0) glfwTerminate();
        throw std::runtime_error("GlfwWindowContext: could not create a " + std::to_string(width) + " x " +
                                 std::to_string(height) + " window with an OpenGL 3.3 core context: " + reason);
    }
    try {
        glfwMakeContextCurrent(window_);
        glfwSwapInterval(vsync ? 1 : 0);
        loadFunctions(&glfwGetProcAddress, "GLFW (window)");
    } catch (...) {
        glfwDestroyWindow(window_);
        if (--glfwUsers == 0) glfwTerminate();
        throw;
    }
}

GlfwWindowContext::~GlfwWindowContext() {
    std::lock_guard lock(glfwMutex);
    if (glfwGetCurrentContext() == window_) glfwMakeContextCurrent(nullptr);
    glfwDestroyWindow(window_);
    if (--glfwUsers == 0) glfwTerminate();
}

void GlfwWindowContext::makeCurrent() {
    // Always, not only when GLFW thinks another context is current: another GL user in the process
    // (VTK's render windows) makes its own context current behind GLFW's back, and GLFW's record
    // would then send our GL calls to that context. GLX returns at once when nothing changes.
    glfwMakeContextCurrent(window_);
}

int GlfwWindowContext::width() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return w;
}

int GlfwWindowContext::height() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return h;
}

void GlfwWindowContext::resize(int width, int height) {
    checkSize(width, height, "GlfwWindowContext::resize");
    glfwSetWindowSize(window_, width, height);
}

void GlfwWindowContext::present() { glfwSwapBuffers(window_); }

void GlfwWindowContext::pollEvents() { glfwPollEvents(); }

bool GlfwWindowContext::shouldClose() const { return glfwWindowShouldClose(window_) != 0; }

}  // namespace throng
