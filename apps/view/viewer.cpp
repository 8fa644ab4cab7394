#include "viewer.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "cage_wireframe.h"
#include "control_panel.h"
#include "gl/platform_defines.h"
#include "glfw_window.h"
#include "imgui_layer.h"
#include "orbit_camera.h"
#include "result_panel.h"
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

// The maps the columns of a result have, read from the files (no GL).
maps::MapEffects resultEffects(const ResultInputs& result) {
    maps::MapEffects all;
    for (const auto& column : result.columns)
        for (const auto& level : column.levels)
            if (level.asset) all = all | level.asset->maps.kinds();
    return all;
}

int columnNamed(const ResultInputs& result, const std::string& name) {
    for (size_t c = 0; c < result.columns.size(); ++c)
        if (result.columns[c].name == name) return int(c);
    return -1;
}

class Viewer {
public:
    explicit Viewer(const ViewerOptions& options)
        : options_(options),
          window_(options.width, options.height, "subdfit-view"),
          imgui_(window_.handle()),
          resultPrograms_(gl::platformDefines()) {}

    void startFit(const fit::FitOptions& fitOptions, FitInputs inputs) {
        auto session = std::make_unique<FitSession>(fitOptions, std::move(inputs));
        wireframe_ = std::make_unique<CageWireframe>(session->scene().cage);
        session_ = std::move(session);
        panel_.view.mode = options_.mode;
        panel_.view.cageWireframe = options_.cageWireframe;
        panel_.playing = !options_.paused;
        panel_.tessLevel = fitOptions.tessLevel;
        panel_.outPath = fitOptions.out.string();
        panel_.cagePath = fitOptions.cage.string();
        panel_.referencePath = fitOptions.reference.string();
        const auto* maps = session_->fitter().maps();
        if (!viewModeAvailable(panel_.view.mode, maps ? maps->effects() : maps::MapEffects{}))
            panel_.view.mode = ViewMode::Fit;
    }

    void startResult(ResultInputs result) {
        result_ = std::make_unique<ResultInputs>(std::move(result));
        for (const auto& column : result_->columns)
            columns_.push_back(std::make_unique<ResultColumn>(resultPrograms_, column, *result_, options_.tessLevel));
        results_.visible.assign(columns_.size(), 1);
        results_.sideBySide = options_.sideBySide;
        results_.view.mode = options_.mode;
        results_.view.cageWireframe = options_.cageWireframe;
        const int named = columnNamed(*result_, options_.show.empty() ? "subdfit" : options_.show);
        results_.shown = std::max(0, named);
        results_.tessLevel = 0;
        for (auto& column : columns_) results_.tessLevel = std::max(results_.tessLevel, column->tessLevel());
        if (results_.tessLevel == 0) results_.tessLevel = 8;
        const bool reference = result_->columns.front().reference;
        results_.canRefine = reference && result_->folder && columnNamed(*result_, "subdfit") >= 0;
    }

    void run() {
        for (int frame = 1; !window_.shouldClose(); ++frame) {
            const bool last = options_.frames > 0 && frame >= options_.frames;
            drawFrame(last && !options_.screenshot.empty());
            if (last) break;
        }
        if (options_.saveOnExit && session_) {
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

        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, width, height);
        glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        if (session_) fitFrame(io, origin, size);
        else resultFrame(io, origin, size);
        glViewport(0, 0, width, height);
        imgui_.render();
        if (screenshot) writeScreenshot(options_.screenshot, width, height);
        window_.swapBuffers();
    }

    void fitFrame(const ImGuiIO& io, glm::ivec2 origin, glm::ivec2 size) {
        // Steps first, so that the panel shows the state the view will show.
        if (panel_.playing) stepWithinBudget();
        const PanelRequests requests = drawControlPanel(panel_, *session_, kPanelWidth, io.DisplaySize.y);
        handleMouse(io, float(size.y));
        carryOut(requests);
        const float aspect = float(std::max(1, size.x)) / float(std::max(1, size.y));
        auto& fitter = session_->fitter();
        const ViewSource source{.draw = [&](const render::Camera& camera,
                                            const render::RenderTarget& target) { fitter.render(camera, target); },
                                .drawReference =
                                    [&](const render::Camera& camera, const render::RenderTarget& target) {
                                        session_->scene().referenceRenderer.draw(session_->programs(), camera, target);
                                    },
                                .maps = fitter.maps(),
                                .wireframe = wireframe_.get(),
                                .cageVertices = &fitter.vertexGroup().theta};
        renderer_.draw(source, camera_.camera(aspect), panel_.view, origin, size);
    }

    // The visible columns side by side (or the one shown), each with its name and scores on top.
    void resultFrame(const ImGuiIO& io, glm::ivec2 origin, glm::ivec2 size) {
        const ResultPanelRequests requests =
            drawResultPanel(results_, *result_, columns_, kPanelWidth, io.DisplaySize.y);
        handleMouse(io, float(size.y));
        if (!io.WantCaptureKeyboard && !results_.sideBySide) {
            const int count = int(columns_.size());
            if (ImGui::IsKeyPressed(ImGuiKey_RightArrow)) results_.shown = (results_.shown + 1) % count;
            if (ImGui::IsKeyPressed(ImGuiKey_LeftArrow)) results_.shown = (results_.shown + count - 1) % count;
        }
        carryOut(requests);
        if (session_) return;  // refined: the fit takes the window from the next frame on

        std::vector<int> shown;
        for (size_t c = 0; c < columns_.size(); ++c)
            if (results_.sideBySide ? bool(results_.visible[c]) : int(c) == results_.shown) shown.push_back(int(c));
        if (shown.empty()) return;
        ResultColumn* reference = result_->columns.front().reference ? columns_.front().get() : nullptr;
        const float scale = io.DisplayFramebufferScale.x;
        auto* labels = ImGui::GetForegroundDrawList();
        for (size_t k = 0; k < shown.size(); ++k) {
            ResultColumn& column = *columns_[size_t(shown[k])];
            const int left = origin.x + int(k) * size.x / int(shown.size());
            const int right = origin.x + int(k + 1) * size.x / int(shown.size());
            const glm::ivec2 columnSize(right - left, size.y);
            ViewSettings settings = results_.view;
            if (!viewModeAvailable(settings.mode, column.mapEffects())) settings.mode = ViewMode::Fit;
            const float aspect = float(std::max(1, columnSize.x)) / float(std::max(1, columnSize.y));
            renderer_.draw(column.source(reference), camera_.camera(aspect), settings, {left, origin.y}, columnSize);
            const ImVec2 at(float(left) / scale + 8.0f, 8.0f);
            labels->AddText(at, IM_COL32(240, 240, 240, 255), column.inputs().name.c_str());
            labels->AddText(ImVec2(at.x, at.y + ImGui::GetTextLineHeight()), IM_COL32(190, 190, 190, 255),
                            column.inputs().stats.c_str());
            if (k > 0)
                labels->AddLine(ImVec2(float(left) / scale, 0.0f), ImVec2(float(left) / scale, io.DisplaySize.y),
                                IM_COL32(90, 90, 90, 255));
        }
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
            if (session_->stepsTaken() == session_->options().steps)
                panel_.playing = false;  // as `subdfit fit` would stop
        } while (panel_.playing && millisecondsSince(began) < options_.stepBudgetMs);
        const double seconds = millisecondsSince(began) / 1000.0;
        // Smoothed over about a second of frames, for a steady readout.
        panel_.stepsPerSecond += 0.05f * (float(double(steps) / std::max(seconds, 1e-6)) - panel_.stepsPerSecond);
    }

    void carryOut(const PanelRequests& requests) {
        if (requests.resetCamera) camera_.reset();
        if (requests.step) session_->step();
        tryAction(panel_, [&] {
            if (requests.applyTessLevel) {
                session_->setTessLevel(panel_.tessLevel);
                setStatus(panel_,
                          "tessellation " + std::to_string(panel_.tessLevel) + " asked, " +
                              std::to_string(session_->fitter().renderer().tessLevel()) +
                              " rendered (crack-free for this cage)",
                          false);
            }
            if (requests.save) {
                const auto report = session_->save(window_, panel_.outPath);
                char line[160];
                std::snprintf(line, sizeof line, "saved step %d to %s (held-out PSNR %.2f dB)",
                              report["steps"].get<int>(), panel_.outPath.c_str(), report["psnr_holdout"].get<double>());
                setStatus(panel_, line, false);
            }
            if (requests.load) load();
        });
    }

    void carryOut(const ResultPanelRequests& requests) {
        if (requests.resetCamera) camera_.reset();
        tryAction(results_, [&] {
            if (requests.applyTessLevel) {
                for (auto& column : columns_) column->setTessLevel(results_.tessLevel);
                int drawn = 0;
                for (auto& column : columns_) drawn = std::max(drawn, column->tessLevel());
                setStatus(results_,
                          "tessellation " + std::to_string(results_.tessLevel) + " asked, " + std::to_string(drawn) +
                              " drawn (crack-free for each cage)",
                          false);
            }
            if (requests.levelColumn >= 0) columns_[size_t(requests.levelColumn)]->setLevel(requests.level);
            if (requests.refine) {
                fit::FitOptions options = options_.fit;
                FitInputs inputs = refineInputs(*result_, options);
                startFit(options, std::move(inputs));
            }
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
        setStatus(panel_,
                  "loaded " + options.cage.filename().string() + " against " + options.reference.filename().string(),
                  false);
    }

    // Runs a panel action; what goes wrong is shown in the panel, and the viewer carries on.
    template <class Panel, class Action>
    void tryAction(Panel& panel, Action&& action) {
        try {
            action();
        } catch (const std::exception& e) {
            setStatus(panel, e.what(), true);
        }
    }

    template <class Panel>
    static void setStatus(Panel& panel, std::string text, bool error) {
        panel.status = std::move(text);
        panel.statusIsError = error;
    }

    ViewerOptions options_;
    GlfwWindow window_;  // first in, last out: every GL object below dies while its context lives
    ImGuiLayer imgui_;
    ViewRenderer renderer_;
    OrbitCamera camera_;
    // The fit, when one runs.
    std::unique_ptr<FitSession> session_;
    std::unique_ptr<CageWireframe> wireframe_;
    PanelState panel_;
    // The result, when one is shown (and kept while a refinement of it runs); its columns share
    // one program cache.
    gl::ProgramCache resultPrograms_;
    std::unique_ptr<ResultInputs> result_;
    std::vector<std::unique_ptr<ResultColumn>> columns_;
    ResultPanelState results_;
};

}  // namespace

void runViewer(const ViewerOptions& options, FitInputs inputs) {
    if (!viewModeAvailable(options.mode,
                           fit::mapEffectsOf(options.fit, fit::shadingOf(options.fit, inputs.reference)))) {
        const bool appearance = options.mode == ViewMode::BaseColor || options.mode == ViewMode::MetallicRoughness;
        throw Error(std::string("invalid option: --mode: the ") + viewModeName(options.mode) + " view needs " +
                    (appearance ? "a reference whose material has it" : "--maps with that map"));
    }
    Viewer viewer(options);
    viewer.startFit(options.fit, std::move(inputs));
    viewer.run();
}

void checkResultOptions(const ViewerOptions& options, const ResultInputs& result) {
    if (!resultModeAvailable(options.mode, resultEffects(result), result.columns.front().reference))
        throw Error(std::string("invalid option: --mode: the ") + viewModeName(options.mode) + " view needs " +
                    (options.mode == ViewMode::Difference ? "the reference (a result folder whose reference is there)"
                     : options.mode == ViewMode::Target   ? "a fit (the reference is a column of the result view)"
                                                          : "a shipped asset with that map"));
    if (!options.show.empty() && columnNamed(result, options.show) < 0) {
        std::string names;
        for (const auto& column : result.columns) names += (names.empty() ? "" : ", ") + column.name;
        throw Error("invalid option: --show: no column " + options.show + " (there are: " + names + ")");
    }
}

void runViewer(const ViewerOptions& options, ResultInputs result) {
    checkResultOptions(options, result);
    Viewer viewer(options);
    viewer.startResult(std::move(result));
    viewer.run();
}

}  // namespace subdfit::view
