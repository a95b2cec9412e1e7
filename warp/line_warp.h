// The 1-D forward warp and resampling of one line (a row in the horizontal pass, a column in the vertical pass),
// paper section 3.2.1 and Figure 10. One kernel serves rows and columns: the output is strided.
//
// Input: n samples at source positions k + 0.5 (k = 0..n-1), each with a final position pos[k] along the line, a
// colour, an optional attribute carried along (the final row coordinate in the horizontal pass), and a validity
// flag (empty texels and texels that cannot be pre-warped are invalid).
//
// Order: samples with source position < split_pos (the epipole's coordinate along the line) are processed from
// the first towards the split, the others from the last towards the split; later samples overwrite earlier ones
// (painter's algorithm, correct because the order is occlusion-compatible). Finally the span between the two
// samples nearest the split is filled like any other span, so there is no seam at the epipole.
//
// Spans: between consecutive valid samples A (earlier) and B (later) every output pixel x whose centre
// c = x + 0.5 lies between A.pos (excluded) and B.pos (included) gets colour and attribute linearly interpolated
// at c. A valid sample whose predecessor is invalid (or the first of a part) is written to the pixel containing
// its position, floor(pos). Pixels outside [0, n) are dropped. Written pixels get alpha 255.
#pragma once

#include <cstddef>
#include <cstdint>

#include "image.h"

namespace rtm {

template <class P>
struct LineInput {
    int n = 0;
    const P* pos = nullptr;
    const Rgba8* color = nullptr;
    const P* attr = nullptr;  // may be null
    const uint8_t* valid = nullptr;
};

template <class P>
struct LineOutput {
    int n = 0;                         // number of output pixels along the line
    Rgba8* color = nullptr;            // pixel 0
    std::ptrdiff_t color_stride = 1;   // in pixels, may be negative
    P* attr = nullptr;                 // may be null
    std::ptrdiff_t attr_stride = 1;
};

// Index of the first sample whose source position k + 0.5 is >= split_pos, clamped to [0, n].
int split_index(double split_pos, int n);

template <class P>
void warp_line(const LineInput<P>& in, int split, const LineOutput<P>& out);

extern template void warp_line<float>(const LineInput<float>&, int, const LineOutput<float>&);
extern template void warp_line<double>(const LineInput<double>&, int, const LineOutput<double>&);

}  // namespace rtm
