// The pre-warp: turns a relief texture into an ordinary texture for one centre of projection (paper section 3).
// Output: same size and orientation as the source; pixel (x, row) covers u in [x, x+1), v in [h-1-row, h-row).
// Pixels where nothing landed have alpha 0; every other pixel has alpha 255.
//
// Reconstruction (section 3.2): a horizontal pass moves every texel to its final column, interpolating colour
// and the final row coordinate along the row between non-empty neighbours; a vertical pass moves texels to their
// final rows, interpolating colour. Each line is warped in occlusion-compatible order: split at the epipole,
// each part from the border towards the epipole, and the span between the two last texels is filled like any
// other. Samples that land outside the texture are dropped, unless keep_outliers asks for a margin around the
// quad (paper section 4, Figure 12): then the output covers u in [-left, w + right), v in [-bottom, h + top),
// with the margins chosen per view to hold every sample (up to max_margin texels per side).
//
// Surface discontinuities (section 4.1.1): where the relief carries marks (mark_discontinuities), the horizontal
// pass never interpolates across a marked edge, and the vertical pass never connects two intermediate pixels
// whose carried displacements differ by more than the relief's threshold: no "skins".
//
// Depth correction (section 4.2): on request, the displacement seen at each output pixel is interpolated along
// with colour and written, quantized with the relief's 8-bit quantizer (index 255 where empty). Since the
// pre-warped point P and the surface point X lie on one ray from the eye, X - E = (P - E) * (1 + k3*d): the
// texture-mapping stage scales the polygon's eye-space depth by 1 + k3*d to get the perceived depth.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "image.h"
#include "isa.h"
#include "prewarp_coefficients.h"
#include "relief_texture.h"
#include "tables.h"

namespace rtm {

namespace fast {
struct ReverseBuffers;  // warp/simd/pipelined_job.h
}

enum class Reconstruction { two_pass, pipelined };

// How a span between two warped samples becomes pixels (section 3.2.1):
//   point    - each pixel whose centre the span covers takes the colour interpolated at that centre;
//   coverage - coverage-weighted, in the manner of Fant's resampling: each pixel takes the average colour of the
//              parts of spans that cover it, weighted by the length covered, and alpha = the covered fraction.
enum class Filter { point, coverage };

struct PrewarpOptions {
    Reconstruction method = Reconstruction::two_pass;
    bool exact = false;          // unquantized displacement and double-precision coordinates (the reference path)
    int threads = 0;             // 0 = all available; the output never depends on it
    bool keep_outliers = false;  // keep samples that leave the quad in a margin (for the side polygons)
    int max_margin = -1;         // largest margin per side in texels; -1 = 2 * max(w, h)
    // With keep_outliers: no side's margin larger than this side of the cap (the part of the margins a camera can
    // see, objects/view_analysis.h visible_margins); texels beyond are dropped like those past max_margin. Negative
    // sides: no cap. Margins only ever shrink; the quad itself is always whole.
    std::array<int, 4> margin_cap{-1, -1, -1, -1};  // left, right, bottom, top
    // The SIMD target of the kernels (warp/isa.h): automatic takes RTM_ISA or the fastest this CPU has; generic
    // the reference kernels. Same output on every target. A target the CPU lacks throws std::invalid_argument.
    Isa isa = Isa::automatic;
    Filter filter = Filter::point;
    // Texels whose displacement is exactly zero do not move (paper section 5, the brick wall): copy runs of them
    // without the warp arithmetic. Same output either way; off only to measure what the copy saves. "Zero" is a
    // level that decodes to exactly 0 (with `exact`: a displacement of exactly 0.0). It applies to the reference
    // kernels with the point filter (the fast kernels always copy one-pixel spans that lie on pixel centres).
    bool copy_still_runs = true;
};

// Texels of output beyond the quad on each side (all 0 unless keep_outliers).
struct PrewarpExtent {
    int left = 0, right = 0, bottom = 0, top = 0;
    friend bool operator==(const PrewarpExtent&, const PrewarpExtent&) = default;
};

// Intermediate buffers, reused across frames so a steady-state pre-warp allocates nothing.
struct PrewarpWorkspace {
    ImageRGBA8 mid_color;         // horizontal-pass output
    ImageF mid_v, mid_d;          // final v and displacement carried by the horizontal pass (lookup-table path)
    Image2D<double> mid_v_exact;  // the same in double precision (--exact)
    Image2D<double> mid_d_exact;
    // The fast pipelined kernel's row chunks after a part's first (warp/simd/schedule.cpp): output-sized images, 0
    // everywhere between pre-warps (the kernel clears what it wrote).
    std::vector<ImageRGBA8> chunk_scratch;
    bool chunk_scratch_dirty = false;  // set while chunks and composite run: an interrupted pre-warp left pixels
    // The row chunks of each part (0: bottom, 1: top): the first row of each chunk in the part's order and the
    // part's row count last, balanced by the times the chunks took in the last pre-warp (balance_row_chunks). Any
    // increasing bounds from 0 to the row count give the same output; others are replaced by equal chunks.
    std::array<std::vector<int>, 2> chunk_bounds;
    // The Highway pipelined kernel's buffers (warp/simd/hwy_pipelined.cpp), one per task of a pre-warp (a part's
    // column range or row chunk, by its index), whichever thread runs it: grown in the first pre-warps, then reused.
    // Reverse mode's (warp/simd/pipelined_job.h) are made at a task's first use of them.
    std::vector<std::vector<float>> task_buffers;
    std::vector<std::shared_ptr<fast::ReverseBuffers>> reverse_buffers;
};

struct PrewarpStats {
    long long texels = 0;   // source texels visited
    long long dropped = 0;  // texels that could not be pre-warped (1 + k3*d <= 0)
    PrewarpExtent extent;   // the output's margins around the quad
    // Texels the row warp copied as zero-displacement runs, without the warp arithmetic: every still texel except
    // those right after a connected moving texel in occlusion-compatible order, whose span is drawn. Counted by the
    // reference kernels only (0 from the fast kernels, which copy without counting).
    long long still_copied = 0;
    // The work the reconstruction does, counted by the reference kernels with point sampling only (0 otherwise):
    // pixels the row warp produced, overwrites included (the same for both reconstructions), and samples the
    // column warp rasterized (two-pass: the intermediate pixels that survived their row's overwrites; pipelined:
    // every pixel the row warp produced, paper section 3.2.2). Their ratio is what the pipelined reconstruction
    // pays for foldovers.
    long long row_pixels = 0;
    long long column_samples = 0;
    // The target whose kernels computed this pre-warp (generic: the reference kernels, also where the chosen
    // target's kernels do not cover the case).
    Isa isa = Isa::generic;
};

// Non-empty texels at zero displacement (the texels copy_still_runs copies), whatever the view: a level that decodes
// to exactly 0, or with `exact` a displacement of exactly 0.0.
long long count_still_texels(const ReliefTexture& relief, bool exact);

// Pre-warps `relief` for the eye in `k`. `out` is resized to the relief's size plus the margins. If `displ_out`
// is not null it receives the quantized displacement seen at each output pixel (for depth correction).
PrewarpStats prewarp(const ReliefTexture& relief, const PrewarpCoefficients& k, const PrewarpOptions& options,
                     PrewarpWorkspace& workspace, ImageRGBA8& out, Image2D<uint8_t>* displ_out = nullptr);

// The margins that hold every sample of this view (before clamping to max_margin).
PrewarpExtent outlier_extent(const ReliefTexture& relief, const PrewarpCoefficients& k, int max_margin);

// The margins prewarp() gives its output for these options (none unless keep_outliers; max_margin's default).
PrewarpExtent prewarp_extent(const ReliefTexture& relief, const PrewarpCoefficients& k, const PrewarpOptions& options);

// Widens [umin, umax] x [vmin, vmax] to hold where every point of the box [us0, us1] x [vs0, vs1] x [dmin, dmax]
// (texel units, world displacement) is pre-warped to. u_i is linear in u_s and monotonic in d (likewise v_i), so
// the extremes are at the box's eight corners; displacements that cannot be pre-warped (1 + k3*d <= 0) are cut
// just below the eye's plane (those texels are dropped).
void widen_by_warped_box(const PrewarpCoefficients& k, double us0, double us1, double vs0, double vs1, double dmin,
                         double dmax, double& umin, double& umax, double& vmin, double& vmax);

// Convenience: computes coefficients and tables itself.
ImageRGBA8 prewarp(const ReliefTexture& relief, const glm::dvec3& eye, const PrewarpOptions& options = {});

std::string to_string(Reconstruction m);
std::string to_string(Filter f);

}  // namespace rtm
