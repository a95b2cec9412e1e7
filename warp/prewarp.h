// The pre-warp: turns a relief texture into an ordinary texture for one centre of projection (paper section 3).
// Output: same size and orientation as the source; pixel (x, row) covers u in [x, x+1), v in [h-1-row, h-row).
// Pixels where nothing landed have alpha 0; every other pixel has alpha 255.
//
// Reconstruction (section 3.2): a horizontal pass moves every texel to its final column, interpolating colour
// and the final row coordinate along the row between non-empty neighbours; a vertical pass moves texels to their
// final rows, interpolating colour. Each line is warped in occlusion-compatible order: split at the epipole,
// each part from the border towards the epipole, and the span between the two last texels is filled like any
// other. Samples that land outside the texture are dropped.
#pragma once

#include <string>
#include <vector>

#include "image.h"
#include "prewarp_coefficients.h"
#include "relief_texture.h"
#include "tables.h"

namespace rtm {

enum class Reconstruction { two_pass, pipelined };

struct PrewarpOptions {
    Reconstruction method = Reconstruction::two_pass;
    bool exact = false;  // unquantized displacement and double-precision coordinates (the reference path)
    int threads = 0;     // 0 = all available; the output never depends on it
};

// Intermediate buffers, reused across frames so a steady-state pre-warp allocates nothing.
struct PrewarpWorkspace {
    ImageRGBA8 mid_color;   // horizontal-pass output
    ImageF mid_v;           // final v coordinate carried by the horizontal pass (lookup-table path)
    Image2D<double> mid_v_exact;  // the same in double precision (--exact)
};

struct PrewarpStats {
    long long texels = 0;        // source texels visited
    long long dropped = 0;       // texels that could not be pre-warped (1 + k3*d <= 0)
};

// Pre-warps `relief` for the eye in `k`. `out` is resized to the relief's size.
PrewarpStats prewarp(const ReliefTexture& relief, const PrewarpCoefficients& k, const PrewarpOptions& options,
                     PrewarpWorkspace& workspace, ImageRGBA8& out);

// Convenience: computes coefficients and tables itself.
ImageRGBA8 prewarp(const ReliefTexture& relief, const glm::dvec3& eye, const PrewarpOptions& options = {});

std::string to_string(Reconstruction m);

}  // namespace rtm
