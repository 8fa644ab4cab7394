#include "viewer.h"

#include <chrono>
#include <cstdio>
#include <memory>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "cage_wireframe.h"
#include "control_panel.h"
#include "glfw_window.h"
#include "imgui_layer.h"
#include "orbit_camera.h"
#include "screenshot.h"
#include "util/error.h"
#include "view_renderer.h"

namespace subdfit::view {
namespace {

using Clock = std::chrono::steady_clock;

constexpr float kPanelWidth = 360.0f;  // window coordinates

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

class Viewer {
public:
    Viewer(const ViewerOptions& options, FitInputs inputs)
        : options_(options),
          window_(options.width, options.height, "subdfit-view"),
          imgui_(window_.handle()),
          session_(std::make_unique<FitSession>(options.fit, std::move(inputs))),
          wireframe_(std::make_unique<CageWireframe>(session_->scene().cage)) {
        panel_.view.mode = options.mode;
        panel_.view.cageWireframe = options.cageWireframe;
        panel_.playing = !options.paused;
        panel_.tessLevel = options.fit.tessLevel;
        panel_.outPath = options.fit.out.string();
        panel_.cagePath = options.fit.cage.string();
        panel_.referencePath = options.fit.reference.string();
    }

    void run() {
        for (int frame = 1; !window_.shouldClose(); ++frame) {
            const bool last = options_.frames > 0 && frame >= options_.frames;
            drawFrame(last && !options_.screenshot.empty());
            if (last) break;
        }
        if (options_.saveOnExit) {
            session_->save(window_, panel_.outPath);
            std::printf("%s\n", (std::filesystem::path(panel_.outPath) / "report.json").string().c_str());
        }
    }

private:
    void drawFrame(bool screenshot) {
        glfwPollEvents();
        imgui_.beginFrame();
        const ImGuiIO& io = ImGui::GetIO();
        int width = 0, height = 0;
        window_.framebufferSize(width, height);
        // The view fills the window right of the panel; the panel is sized in window units.
        const int panelPixels = std::min(width, int(kPanelWidth * io.DisplayFramebufferScale.x));
        const glm::ivec2 origin(panelPixels, 0), size(width - panelPixels, height);

        // Steps first, so that the panel shows the state the view will show.
        if (panel_.playing) stepWithinBudget();
        const PanelRequests requests = drawControlPanel(panel_, *session_, kPanelWidth, io.DisplaySize.y);
        handleMouse(io, float(size.y));
        carryOut(requests);

        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, width, height);
        glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        const float aspect = float(std::max(1, size.x)) / float(std::max(1, size.y));
        renderer_.draw(*session_, *wireframe_, camera_.camera(aspect), panel_.view, origin, size);
        glViewport(0, 0, width, height);
        imgui_.render();
        if (screenshot) writeScreenshot(options_.screenshot, width, height);
        window_.swapBuffers();
    }

    void handleMouse(const ImGuiIO& io, float viewHeight) {
        if (io.WantCaptureMouse) return;  // over the panel, or dragging one of its widgets
        const glm::vec2 delta(io.MouseDelta.x, io.MouseDelta.y);
        // Only buttons held since an earlier frame drag: the press frame's delta is the jump
        // from wherever the pointer was before (e.g. the panel), not a drag.
        auto dragging = [&](int button) { return io.MouseDown[button] && io.MouseDownDuration[button] > 0.0f; };
        if (delta == glm::vec2(0.0f)) {
            // no drag this frame
        } else if (dragging(ImGuiMouseButton_Left)) {
            camera_.orbit(delta);
        } else if (dragging(ImGuiMouseButton_Right) || dragging(ImGuiMouseButton_Middle)) {
            camera_.pan(delta * io.DisplayFramebufferScale.y, viewHeight);
        }
        if (io.MouseWheel != 0.0f) camera_.zoom(io.MouseWheel);
    }

    // Whole steps until the budget is spent: a step's cost is measured to its end (its loss
    // readback waits for the GPU), so the frame's stall is bounded by the budget plus one step.
    void stepWithinBudget() {
        const auto began = Clock::now();
        int steps = 0;
        if (!session_->anythingOptimised()) return;
        do {
            session_->step();
            ++steps;
            if (session_->stepsTaken() == session_->options().steps) panel_.playing = false;  // as `subdfit fit` would stop
        } while (panel_.playing && millisecondsSince(began) < options_.stepBudgetMs);
        const double seconds = millisecondsSince(began) / 1000.0;
        // Smoothed over about a second of frames, for a steady readout.
        panel_.stepsPerSecond += 0.05f * (float(double(steps) / std::max(seconds, 1e-6)) - panel_.stepsPerSecond);
    }

    void carryOut(const PanelRequests& requests) {
        if (requests.resetCamera) camera_.reset();
        if (requests.step) session_->step();
        tryAction([&] {
            if (requests.applyTessLevel) {
                session_->setTessLevel(panel_.tessLevel);
                setStatus("tessellation " + std::to_string(panel_.tessLevel) + " asked, " +
                              std::to_string(session_->fitter().renderer().tessLevel()) + " rendered (crack-free for this cage)",
                          false);
            }
            if (requests.save) {
                const auto report = session_->save(window_, panel_.outPath);
                char line[160];
                std::snprintf(line, sizeof line, "saved step %d to %s (held-out PSNR %.2f dB)", report["steps"].get<int>(),
                              panel_.outPath.c_str(), report["psnr_holdout"].get<double>());
                setStatus(line, false);
            }
            if (requests.load) load();
        });
    }

    // A new session on other inputs, same settings; the current one stays if it fails.
    void load() {
        fit::FitOptions options = session_->options();
        options.cage = panel_.cagePath;
        options.reference = panel_.referencePath;
        options.resume = false;
        auto session = std::make_unique<FitSession>(options, loadFitInputs(options));
        auto wireframe = std::make_unique<CageWireframe>(session->scene().cage);
        session_ = std::move(session);
        wireframe_ = std::move(wireframe);
        panel_.tessLevel = options.tessLevel;
        panel_.playing = !options_.paused;
        setStatus("loaded " + options.cage.filename().string() + " against " + options.reference.filename().string(), false);
    }

    // Runs a panel action; what goes wrong is shown in the panel, and the viewer carries on.
    template <class Action>
    void tryAction(Action&& action) {
        try {
            action();
        } catch (const std::exception& e) {
            setStatus(e.what(), true);
        }
    }

    void setStatus(std::string text, bool error) {
        panel_.status = std::move(text);
        panel_.statusIsError = error;
    }

    ViewerOptions options_;
    GlfwWindow window_;  // first in, last out: every GL object below dies while its context lives
    ImGuiLayer imgui_;
    std::unique_ptr<FitSession> session_;
    std::unique_ptr<CageWireframe> wireframe_;
    ViewRenderer renderer_;
    OrbitCamera camera_;
    PanelState panel_;
};

}  // namespace

void runViewer(const ViewerOptions& options, FitInputs inputs) {
    if (!viewModeAvailable(options.mode, fit::mapEffectsOf(options.fit, fit::shadingOf(options.fit, inputs.reference)))) {
        const bool appearance = options.mode == ViewMode::BaseColor || options.mode == ViewMode::MetallicRoughness;
        throw Error(std::string("invalid option: --mode: the ") + viewModeName(options.mode) + " view needs " +
                    (appearance ? "a reference whose material has it" : "--maps with that map"));
    }
    Viewer(options, std::move(inputs)).run();
}

}  // namespace subdfit::view
