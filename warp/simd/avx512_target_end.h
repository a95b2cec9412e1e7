// Closes the AVX-512 part a fast kernel file opened with warp/simd/avx512_target_begin.h.
#pragma GCC diagnostic pop
#pragma GCC pop_options
