#include "control_panel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <imgui.h>
#include <imgui_stdlib.h>

namespace subdfit::view {
namespace {

// log10, so that the late, small improvements stay visible next to the first big ones; a long
// run is averaged into at most kCurvePoints bins, so drawing it stays cheap whatever its length.
std::vector<float> lossCurve(const std::vector<float>& losses) {
    constexpr size_t kCurvePoints = 512;
    const size_t bins = std::min(losses.size(), kCurvePoints);
    std::vector<float> curve(bins, 0.0f);
    for (size_t b = 0; b < bins; ++b) {
        const size_t begin = b * losses.size() / bins, end = (b + 1) * losses.size() / bins;
        for (size_t i = begin; i < end; ++i) curve[b] += std::log10(std::max(losses[i], 1e-12f));
        curve[b] /= float(end - begin);
    }
    return curve;
}

void fitControls(PanelState& state, FitSession& session, PanelRequests& requests) {
    const bool canStep = session.anythingOptimised();
    ImGui::BeginDisabled(!canStep);
    if (ImGui::Button(state.playing ? "Pause" : "Play", ImVec2(80, 0))) state.playing = !state.playing;
    ImGui::SameLine();
    ImGui::BeginDisabled(state.playing);
    if (ImGui::Button("Step", ImVec2(80, 0))) requests.step = true;
    ImGui::EndDisabled();
    ImGui::EndDisabled();
    if (!canStep) state.playing = false;
    ImGui::SameLine();
    if (ImGui::Button("Reset view")) requests.resetCamera = true;

    const auto& losses = session.losses();
    ImGui::Text("step %d / %d   %.1f steps/s", session.stepsTaken(), session.options().steps,
                double(state.stepsPerSecond));
    const auto curve = lossCurve(losses);
    char overlay[64];
    std::snprintf(overlay, sizeof overlay, "loss %.3e", losses.empty() ? 0.0 : double(losses.back()));
    ImGui::PlotLines("##loss", curve.data(), int(curve.size()), 0, overlay, FLT_MAX, FLT_MAX,
                     ImVec2(ImGui::GetContentRegionAvail().x, 90));
    ImGui::TextDisabled("mean loss per step, log scale");
}

void groupControls(FitSession& session) {
    auto& fitter = session.fitter();
    for (auto* group : fitter.groups()) {
        // The vertices' knobs are saved as fractions of the cage's mean edge, which must stay below 1.
        const float most = group == &fitter.vertexGroup() ? 0.99f * session.meanEdge() : 0.99f;
        ImGui::PushID(group->name().c_str());
        bool on = fitter.optimised(*group);
        const std::string label = "optimise " + group->name() + " (" + std::to_string(group->count()) + ")";
        if (ImGui::Checkbox(label.c_str(), &on)) fitter.setOptimised(*group, on);
        float epsilon = group->settings().epsilon;
        float learningRate = group->settings().learningRate;
        bool changed = ImGui::SliderFloat("epsilon", &epsilon, 1e-5f, 0.5f, "%.2e", ImGuiSliderFlags_Logarithmic);
        changed |=
            ImGui::SliderFloat("learning rate", &learningRate, 1e-5f, 0.5f, "%.2e", ImGuiSliderFlags_Logarithmic);
        if (changed) fitter.setRates(*group, std::clamp(epsilon, 1e-6f, most), std::clamp(learningRate, 1e-6f, most));
        ImGui::TextDisabled("annealed learning rate now %.2e",
                            double(group->settings().learningRate * fitter.learningRateScale()));
        ImGui::PopID();
    }
}

void viewControls(PanelState& state, FitSession& session, PanelRequests& requests) {
    const auto effects = session.fitter().maps() ? session.fitter().maps()->effects() : maps::MapEffects{};
    for (int m = 0; m < kViewModeCount; ++m) {
        const auto mode = ViewMode(m);
        if (!viewModeAvailable(mode, effects)) continue;
        if (ImGui::RadioButton(viewModeName(mode), state.view.mode == mode)) state.view.mode = mode;
    }
    if (!viewModeAvailable(state.view.mode, effects)) state.view.mode = ViewMode::Fit;
    float& scale = state.scales[size_t(state.view.mode)];
    const auto mode = state.view.mode;
    // Always there (disabled where the mode has no colour map), so the widgets below never move.
    ImGui::BeginDisabled(mode != ViewMode::Difference && mode != ViewMode::Displacement && mode != ViewMode::NormalMap);
    ImGui::SliderFloat("colour gain", &scale, 0.1f, 1000.0f, "%.1f", ImGuiSliderFlags_Logarithmic);
    ImGui::EndDisabled();
    state.view.scale = scale;
    ImGui::Checkbox("cage wireframe", &state.view.cageWireframe);

    ImGui::SliderInt("tessellation", &state.tessLevel, 1, 64);
    ImGui::SameLine();
    ImGui::BeginDisabled(state.tessLevel == session.options().tessLevel);
    if (ImGui::Button("Apply")) requests.applyTessLevel = true;
    ImGui::EndDisabled();
    ImGui::TextDisabled("rendered at %d segments per face edge", session.fitter().renderer().tessLevel());
}

void fileControls(PanelState& state, PanelRequests& requests) {
    ImGui::InputText("out", &state.outPath);
    if (ImGui::Button("Save result")) requests.save = true;
    ImGui::Spacing();
    ImGui::InputText("cage", &state.cagePath);
    ImGui::InputText("reference", &state.referencePath);
    if (ImGui::Button("Load")) requests.load = true;
    if (!state.status.empty()) {
        if (state.statusIsError) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.4f, 0.35f, 1.0f));
        ImGui::TextWrapped("%s", state.status.c_str());
        if (state.statusIsError) ImGui::PopStyleColor();
    }
}

}  // namespace

PanelRequests drawControlPanel(PanelState& state, FitSession& session, float width, float height) {
    PanelRequests requests;
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(ImVec2(width, height));
    ImGui::Begin("subdfit-view", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::PushItemWidth(width * 0.5f);
    if (ImGui::CollapsingHeader("Fit", ImGuiTreeNodeFlags_DefaultOpen)) fitControls(state, session, requests);
    if (ImGui::CollapsingHeader("Parameter groups", ImGuiTreeNodeFlags_DefaultOpen)) groupControls(session);
    if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) viewControls(state, session, requests);
    if (ImGui::CollapsingHeader("Files", ImGuiTreeNodeFlags_DefaultOpen)) fileControls(state, requests);
    ImGui::PopItemWidth();
    ImGui::End();
    return requests;
}

}  // namespace subdfit::view
