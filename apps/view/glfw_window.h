#pragma once
// The viewer's GL provider: a GLFW window with a GL 4.5 core context, behind the same
// context::GlContext interface as the headless providers. Only the viewer links GLFW.
#include <string>

#include "context/gl_context.h"

struct GLFWwindow;

namespace subdfit::view {

class GlfwWindow : public context::GlContext {
public:
    // Opens the window, makes its context current and loads GL through it (context::loadGl).
    // Throws subdfit::Error with GLFW's own reason (e.g. no display) otherwise.
    GlfwWindow(int width, int height, const std::string& title);
    ~GlfwWindow() override;
    GlfwWindow(const GlfwWindow&) = delete;
    GlfwWindow& operator=(const GlfwWindow&) = delete;

    void makeCurrent() override;
    context::GlProc getProcAddress(const char* name) override;
    std::string providerName() const override { return "glfw"; }

    GLFWwindow* handle() const { return window_; }
    bool shouldClose() const;
    void framebufferSize(int& width, int& height) const;
    void swapBuffers();

private:
    GLFWwindow* window_ = nullptr;
};

}  // namespace subdfit::view
