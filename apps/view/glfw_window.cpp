#include "glfw_window.h"

#include <GLFW/glfw3.h>

#include "util/error.h"

namespace subdfit::view {
namespace {

// GLFW reports why a call failed through a callback, not through the call's result.
std::string lastGlfwError;

void recordGlfwError(int, const char* description) { lastGlfwError = description; }

std::string glfwReason() { return lastGlfwError.empty() ? "unknown GLFW error" : lastGlfwError; }

}  // namespace

GlfwWindow::GlfwWindow(int width, int height, const std::string& title) {
    glfwSetErrorCallback(recordGlfwError);
    if (!glfwInit()) throw Error("cannot open a window: " + glfwReason());
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    // The screenshot reads the back buffer after the frame is drawn; no multisampling so that
    // what is read is exactly what the composite pass wrote.
    glfwWindowHint(GLFW_SAMPLES, 0);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) {
        const std::string reason = glfwReason();
        glfwTerminate();
        throw Error("cannot open a GL 4.5 core window: " + reason);
    }
    makeCurrent();
    glfwSwapInterval(1);
    try {
        context::loadGl(*this);
    } catch (...) {
        glfwDestroyWindow(window_);
        glfwTerminate();
        throw;
    }
}

GlfwWindow::~GlfwWindow() {
    glfwDestroyWindow(window_);
    glfwTerminate();
}

void GlfwWindow::makeCurrent() { glfwMakeContextCurrent(window_); }

context::GlProc GlfwWindow::getProcAddress(const char* name) { return glfwGetProcAddress(name); }

bool GlfwWindow::shouldClose() const { return glfwWindowShouldClose(window_); }

void GlfwWindow::framebufferSize(int& width, int& height) const { glfwGetFramebufferSize(window_, &width, &height); }

void GlfwWindow::swapBuffers() { glfwSwapBuffers(window_); }

}  // namespace subdfit::view
