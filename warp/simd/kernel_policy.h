// A test seam, not an option: how the SIMD kernels schedule their work where there is more than one way. Every
// choice gives the same output to the bit; `automatic` is what the kernels' measurements chose, and only the tests
// (tests/warp/fast_kernels_test.cpp) steer the others, to reach every path. Nothing outside warp/ and tests/
// includes this header.
#pragma once

namespace rtm {

enum class KernelChoice { automatic, always, never };

struct FastKernelPolicy {
    // The pipelined kernel's reverse mode (warp/simd/hwy_pipelined.cpp, RunRows): automatic switches a part to it where
    // its rows overdraw much; always runs whole parts in it.
    KernelChoice pipelined_reverse = KernelChoice::automatic;
    // Threads of the pipelined kernel on chunks of rows rather than ranges of columns (warp/simd/schedule.cpp,
    // pipelined_row_chunks): automatic takes row chunks with threads and one part.
    KernelChoice pipelined_row_chunks = KernelChoice::automatic;
    // The two-pass kernel's backward rows (warp/simd/hwy_row-inl.h, WarpRowBackward): automatic takes the rows that
    // fold over; always every row whose samples all take part.
    KernelChoice two_pass_reverse = KernelChoice::automatic;
    // With two_pass_reverse: clear each backward row and warp it forwards again (the fallback for a backward warp
    // that fails, otherwise unreachable).
    bool two_pass_redo_forwards = false;
    // How the avx2 kernels store some lanes of a vector they own (warp/simd/hwy_columns-inl.h, StoreOwned): always a
    // load, blend and store, never AVX2's masked store; automatic the first where that instruction is slow
    // (avx2_masked_store_slow, warp/isa.h). No other target reads it.
    KernelChoice avx2_blend_stores = KernelChoice::automatic;
};

namespace simd::testing {

// The policy every pre-warp of this process uses (all automatic unless a test set another).
const FastKernelPolicy& kernel_policy();

// Pixels the two-pass vertical pass copied as still pixels (warp/simd/schedule.cpp, vertical_with_still) since the
// process started: the tests check that their reliefs reach that path.
long long vertical_still_copies();

// Sets the policy for the scope's lifetime, then restores the previous one. Not for concurrent pre-warps.
class ScopedKernelPolicy {
public:
    explicit ScopedKernelPolicy(const FastKernelPolicy& policy);
    ~ScopedKernelPolicy();
    ScopedKernelPolicy(const ScopedKernelPolicy&) = delete;
    ScopedKernelPolicy& operator=(const ScopedKernelPolicy&) = delete;

private:
    FastKernelPolicy saved_;
};

}  // namespace simd::testing
}  // namespace rtm
