// Per-view tables of the fast pre-warp kernels (warp/simd/schedule.h), built from the reference's PrewarpTables: the
// AVX-512 (VBMI) row set-up reads the byte planes, the other targets `level`; every Highway target the identity range.
#pragma once

#include <cstdint>

#include "warp/tables.h"

namespace rtm::fast {

// The three float tables (K1, K2, R of warp/tables.h) held as byte planes, plane[t][b][q] = byte b of table t at
// level q, so that 64 texels look them up with 128-byte two-register byte permutes (AVX-512 VBMI) instead of
// gathers. K1 is NaN at every level that cannot be pre-warped (and at 255): validity becomes "the position is
// finite", which the reference also requires.
struct alignas(64) FastTables {
    uint8_t plane[3][4][256];
    uint8_t dropped[256];  // 1 for a non-empty level that cannot be pre-warped
    // 0x80 for a level whose K1 and K2 are +-0 and R is 1 (zero displacement): (u_s + K1) * R + margin is then
    // u_s + margin exactly (likewise v), and a chunk of such texels skips the lookups (prepare_row). 64-aligned.
    uint8_t identity[256];
    // Per level: K1 (NaN at every level that cannot be pre-warped, and at 255, as the planes hold it), K2, R and a
    // zero, for the Highway row set-up but on AVX-512: one 16-byte load a texel on AVX2 (then a transpose), three
    // gathers on the other targets, where K1, R, K2 and `valid` took four.
    alignas(64) float level[256][4];
    // The first run of consecutive identity levels, [identity_lo, identity_hi] (empty, lo > hi, when there is
    // none): a vector of texels whose levels all lie in it skips the Highway row set-up's lookups. A monotonic
    // quantizer has at most one level at zero displacement; a flat relief may have all of them.
    int identity_lo = 1, identity_hi = 0;
    bool any_dropped = false;
    bool any_identity = false;
};

FastTables make_fast_tables(const PrewarpTables& tab);

// True when this CPU runs the fast kernels (AVX-512 F, BW, DQ, VL, VBMI, VNNI, and BMI2).
bool cpu_supported();

}  // namespace rtm::fast
