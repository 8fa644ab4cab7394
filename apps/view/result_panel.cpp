#include "result_panel.h"

#include <algorithm>

#include <imgui.h>

#include "cage_wireframe.h"

namespace subdfit::view {
namespace {

constexpr float kStatsAt = 130.0f;  // where a column's figures start on its row

const char* resultModeName(ViewMode mode) {
    if (mode == ViewMode::Fit) return "Shaded";
    if (mode == ViewMode::Difference) return "Error against the reference";
    return viewModeName(mode);
}

maps::MapEffects unionOfEffects(std::vector<std::unique_ptr<ResultColumn>>& columns) {
    maps::MapEffects all;
    for (auto& column : columns) all = all | column->mapEffects();
    return all;
}

void columnTable(ResultPanelState& state, const ResultInputs& inputs,
                 std::vector<std::unique_ptr<ResultColumn>>& columns, ResultPanelRequests& requests) {
    ImGui::TextWrapped("%s", inputs.title.c_str());
    if (ImGui::RadioButton("side by side", state.sideBySide)) state.sideBySide = true;
    ImGui::SameLine();
    if (ImGui::RadioButton("one at a time (left, right keys)", !state.sideBySide)) state.sideBySide = false;
    ImGui::TextDisabled("shown");
    ImGui::SameLine(kStatsAt);
    ImGui::TextDisabled("bytes, held-out PSNR, SSIM");
    for (size_t c = 0; c < columns.size(); ++c) {
        const ColumnInputs& column = columns[c]->inputs();
        ImGui::PushID(int(c));
        if (state.sideBySide) {
            bool on = state.visible[c];
            if (ImGui::Checkbox(column.name.c_str(), &on)) state.visible[c] = on;
        } else if (ImGui::RadioButton(column.name.c_str(), state.shown == int(c))) {
            state.shown = int(c);
        }
        ImGui::SameLine(kStatsAt);
        ImGui::TextUnformatted(column.stats.c_str());
        // A chain of levels of detail, or a file's prefixes: a slider for each column that has one.
        int level = columns[c]->level();
        const bool prefixes = !column.levels.back().label.empty();
        if (column.levels.size() > 1 &&
            ImGui::SliderInt(prefixes ? "prefix" : "level of detail", &level, 0, int(column.levels.size()) - 1)) {
            requests.levelColumn = int(c);
            requests.level = level;
        }
        if (prefixes) {
            const std::string& label = column.levels[size_t(columns[c]->level())].label;
            ImGui::TextDisabled("%s", label.empty() ? "the whole file" : label.c_str());
        }
        ImGui::PopID();
    }
    for (const auto& note : inputs.notes) {
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextDisabled("%s", note.c_str());
        ImGui::PopTextWrapPos();
    }
}

void viewControls(ResultPanelState& state, std::vector<std::unique_ptr<ResultColumn>>& columns, bool reference,
                  ResultPanelRequests& requests) {
    const maps::MapEffects effects = unionOfEffects(columns);
    for (int m = 0; m < kViewModeCount; ++m) {
        const auto mode = ViewMode(m);
        if (!resultModeAvailable(mode, effects, reference)) continue;
        if (ImGui::RadioButton(resultModeName(mode), state.view.mode == mode)) state.view.mode = mode;
    }
    if (!resultModeAvailable(state.view.mode, effects, reference)) state.view.mode = ViewMode::Fit;
    const auto mode = state.view.mode;
    float& scale = state.scales[size_t(mode)];
    ImGui::BeginDisabled(mode != ViewMode::Difference && mode != ViewMode::Displacement && mode != ViewMode::NormalMap);
    ImGui::SliderFloat("colour gain", &scale, 0.1f, 1000.0f, "%.1f", ImGuiSliderFlags_Logarithmic);
    ImGui::EndDisabled();
    state.view.scale = scale;
    if (mode != ViewMode::Fit && mode != ViewMode::Difference) ImGui::TextDisabled("columns without it are shaded");

    ImGui::Checkbox("cage wireframe", &state.view.cageWireframe);
    if (state.view.cageWireframe) {
        auto swatch = [](const char* text, glm::vec4 c) {
            ImGui::SameLine();
            ImGui::TextColored(ImVec4(c.r, c.g, c.b, 1.0f), "%s", text);
        };
        swatch("edge", kSmoothEdgeColor);
        swatch("crease", kSharpCreaseColor);
        swatch("semi-sharp", kSemiSharpCreaseColor);
        swatch("corner", kCornerColor);
    }

    int drawn = 0;
    for (auto& column : columns) drawn = std::max(drawn, column->tessLevel());
    ImGui::BeginDisabled(drawn == 0);
    ImGui::SliderInt("tessellation", &state.tessLevel, 1, 64);
    ImGui::SameLine();
    if (ImGui::Button("Apply")) requests.applyTessLevel = true;
    ImGui::TextDisabled("drawn at %d segments per face edge", drawn);
    ImGui::EndDisabled();
    if (ImGui::Button("Reset view")) requests.resetCamera = true;
}

}  // namespace

bool resultModeAvailable(ViewMode mode, maps::MapEffects anyColumn, bool reference) {
    if (mode == ViewMode::Target) return false;  // the reference is a column of its own
    if (mode == ViewMode::Difference) return reference;
    return viewModeAvailable(mode, anyColumn);
}

ResultPanelRequests drawResultPanel(ResultPanelState& state, const ResultInputs& inputs,
                                    std::vector<std::unique_ptr<ResultColumn>>& columns, float width, float height) {
    ResultPanelRequests requests;
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(ImVec2(width, height));
    ImGui::Begin("subdfit-view", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::PushItemWidth(width * 0.5f);
    const bool reference = !columns.empty() && columns.front()->inputs().reference;
    if (ImGui::CollapsingHeader("Result", ImGuiTreeNodeFlags_DefaultOpen))
        columnTable(state, inputs, columns, requests);
    if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen))
        viewControls(state, columns, reference, requests);
    if (state.canRefine && ImGui::CollapsingHeader("Refine", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::TextWrapped("Fit subdfit's asset further against the reference, in this window (Save writes to --out).");
        if (ImGui::Button("Refine subdfit's result")) requests.refine = true;
    }
    if (!state.status.empty()) {
        if (state.statusIsError) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.4f, 0.35f, 1.0f));
        ImGui::TextWrapped("%s", state.status.c_str());
        if (state.statusIsError) ImGui::PopStyleColor();
    }
    ImGui::PopItemWidth();
    ImGui::End();
    return requests;
}

}  // namespace subdfit::view
