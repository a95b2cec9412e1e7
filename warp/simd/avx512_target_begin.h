// Opens the AVX-512 part of a fast kernel file (warp/simd/avx512_two_pass.cpp, warp/simd/avx512_pipelined.cpp): include
// it after every other header, then warp/simd/avx512_line.h and the other kernel headers, and close the part with
// warp/simd/avx512_target_end.h at the end of the file. No include guard: each file opens and closes the part once.
//
// The features are those fast::cpu_supported() (warp/simd/schedule.cpp) checks before any of this code runs, plus
// BMI1, LZCNT, POPCNT and PREFETCHW, which every CPU with AVX-512 VBMI and VNNI has.
#if defined(__clang__)
// Clang ignores GCC's target pragma: the same features as an attribute of every function in the part.
#pragma clang attribute push(                                                                                         \
    __attribute__((target("avx512f,avx512bw,avx512dq,avx512vl,avx512vbmi,avx512vnni,bmi,bmi2,lzcnt,popcnt,prfchw"))), \
    apply_to = function)
#else
#pragma GCC push_options
// GCC 12 reports _mm512_undefined_* inside its own intrinsics as possibly uninitialized.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC target("avx512f,avx512bw,avx512dq,avx512vl,avx512vbmi,avx512vnni,bmi,bmi2,lzcnt,popcnt,prfchw")
#endif
