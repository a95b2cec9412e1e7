#include "viewer/panel.h"
#include "viewer/perpixel_panel.h"

#include <imgui.h>

#include <algorithm>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace rtm::viewer {

namespace {

const char* kSkips[] = {kSkipBackFacing,    kSkipOutsideFrustum, kSkipSubpixelParallax, kSkipReuse,
                        kSkipPartialUpload, kSkipInsideSlab,     kSkipZeroRuns,         kSkipOffscreenMargins};

// A titled separator (ImGui 1.86 has no SeparatorText).
void section(const char* title) {
    ImGui::Separator();
    ImGui::TextDisabled("%s", title);
}

// The methods in the panel's list: every render method, the per-pixel ones after the paper's (reliefs and scenes).
const std::vector<RenderMethod>& methods() {
    static const std::vector<RenderMethod> m = render_methods();
    return m;
}

std::string method_label(RenderMethod m) { return m == RenderMethod::raycast ? "raycast (still)" : to_string(m); }

bool method_combo(const char* id, RenderMethod& m, bool with_raycast) {
    bool changed = false;
    if (ImGui::BeginCombo(id, method_label(m).c_str())) {
        for (RenderMethod x : methods()) {
            if (x == RenderMethod::raycast && !with_raycast) continue;
            if (ImGui::Selectable(method_label(x).c_str(), x == m)) {
                m = x;
                changed = true;
            }
        }
        ImGui::EndCombo();
    }
    return changed;
}

}  // namespace

glm::vec4 draw_panel(ViewSettings& s, PanelContext& c, KeyRequests& r) {
    ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Always);
    const float u = c.ui_scale;
    ImGui::SetNextWindowSize(ImVec2(330 * u, 0), ImGuiCond_Always);
    // Opaque: the panel's pixels do not depend on the image under it, so they are kept and copied between its
    // renders (viewer/panel_cache.h).
    ImGui::SetNextWindowBgAlpha(1.f);
    ImGui::Begin("rtm view", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                     ImGuiWindowFlags_NoSavedSettings);
    ImGui::TextWrapped("%s: %s", c.loaded_kind.c_str(), c.loaded_name.c_str());
    if (!c.status.empty()) ImGui::TextColored(ImVec4(1, 0.5f, 0.3f, 1), "%s", c.status.c_str());

    // Frame time by stage (Table 1 of the paper), frames per second, texels pre-warped.
    const FrameSample all = c.stats ? c.stats->mean() : FrameSample{};
    const FrameStats* ts = c.timed_stats ? c.timed_stats : c.stats;
    const FrameSample m = ts ? ts->mean() : FrameSample{};
    ImGui::Text("%.1f fps   %.2f ms/frame", c.stats ? c.stats->fps() : 0.0, all.frame_ms);
    ImGui::TextDisabled("stages: timed frames (1 in %d), %.1f ms", c.timed_every, m.frame_ms);
    if (ImGui::BeginTable("stages", 3, ImGuiTableFlags_SizingFixedFit)) {
        auto row = [&](const char* name, double ms) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(name);
            ImGui::TableNextColumn();
            ImGui::Text("%7.3f ms", ms);
            ImGui::TableNextColumn();
            ImGui::Text("%5.1f %%", m.frame_ms > 0 ? 100.0 * ms / m.frame_ms : 0.0);
        };
        row("pre-warp", m.stages.prewarp_ms);
        row("upload", m.stages.upload_ms);
        row("texture mapping", m.stages.texture_map_ms);
        row("other", m.other_ms());
        ImGui::EndTable();
    }
    if (c.stats && !c.stats->samples().empty()) {
        const std::vector<float> frame = c.stats->series(0), pre = c.stats->series(1);
        const float top = std::max(1.0f, *std::max_element(frame.begin(), frame.end()));
        ImGui::PlotLines("frame", frame.data(), int(frame.size()), 0, nullptr, 0.f, top, ImVec2(250 * u, 40 * u));
        ImGui::PlotLines("pre-warp", pre.data(), int(pre.size()), 0, nullptr, 0.f, top, ImVec2(250 * u, 40 * u));
    }
    ImGui::Text("texels warped: %lld / frame", all.texels_warped);

    section("method");
    method_combo("##method", s.method, true);
    if (const std::optional<PerPixelMethod> pp = perpixel_method(s.method)) {
        ImGui::TextDisabled("per-pixel settings (reliefs, scenes)");
        perpixel_settings_panel(*pp, s.perpixel, u);
    }
    bool auto_level = s.level < 0;
    if (ImGui::Checkbox("auto level", &auto_level)) s.level = auto_level ? -1 : 0;
    if (!auto_level) {
        ImGui::SameLine();
        ImGui::SetNextItemWidth(120 * u);
        ImGui::SliderInt("level", &s.level, 0, 8);
    } else if (c.report) {
        ImGui::SameLine();
        ImGui::Text("(level %d)", c.report->level);
    }
    ImGui::Checkbox("side polygons", &s.side_polygons);
    ImGui::Checkbox("depth correction", &s.depth_correction);
    ImGui::Checkbox("coverage filter (two-pass)", &s.coverage);
    bool mark = s.discontinuity >= 0;
    static float threshold = 0.05f;  // the slider's value while it is dragged; applied on release (re-marks)
    if (mark && !ImGui::IsAnyItemActive()) threshold = float(s.discontinuity);
    if (ImGui::Checkbox("discontinuities", &mark)) s.discontinuity = mark ? threshold : -1;
    if (mark) {
        ImGui::SetNextItemWidth(140 * u);
        ImGui::SliderFloat("threshold", &threshold, 0.0f, 0.5f, "%.3f");
        if (ImGui::IsItemDeactivatedAfterEdit()) s.discontinuity = threshold;
    }
    const int hw = int(std::max(1u, std::thread::hardware_concurrency()));
    ImGui::SetNextItemWidth(140 * u);
    ImGui::SliderInt("threads (0 = all)", &s.threads, 0, hw);

    section("skips");
    ImGui::Checkbox("skips on", &s.skips);
    for (const char* k : kSkips) {
        const bool fired = c.report &&
                           std::find(c.report->skips.begin(), c.report->skips.end(), k) != c.report->skips.end();
        ImGui::TextColored(fired ? ImVec4(0.4f, 1, 0.4f, 1) : ImVec4(0.5f, 0.5f, 0.5f, 1), "%s %s",
                           fired ? "[fired]" : "[     ]", k);
    }

    section("camera");
    int mode = s.fly ? 1 : 0;
    ImGui::RadioButton("orbit", &mode, 0);
    ImGui::SameLine();
    ImGui::RadioButton("fly (WASD)", &mode, 1);
    s.fly = mode == 1;
    ImGui::SameLine();
    if (ImGui::Button("frame (F)")) r.frame = true;
    if (s.fly && c.fly) {
        float speed = float(c.fly->speed);
        ImGui::SetNextItemWidth(140 * u);
        if (ImGui::DragFloat("speed", &speed, speed * 0.01f, 1e-6f, 1e6f, "%.3g")) c.fly->speed = speed;
    }
    if (c.has_path && c.path_time && c.playing) {
        if (ImGui::Button(*c.playing ? "pause" : "play")) r.toggle_play = true;
        ImGui::SameLine();
        float t = float(*c.path_time);
        ImGui::SetNextItemWidth(200 * u);
        if (ImGui::SliderFloat("path", &t, 0.f, float(c.path_duration), "%.2f s")) *c.path_time = t;
    }

    section("view");
    ImGui::Checkbox("insets", &s.insets);
    ImGui::SameLine();
    ImGui::Checkbox("outlines", &s.outlines);
    ImGui::SameLine();
    ImGui::Checkbox("vsync", &s.vsync);
    // The split view: off, the right half with another method (the per-pixel ones too: against the pre-warp), or
    // the error against the truth.
    const char* modes[] = {"no split", "split: method", "split: error vs truth"};
    int si = s.split == SplitMode::off ? 0 : s.split == SplitMode::method ? 1 : 2;
    ImGui::SetNextItemWidth(200 * u);
    if (ImGui::Combo("##split", &si, modes, 3))
        s.split = si == 0 ? SplitMode::off : si == 1 ? SplitMode::method : SplitMode::truth;
    if (s.split == SplitMode::method) {
        ImGui::SetNextItemWidth(200 * u);
        method_combo("right half##splitmethod", s.split_method, false);
    }
    if (ImGui::Button("screenshot (P)")) r.screenshot = true;
    ImGui::SameLine();
    ImGui::TextDisabled("%s", c.gl_renderer.c_str());
    const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    ImGui::End();
    return {pos.x, pos.y, size.x, size.y};
}

}  // namespace rtm::viewer
