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

# Each step's wall time, printed as it ends and all together at the end (so a CI log says where its time went).
step_names=()
step_secs=()
step_name=""
step_start=$SECONDS
step() {
  if [ -n "$step_name" ]; then
    step_names+=("$step_name")
    step_secs+=($((SECONDS - step_start)))
    echo "-- $step_name: $((SECONDS - step_start)) s"
  fi
  step_name=$1
  step_start=$SECONDS
  [ -n "$1" ] && echo "== $1"
  return 0
}
summary() {
  step ""
  echo "== Time per step (total $((SECONDS / 60)) min $((SECONDS % 60)) s)"
  local i
  for i in "${!step_names[@]}"; do printf '%6d s  %s\n' "${step_secs[$i]}" "${step_names[$i]}"; done
}
trap summary EXIT

step "Packages (scripts/setup.sh)"
bash scripts/setup.sh
jobs=$(nproc)

step "Format: .clang-format and 120 columns (scripts/format.sh --check)"
bash scripts/format.sh --check

step "Release build"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$jobs"
step "Release tests"
ctest --test-dir build --output-on-failure -j"$jobs"

if [ "${RTM_SKIP_ARM:-0}" != 1 ]; then
  step "aarch64: warp/ cross-built and tested under qemu (scripts/arm.sh)"
  bash scripts/arm.sh
fi

if [ "${RTM_SKIP_SANITIZE:-0}" != 1 ]; then
  step "AddressSanitizer + UndefinedBehaviorSanitizer build"
  # -O1 with line tables only: half the compile time of RelWithDebInfo's -O2 -g (21.7 s against 10.6 s for
  # measure/compare.cpp), and the sanitizers' reports still name file and line.
  cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRTM_SANITIZE=ON \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" >/dev/null
  cmake --build build-asan -j"$jobs"
  step "AddressSanitizer + UndefinedBehaviorSanitizer tests"
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
    step "libFuzzer targets (scripts/fuzz.sh)"
    RTM_FUZZ_SECONDS=${RTM_FUZZ_SECONDS:-30} bash scripts/fuzz.sh
  fi
fi
