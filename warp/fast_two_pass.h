// The fast two-pass pre-warp kernels (AVX-512): the same output as prewarp()'s two-pass lookup-table path
// (warp/prewarp.cpp) bit for bit, for reliefs without discontinuity marks and without depth output. Scheduling
// (threads, ranges) lives in warp/fast_prewarp.cpp; these functions only work on the ranges they are given.
//
// Horizontal pass, rows [r0, r1): per texel, u_i = (u_s + K1[q]) * R[q] + left margin and the final row coordinate
// v_i = (v_s + K2[q]) * R[q] + bottom margin in float exactly as the reference computes them; each row is warped
// by the line kernel of warp/fast_line.h into the intermediate image (colour and v_i, row-major).
//
// Vertical pass, columns [x0, x1): columns are taken 16 at a time; the 16 x h block of the intermediate image is
// transposed in 16 x 16 tiles into 16 contiguous lines, each line is warped by the same row kernel, and the 16
// output lines are transposed back into the output's rows (one 64-byte write per row).
#pragma once

#include <atomic>
#include <cstdint>

#include "warp/fast_tables.h"
#include "warp/image.h"
#include "warp/prewarp.h"
#include "warp/relief_texture.h"

namespace rtm::fast {

// Lookup tables in the form the kernels use: K1 is NaN at every level that cannot be pre-warped (and at 255),
// so validity is "the position is finite", which the reference also requires.
struct TwoPassJob {
    const ReliefTexture* relief = nullptr;
    const FastTables* tables = nullptr;
    PrewarpExtent extent;
    int split_u = 0, split_v = 0;  // split_index of the epipole along rows and columns
    // The intermediate image in column tiles: 16 columns x all rows per tile, tile after tile, so that the vertical
    // pass reads each tile as one sequential stream. Pixel (x, row) is at ((x / 16) * height + row) * 16 + x % 16.
    // Both start on a 64-byte boundary.
    uint32_t* mid = nullptr;
    float* mid_v = nullptr;
    int mid_width = 0;  // out width (the tiles' width is rounded up)
    ImageRGBA8* out = nullptr;     // out width x out height
    std::atomic<long long>* dropped = nullptr;
};

void horizontal_rows(const TwoPassJob& job, int r0, int r1);
void vertical_columns(const TwoPassJob& job, int x0, int x1);  // x0 a multiple of 16

}  // namespace rtm::fast
