// Dear ImGui's panel drawn at a limited rate. On llvmpipe the panel (a 330x714 window of text, a table and two plots)
// costs about 13 ms a frame to rasterize, most of a frame (docs/BENCHMARKS.md, "Viewer"); its content changes with an
// event, a setting, or its numbers and plots. So its windows are rendered into a texture the size of the panel's
// rectangle only when asked (an event, a changed setting, a screenshot), when the rectangle changed, or once per
// refresh interval (100 ms: the numbers and plots at 10 Hz), and the texture is copied onto every other frame with one
// blit. The background draw list (the insets and outlines, which follow the view) is drawn every frame, directly.
//
// The copy is exact only for what the windows draw inside the rectangle over an opaque background: the panel's
// window background is opaque (viewer/panel.cpp). When the windows draw outside it (an open combo box, a plot's
// tooltip), they are drawn directly, every frame, as before.
#pragma once

#include <glm/vec4.hpp>

#include "warp/timing.h"

struct ImDrawData;

namespace rtm::viewer {

class PanelCache {
public:
    // refresh_ms: the longest time the cached panel is shown without being rendered again; 0 draws the windows
    // directly every frame (no cache).
    explicit PanelCache(double refresh_ms = 100.0) : refresh_ms_(refresh_ms) {}
    ~PanelCache();
    PanelCache(const PanelCache&) = delete;
    PanelCache& operator=(const PanelCache&) = delete;

    // Draws ImGui's draw data (after ImGui::Render) into framebuffer 0: the background list, then the windows from
    // the cache when they draw only inside `panel` (x, y, w, h in ImGui units; w = 0 for no panel), rendering them
    // into it first when `refresh`, when the interval passed or when the rectangle changed; then the foreground list.
    void render(ImDrawData* data, const glm::vec4& panel, bool refresh);

    long long renders() const { return renders_; }  // frames whose windows were rendered (into the cache or not)
    long long blits() const { return blits_; }      // frames that showed the cached panel without rendering it

private:
    double refresh_ms_;
    unsigned fbo_ = 0, texture_ = 0;
    int fbo_w_ = 0, fbo_h_ = 0;
    int x0_ = 0, y0_ = 0, x1_ = 0, y1_ = 0;  // the cached rectangle, framebuffer pixels, top-left origin
    bool valid_ = false;
    Clock::time_point rendered_at_;
    long long renders_ = 0, blits_ = 0;
    void resize(int w, int h);
};

}  // namespace rtm::viewer
