#include "viewer/panel_cache.h"

#include <glad/gl.h>
#include <imgui.h>
#include <backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "texmap/gl_context.h"

namespace rtm::viewer {

namespace {

// Draws `lists` of `data` with an orthographic projection of the rectangle at `pos` of `size` (ImGui units) onto the
// bound framebuffer's viewport (0, 0, size * scale).
void render_lists(const ImDrawData& data, std::vector<ImDrawList*>& lists, ImVec2 pos, ImVec2 size) {
    if (lists.empty()) return;
    ImDrawData d = data;
    d.CmdLists = lists.data();
    d.CmdListsCount = int(lists.size());
    d.TotalVtxCount = d.TotalIdxCount = 0;
    for (const ImDrawList* l : lists) {
        d.TotalVtxCount += l->VtxBuffer.Size;
        d.TotalIdxCount += l->IdxBuffer.Size;
    }
    d.DisplayPos = pos;
    d.DisplaySize = size;
    ImGui_ImplOpenGL3_RenderDrawData(&d);
}

// The extent (ImGui units) that the windows' lists can change: each command's vertices with some opacity, within its
// clip rectangle. Empty (x0 > x1) when they draw nothing.
ImVec4 drawn_extent(const std::vector<ImDrawList*>& lists) {
    ImVec4 e(INFINITY, INFINITY, -INFINITY, -INFINITY);
    for (const ImDrawList* l : lists)
        for (const ImDrawCmd& c : l->CmdBuffer) {
            if (c.UserCallback || c.ElemCount == 0) continue;
            ImVec4 b(INFINITY, INFINITY, -INFINITY, -INFINITY);
            for (unsigned i = c.IdxOffset; i < c.IdxOffset + c.ElemCount; ++i) {
                const ImDrawVert& v = l->VtxBuffer[int(c.VtxOffset + l->IdxBuffer[int(i)])];
                if (((v.col >> IM_COL32_A_SHIFT) & 0xFF) == 0) continue;  // an anti-aliased fringe's outer edge
                b.x = std::min(b.x, v.pos.x);
                b.y = std::min(b.y, v.pos.y);
                b.z = std::max(b.z, v.pos.x);
                b.w = std::max(b.w, v.pos.y);
            }
            b.x = std::max(b.x, c.ClipRect.x);
            b.y = std::max(b.y, c.ClipRect.y);
            b.z = std::min(b.z, c.ClipRect.z);
            b.w = std::min(b.w, c.ClipRect.w);
            if (b.x >= b.z || b.y >= b.w) continue;
            e = ImVec4(std::min(e.x, b.x), std::min(e.y, b.y), std::max(e.z, b.z), std::max(e.w, b.w));
        }
    return e;
}

// The largest float not above `pixels / scale` whose product with `scale`, truncated as the OpenGL 3 back end does,
// is still `pixels`: the back end's viewport then has exactly the texture's size.
float units_for(int pixels, float scale) {
    float u = float(pixels) / scale;
    while (int(u * scale) < pixels) u = std::nextafter(u, INFINITY);
    return u;
}

}  // namespace

PanelCache::~PanelCache() {
    if (fbo_) glDeleteFramebuffers(1, &fbo_);
    if (texture_) glDeleteTextures(1, &texture_);
}

void PanelCache::resize(int w, int h) {
    if (w == fbo_w_ && h == fbo_h_ && fbo_) return;
    if (!fbo_) glGenFramebuffers(1, &fbo_);
    if (!texture_) glGenTextures(1, &texture_);
    glBindTexture(GL_TEXTURE_2D, texture_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture_, 0);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (status != GL_FRAMEBUFFER_COMPLETE) throw GlError("the panel's framebuffer is incomplete");
    check_gl("the panel's framebuffer");
    fbo_w_ = w;
    fbo_h_ = h;
    valid_ = false;
}

void PanelCache::render(ImDrawData* data, const glm::vec4& panel, bool refresh) {
    if (!data || !data->Valid) return;
    const float sx = data->FramebufferScale.x > 0 ? data->FramebufferScale.x : 1.f;
    const float sy = data->FramebufferScale.y > 0 ? data->FramebufferScale.y : 1.f;
    const int fb_w = int(data->DisplaySize.x * sx), fb_h = int(data->DisplaySize.y * sy);
    if (fb_w <= 0 || fb_h <= 0) return;
    std::vector<ImDrawList*> background, windows, foreground;
    ImDrawList* const bg = ImGui::GetBackgroundDrawList();
    ImDrawList* const fg = ImGui::GetForegroundDrawList();
    for (int i = 0; i < data->CmdListsCount; ++i) {
        ImDrawList* l = data->CmdLists[i];
        (l == bg ? background : l == fg ? foreground : windows).push_back(l);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    render_lists(*data, background, data->DisplayPos, data->DisplaySize);

    // The panel's rectangle in whole framebuffer pixels, and whether the windows draw inside it only.
    const int x0 = std::clamp(int(std::floor(panel.x * sx)), 0, fb_w);
    const int y0 = std::clamp(int(std::floor(panel.y * sy)), 0, fb_h);
    const int x1 = std::clamp(int(std::ceil((panel.x + panel.z) * sx)), 0, fb_w);
    const int y1 = std::clamp(int(std::ceil((panel.y + panel.w) * sy)), 0, fb_h);
    bool cached = refresh_ms_ > 0 && x1 > x0 && y1 > y0 && !windows.empty();
    if (cached) {
        const ImVec4 e = drawn_extent(windows);
        // Within half a pixel of the rectangle: a triangle covers a pixel when it covers the pixel's centre, so
        // nothing drawn there reaches a pixel outside (ImGui's clip rectangles end at 330.01 for a 330 wide panel).
        const float hx = 0.5f / sx, hy = 0.5f / sy;
        cached = e.x > float(x0) / sx - hx && e.y > float(y0) / sy - hy && e.z < float(x1) / sx + hx &&
                 e.w < float(y1) / sy + hy;
    }
    if (!cached) {
        valid_ = false;
        if (!windows.empty()) ++renders_;
        render_lists(*data, windows, data->DisplayPos, data->DisplaySize);
    } else {
        const bool moved = x0 != x0_ || y0 != y0_ || x1 != x1_ || y1 != y1_;
        if (refresh || !valid_ || moved || ms_since(rendered_at_) >= refresh_ms_) {
            resize(x1 - x0, y1 - y0);
            glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
            glDisable(GL_SCISSOR_TEST);
            glClearColor(0.f, 0.f, 0.f, 0.f);
            glClear(GL_COLOR_BUFFER_BIT);
            const ImVec2 pos(data->DisplayPos.x + float(x0) / sx, data->DisplayPos.y + float(y0) / sy);
            render_lists(*data, windows, pos, ImVec2(units_for(x1 - x0, sx), units_for(y1 - y0, sy)));
            x0_ = x0;
            y0_ = y0;
            x1_ = x1;
            y1_ = y1;
            valid_ = true;
            rendered_at_ = Clock::now();
            ++renders_;
        } else {
            ++blits_;
        }
        // One copy of the panel's pixels (no blending: its background is opaque), bottom-left origin. A blit, not a
        // textured quad in the background list's pass: interleaved runs of the relief with the panel (load 9 to 11)
        // gave an overlay of 1.17 to 1.25 ms with the blit, 1.69 to 1.82 ms with the quad (with the insets: 2.48 to
        // 2.94 ms against 2.92 to 3.25 ms).
        glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
        glDisable(GL_SCISSOR_TEST);
        glBlitFramebuffer(0, 0, fbo_w_, fbo_h_, x0_, fb_h - y1_, x1_, fb_h - y0_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    render_lists(*data, foreground, data->DisplayPos, data->DisplaySize);
}

}  // namespace rtm::viewer
