#!/usr/bin/env bash
# Installs what is missing, checks the format (scripts/format.sh), builds, and runs the whole test suite: the
# Release build's tests, then the same tests built with AddressSanitizer and UndefinedBehaviorSanitizer
# (build-asan/), then the libFuzzer targets of fuzz/ for RTM_FUZZ_SECONDS (default 30) each, side by side
# (scripts/fuzz.sh, build-fuzz/). After the Release tests, the pre-warp kernels cross-built for aarch64 and tested
# under qemu, NEON and SVE (scripts/arm.sh, build-arm/; a few minutes). Exit status non-zero on any failure. Set
# RTM_SKIP_SANITIZE=1 to run only the Release suite, RTM_SKIP_FUZZ=1 to leave out the fuzzers, RTM_SKIP_ARM=1 to
# leave out the ARM step. The sanitizer run cuts the random sweeps to RTM_SWEEP_CASES (default 300) cases.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
jobs=$(nproc)

echo "== Format: .clang-format and 120 columns (scripts/format.sh --check)"
bash scripts/format.sh --check

echo "== Release build and tests"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$jobs"
ctest --test-dir build --output-on-failure -j"$jobs"

if [ "${RTM_SKIP_ARM:-0}" != 1 ]; then
  echo "== aarch64: warp/ cross-built and tested under qemu (scripts/arm.sh)"
  bash scripts/arm.sh
fi

if [ "${RTM_SKIP_SANITIZE:-0}" != 1 ]; then
  echo "== AddressSanitizer + UndefinedBehaviorSanitizer build and tests"
  # -O1 with line tables only: half the compile time of RelWithDebInfo's -O2 -g (21.7 s against 10.6 s for
  # measure/compare.cpp), and the sanitizers' reports still name file and line.
  cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRTM_SANITIZE=ON \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" >/dev/null
  cmake --build build-asan -j"$jobs"
  # OSMesa/llvmpipe and TBB keep some allocations for the life of the process: leaks are not checked here.
  # The random sweeps of the SIMD kernels run whole in the Release suite; here the first RTM_SWEEP_CASES cases of
  # each (default 300 of 2000 to 3000) put every kernel path under the sanitizers in a fraction of the time. The
  # avx3 target is not built here (warp/CMakeLists.txt says why; the Release suite runs its tests whole): its tests
  # would add 54 s of test time (half of it on two cores).
  RTM_SWEEP_CASES=${RTM_SWEEP_CASES:-300} \
    ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir build-asan --output-on-failure -j"$jobs" -LE no_sanitize

  if [ "${RTM_SKIP_FUZZ:-0}" != 1 ]; then
    # Bounded: about a minute of building (only the readers are instrumented) and RTM_FUZZ_SECONDS of fuzzing.
    RTM_FUZZ_SECONDS=${RTM_FUZZ_SECONDS:-30} bash scripts/fuzz.sh
  fi
fi
