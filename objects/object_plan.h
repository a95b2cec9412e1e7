// What a frame does with each visible face of a six-face object (objects/relief_object.h): the relief quad's
// decisions (objects/frame_plan.h) as they apply to a face of an object, decided per face, without OpenGL.
//
// The rules, in order (each only with DrawOptions::skips, except the level choice):
//   outside-frustum: the face's quad lies outside the view frustum -> nothing (not pre-warped, not drawn). The faces
//     not visible from the eye (back-facing) never reach the plan: they cost nothing.
//   level: d.level < 0 -> choose_level of the face (objects/level_choice.h): the level a relief quad of the face's
//     texture draws from the same camera (the density level, no coarser than d.level_error_px pixels of parallax of
//     its texels' displacement spread), else d.level clamped to the pyramid.
//   subpixel-parallax: a warping method whose largest parallax of any point of the box behind the face is below
//     d.subpixel_parallax pixels -> flat (the face's colours as a plain texture).
//   reuse-prewarp: the face's last pre-warp has the same setup and the same adjacent faces, and no point of the box
//     behind the face (the face's own samples and its adjacent faces' alike) moved by d.reuse_tolerance texels since
//     -> reuse (neither pre-warped nor uploaded again).
// The partial upload of a single relief does not carry over: the adjacent faces' samples land anywhere on the face,
// so a new pre-warp is uploaded whole; a reused pre-warp or the same flat level again is not uploaded at all.
#pragma once

#include <string>
#include <vector>

#include "objects/frame_plan.h"
#include "objects/object_region.h"
#include "objects/render_method.h"
#include "texmap/camera.h"
#include "warp/prewarp.h"
#include "warp/relief_texture.h"

namespace rtm {

// What a face's pre-warp was made for: the quad's setup and the faces pre-warped onto it.
struct ObjectFaceSetup {
    PrewarpSetup setup;
    std::vector<int> adjacent;
    friend bool operator==(const ObjectFaceSetup&, const ObjectFaceSetup&) = default;
};

// The pre-warp a face holds: for which setup and view (the face's coefficients k); none when !valid.
struct LastFacePrewarp {
    bool valid = false;
    ObjectFaceSetup setup;
    PrewarpCoefficients k;
};

struct ObjectFacePlan {
    FrameAction action = FrameAction::nothing;  // nothing, flat, prewarp or reuse
    std::vector<std::string> skips;             // the skips that fired for this face, in order
    int level = 0;
    PrewarpOptions prewarp;  // prewarp: the options to pre-warp with (method and still-run copies set)
    ObjectFaceSetup setup;   // prewarp and reuse
    PrewarpCoefficients k;   // flat, prewarp and reuse: the level's coefficients for this eye
};

// The largest parallax (texels) of any point of the box behind face `t` (displacement in [-depth, 0]) for view k:
// u_i - u_s = (u_s - e_u) (1 / (1 + k3 d) - 1) is linear in u_s and monotonic in d (max_parallax_texels's bound).
double box_parallax_texels(const ReliefTexture& t, const PrewarpCoefficients& k, double depth);

// The plan for visible face `face` of an object seen from region `region` (face must be visible in it). `relief` is
// the face's level 0, `level` its pyramid, `depth` the box's extent along the face's normal, `last` what the face
// holds, `spreads` level_displacement_spreads of `relief` (computed here when null; ReliefQuad::spreads caches them).
// `method` is flat, two_pass or pipelined (else std::invalid_argument).
ObjectFacePlan plan_object_face(const Camera& cam, RenderMethod method, const PrewarpOptions& options,
                                const DrawOptions& d, const ObjectRegion& region, int face, const ReliefTexture& relief,
                                const LevelSource& level, double depth, const LastFacePrewarp& last,
                                const std::vector<double>* spreads = nullptr);

}  // namespace rtm
