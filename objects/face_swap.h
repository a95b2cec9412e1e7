// Pre-warping an adjacent face onto a visible face's plane (paper section 4.1, Figure 15).
//
// Faces of the box are perpendicular, so a texel (u_s, v_s, d) of an adjacent face G, expressed in the frame of a
// face F it borders, has its displacement become a column (or row) coordinate of F and its column (or row) become
// F's displacement: FaceSwap is that affine map, a signed permutation with scales for two faces of one box. With
// the swapped coordinates (u', v', d'), G's texels are pre-warped onto F "as if they were F themselves" with the same
// equations 4a and 4b and F's coefficients:  u_i = (u' + k1 d') / (1 + k3 d'),  v_i = (v' + k2 d') / (1 + k3 d').
//
// warp_adjacent_face does it with the same 1-D passes as the single relief (warp/line_warp.h, warp_line_to): a pass
// along G's rows to one of F's final coordinates (carrying the other, d' and G's own displacement), then a pass along
// the intermediate columns to the other. The row pass computes the coordinate G's rows spread along: F's u when G's
// rows run along F's u (or run along F's normal while G's displacement feeds F's u), else F's v. (Always computing u
// first would collapse a row of G that runs along F's v onto one column.) Each pass keeps G's occlusion-compatible
// order: samples lie on G's parallel sampling rays, so along a line of G the ray nearer to the eye's foot on G's plane
// can hide the farther one, never the reverse, whichever side of G's plane the eye is on; the lines are warped from the
// borders towards that foot. Spans are not drawn across G's marked discontinuities (section 4.1.1). The output is
// z-tested on d' (along F's normal; for a viewer in front of F a larger d' is nearer on the same ray), so several
// adjacent faces accumulate into one buffer whatever their order. Two-pass reconstruction with point sampling.
#pragma once

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <string>
#include <vector>

#include "warp/image.h"
#include "warp/isa.h"
#include "warp/prewarp_coefficients.h"
#include "warp/relief_texture.h"

namespace rtm {

struct FaceSwap {
    // (u', v', d') = offset + m * (u_s, v_s, d): F's texel coordinates and displacement (world units) of G's point.
    glm::dvec3 offset{0.0};
    glm::dmat3 m{1.0};
    glm::dvec3 apply(double u_s, double v_s, double d) const { return offset + m * glm::dvec3(u_s, v_s, d); }
    // For perpendicular faces: which of G's (u_s, v_s, d) feeds F's u', v', d' (0, 1, 2), or -1 if several do.
    int source_of(int target) const;
    std::string to_string() const;
};

// The map from relief `src`'s (u_s, v_s, d) to relief `dst`'s frame; exact for any two frames whose dst a, b, f are
// independent.
FaceSwap make_face_swap(const ReliefGeometry& src, const ReliefGeometry& dst);

// Where the adjacent faces' samples land on F, accumulated: colour (alpha 255 where something landed, else 0) and
// d' per pixel (-infinity where empty). Same size and orientation as F's pre-warped texture.
struct AdjacentBuffer {
    ImageRGBA8 color;
    ImageF depth;
    void reset(int width, int height);
};

// One pixel of the row pass's output in warp_adjacent_face: F's other coordinate, d', G's displacement, colour
// (alpha 0: nothing landed), together so that the column pass reads one cache line per sample.
struct AdjacentSample {
    double v = 0, d = 0, g = 0;
    Rgba8 c{};
};

// Scratch for warp_adjacent_face, reused across calls.
struct AdjacentWorkspace {
    ImageRGBA8 mid_color;  // the reference's row-pass output
    Image2D<double> mid_v, mid_d, mid_g;
    Image2D<AdjacentSample> mid;  // the fast path's
    // Per row of `mid`: the extent the last row pass wrote (mid_hi < mid_lo: none). Everything outside it is the
    // empty sample, so a row pass clears only the previous extent and the column pass reads only inside it.
    std::vector<int> mid_lo, mid_hi;
};

// Pre-warps relief `g` (an adjacent face) onto the plane of `f_geom` (width x height texels) for the eye in `kf`
// (compute_coefficients(f_geom, eye)), z-testing into `out` (already sized width x height). With `exact` the
// displacement is g's exact one, else its 8-bit quantized level. Returns the number of texels that could not be
// pre-warped (1 + k3*d' <= 0; none when the eye is in front of F and G lies behind F's plane).
//
// For two faces of one box (every component of the swap has one source, FaceSwap::source_of) it runs a faster
// schedule of the same computation: the swap's terms per column of G, per row and per quantization level computed
// once, a row's coordinates computed branch-free before its line warp, the row pass's output kept together
// (AdjacentSample) and cleared and read only over each row's written extent, rows and columns where nothing landed
// skipped, both passes compiled for SSE4.2 and AVX2 besides the baseline and chosen by `isa`. Its
// output is the reference's, value for value (tests/objects/face_swap_test.cpp compares them over a random sweep),
// on every instruction set `isa` names (warp/isa.h; automatic: RTM_ISA or the fastest; throws std::invalid_argument
// for one this CPU lacks).
long long warp_adjacent_face(const ReliefTexture& g, const ReliefGeometry& f_geom, int width, int height,
                             const PrewarpCoefficients& kf, bool exact, AdjacentWorkspace& ws, AdjacentBuffer& out,
                             int threads = 0, Isa isa = Isa::automatic);

// The reference: the swap applied to every texel as a matrix, the generic schedule; any two frames.
long long warp_adjacent_face_reference(const ReliefTexture& g, const ReliefGeometry& f_geom, int width, int height,
                                       const PrewarpCoefficients& kf, bool exact, AdjacentWorkspace& ws,
                                       AdjacentBuffer& out, int threads = 0);

}  // namespace rtm
