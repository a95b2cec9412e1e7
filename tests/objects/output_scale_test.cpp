// The pre-warp's output scale (warp/upsample.h, docs/DESIGN.md "Output scale") end to end: when the texture-mapping
// stage magnifies the quad, pre-warping into a texture 2x or 4x the source's size brings the frame closer to the
// ray-cast truth, and never loses coverage.
#include <gtest/gtest.h>

#include "measure/compare.h"
#include "measure/image_diff.h"
#include "objects/render_relief.h"
#include "procedural/procedural_media.h"
#include "texmap/gl_context.h"
#include "warp/upsample.h"

namespace rtm {
namespace {

TEST(OutputScale, CloserToTheTruthWhenMagnified) {
    // A 64x64 bumps relief seen from close (distance 0.9 radii): the quad spans most of the 256x256 frame, about
    // 4 pixels per texel, so the texture-mapping stage magnifies the pre-warped texture about 4 times at scale 1.
    const ReliefTexture relief = to_relief(make_bumps(64));
    ReliefQuad q1(relief), q2(upsample(relief, 2)), q4(upsample(relief, 4));
    auto ctx = GlContext::create_offscreen(256, 256);
    Renderer renderer;
    for (const CompareView& v :
         {CompareView{"front", 0, 0, 0.9}, CompareView{"oblique", 30, 20, 0.9}, CompareView{"grazing", 60, 15, 1.0}}) {
        const Camera cam = compare_camera(q1, v, 256, 256);
        RenderSettings s;
        s.prewarp.keep_outliers = true;
        StageTimes t;
        s.method = RenderMethod::raycast;
        const ImageRGBA8 truth = render_relief_frame(q1, nullptr, cam, s, t);
        s.method = RenderMethod::two_pass;
        const DiffResult d1 = diff_images(truth, render_relief_frame(q1, &renderer, cam, s, t));
        const DiffResult d2 = diff_images(truth, render_relief_frame(q2, &renderer, cam, s, t));
        const DiffResult d4 = diff_images(truth, render_relief_frame(q4, &renderer, cam, s, t));
        std::printf("%s: PSNR %.2f / %.2f / %.2f dB, IoU %.4f / %.4f / %.4f at output scale 1 / 2 / 4\n",
                    v.name.c_str(), d1.psnr, d2.psnr, d4.psnr, d1.iou, d2.iou, d4.iou);
        EXPECT_GT(d2.psnr, d1.psnr) << v.name;
        EXPECT_GT(d4.psnr, d2.psnr) << v.name;
        EXPECT_GT(d2.iou, d1.iou - 0.002) << v.name;
        EXPECT_GT(d4.iou, d1.iou - 0.002) << v.name;
    }
}

}  // namespace
}  // namespace rtm
