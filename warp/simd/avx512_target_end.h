// Closes the AVX-512 part a fast kernel file opened with warp/simd/avx512_target_begin.h.
#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC diagnostic pop
#pragma GCC pop_options
#endif
