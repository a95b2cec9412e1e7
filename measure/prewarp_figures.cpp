#include "measure/prewarp_figures.h"

#include <cmath>
#include <filesystem>
#include <system_error>

#include "formats/image_io.h"
#include "measure/html_text.h"
#include "objects/render_relief.h"
#include "texmap/gl_context.h"
#include "warp/prewarp_steps.h"
#include "warp/quadrants.h"

namespace rtm {

namespace {

std::string num(double v) { return fixed(v, 2); }

std::string rgba(const Rgba& c) {
    return "rgba(" + std::to_string(c[0]) + "," + std::to_string(c[1]) + "," + std::to_string(c[2]) + "," +
           fixed(c[3] / 255.0, 3) + ")";
}

// The quantized displacement as grey: the range's minimum black, its maximum white; empty texels transparent.
ImageRGBA8 displacement_grey(const ReliefTexture& t) {
    ImageRGBA8 img(t.width, t.height);
    for (int r = 0; r < t.height; ++r)
        for (int x = 0; x < t.width; ++x) {
            const uint8_t q = t.texel(x, r).q;
            const uint8_t g = q == kEmptyIndex ? 0 : uint8_t(std::lround(q * 255.0 / 254.0));
            img.at(x, r) = {g, g, g, uint8_t(q == kEmptyIndex ? 0 : 255)};
        }
    return img;
}

// The final frame, rendered in a context of our own with a quad of our own (GL objects belong to one context).
ImageRGBA8 render_frame(const ReliefTexture& relief, const Camera& cam) {
    auto ctx = GlContext::create_offscreen(cam.width, cam.height);
    Renderer renderer;
    ReliefQuad quad(relief);
    RenderSettings s;
    s.method = RenderMethod::two_pass;
    s.draw.skips = false;
    StageTimes times;
    return render_relief_frame(quad, &renderer, cam, s, times);
}

std::string figure(const std::string& src, int w, int h, const std::string& caption, const std::string& overlay = {}) {
    const int shown = w >= h ? 256 : std::max(1, 256 * w / std::max(1, h));
    std::string s = "<figure class=\"step\"><div class=\"stack\" style=\"width:" + std::to_string(shown) +
                    "px\"><img src=\"" + html_escape(src) + "\" alt=\"" + html_escape(caption) + "\" width=\"" +
                    std::to_string(shown) + "\"/>";
    s += overlay;
    return s + "</div><figcaption>" + html_escape(caption) + "</figcaption></figure>\n";
}

}  // namespace

std::string prewarp_figures(const PrewarpFiguresInput& in) {
    const ReliefTexture& t = *in.relief;
    const std::string dir = in.out_dir + "/steps";
    std::error_code ec;  // a folder that cannot be made shows as the IoError of the first picture written into it
    std::filesystem::create_directories(dir, ec);
    const PrewarpCoefficients k = compute_coefficients(t.geometry, in.camera.eye);
    const PrewarpSteps steps = prewarp_steps(t, k, {});
    write_rgba8(dir + "/source.png", color_image(t));
    write_rgba8(dir + "/displacement.png", displacement_grey(t));
    write_rgba8(dir + "/horizontal.png", steps.horizontal);
    write_rgba8(dir + "/prewarped.png", steps.prewarped);
    std::string frame_note;
    std::optional<ImageRGBA8> frame = in.frame;
    if (!frame) {
        try {
            frame = render_frame(t, in.camera);
        } catch (const std::exception& e) {
            frame_note = std::string("The final frame could not be rendered here: ") + e.what();
        }
    }
    if (frame) write_rgba8(dir + "/frame.png", *frame);

    std::string s =
        "<section id=\"steps\"><h2>The pre-warp step by step</h2>\n<p>One view of " + std::to_string(t.width) + "x" +
        std::to_string(t.height) + " texels from the eye at (" + num(in.camera.eye.x) + ", " + num(in.camera.eye.y) +
        ", " + num(in.camera.eye.z) +
        "), as in Figure 9 of Oliveira, Bishop and McAllister, \"Relief Texture Mapping\" (SIGGRAPH 2000)."
        " The pre-warp moves each texel to where the surface point it carries would be seen on the relief "
        "quad; the texture mapping then draws the quad as an ordinary texture.</p>\n<div class=\"steps\">\n";
    // The source with the epipole and the quadrants (Figure 7): texel units, x = u, y = h - v (row from the top).
    std::string overlay;
    if (k.side == ViewSide::front && std::isfinite(k.epipole_u) && std::isfinite(k.epipole_v)) {
        const QuadrantOverlay o = quadrant_overlay({0, 0}, {double(t.width), double(t.height)},
                                                   {k.epipole_u, double(t.height) - k.epipole_v});
        const double unit = std::max(t.width, t.height) / 256.0;  // one displayed pixel in texels
        overlay = "<svg class=\"overlay\" xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " +
                  std::to_string(t.width) + " " + std::to_string(t.height) + "\">";
        for (const QuadrantOverlay::Box& b : o.quadrants)
            overlay += "<rect x=\"" + num(b.p0.x) + "\" y=\"" + num(b.p0.y) + "\" width=\"" + num(b.p1.x - b.p0.x) +
                       "\" height=\"" + num(b.p1.y - b.p0.y) + "\" fill=\"" + rgba(b.colour) + "\"/>";
        const std::string ex = num(o.epipole.x), ey = num(o.epipole.y), line = rgba(kQuadrantLineColour);
        overlay += "<line x1=\"" + ex + "\" y1=\"0\" x2=\"" + ex + "\" y2=\"" + std::to_string(t.height) +
                   "\" stroke=\"" + line + "\" stroke-width=\"" + num(1.5 * unit) + "\"/>";
        overlay += "<line x1=\"0\" y1=\"" + ey + "\" x2=\"" + std::to_string(t.width) + "\" y2=\"" + ey +
                   "\" stroke=\"" + line + "\" stroke-width=\"" + num(1.5 * unit) + "\"/>";
        overlay += "<circle cx=\"" + ex + "\" cy=\"" + ey + "\" r=\"" + num((o.inside ? 4 : 5) * unit) + "\" fill=\"" +
                   (o.inside ? rgba(kEpipoleColour) : "none") + "\" stroke=\"" + rgba(kEpipoleColour) +
                   "\" stroke-width=\"" + num(2 * unit) + "\"><title>epipole (" + fixed(k.epipole_u, 1) + ", " +
                   fixed(k.epipole_v, 1) + ") texels</title></circle></svg>";
    }
    const std::string where = std::string(k.side != ViewSide::front    ? "the eye does not face the relief"
                                          : std::isfinite(k.epipole_u) ? ""
                                                                       : "no epipole");
    s += figure("steps/source.png", t.width, t.height,
                "(a) The source colour, with the epipole (" + fixed(k.epipole_u, 1) + ", " + fixed(k.epipole_v, 1) +
                    ") in texels" +
                    (where.empty() ? std::string(" and the four occlusion-compatible quadrants: each is warped from "
                                                 "the borders towards the epipole (a ring marks an epipole beyond "
                                                 "the texture, drawn on its border)")
                                   : ": " + where) +
                    ".",
                overlay);
    s += figure("steps/displacement.png", t.width, t.height,
                "(a) The displacement as grey: black " + fixed(t.quant.min, 3) + ", white " + fixed(t.quant.max, 3) +
                    " world units.");
    s += figure("steps/horizontal.png", steps.horizontal.width, steps.horizontal.height,
                "(b) After the horizontal pass: every texel moved along its row to its final column, colour and "
                "final row interpolated between neighbours.");
    s += figure("steps/prewarped.png", steps.prewarped.width, steps.prewarped.height,
                "(c) The pre-warped texture after the vertical pass: every texel at its final row (" +
                    std::to_string(steps.stats.dropped) + " texels could not be pre-warped).");
    if (frame)
        s += figure("steps/frame.png", frame->width, frame->height,
                    "(d) The final frame: the pre-warped texture mapped onto the relief quad (" +
                        std::to_string(frame->width) + "x" + std::to_string(frame->height) + " pixels).");
    s += "</div>\n";
    if (!frame_note.empty()) s += "<p class=\"note\">" + html_escape(frame_note) + "</p>\n";
    return s + "</section>\n";
}

}  // namespace rtm
