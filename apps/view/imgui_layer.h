#pragma once
// Dear ImGui on a GLFW window (its GLFW and OpenGL 3 backends), set up and torn down with the
// object. The window and its context must outlive it.
struct GLFWwindow;

namespace subdfit::view {

class ImGuiLayer {
public:
    explicit ImGuiLayer(GLFWwindow* window);
    ~ImGuiLayer();
    ImGuiLayer(const ImGuiLayer&) = delete;
    ImGuiLayer& operator=(const ImGuiLayer&) = delete;

    void beginFrame();
    void render();  // draws the frame's UI into the bound framebuffer
};

}  // namespace subdfit::view
