#!/usr/bin/env bash
# The pre-warp kernels on 64-bit ARM, without an ARM machine: installs what is missing (run as root, or with sudo
# available), cross-builds warp/ and its tests for aarch64 (cmake/aarch64-linux-gnu.cmake, RTM_WARP_ONLY: build-arm/)
# and runs the tests of tests/warp that depend on the target under qemu-user, twice: on a CPU with NEON only
# (QEMU_CPU=cortex-a72: the neon target) and on one with SVE and SVE2 (QEMU_CPU=max,sve=on: the sve and neon
# targets, each in turn), every SIMD target's output (both reconstructions) against the reference kernels' bit for
# bit. Bounded to a few
# minutes: the tests run are RTM_ARM_TESTS (a GoogleTest filter; default the SIMD kernels' and the target choice's
# tests, '*' for all of tests/warp, which takes far longer emulated), and the random sweeps of
# tests/warp/fast_kernels_test.cpp are cut to their first RTM_SWEEP_CASES cases (default 200 here, of 2000 and 3000
# natively; the 8 large reliefs to 1; the kernel-policy sweeps and their large reliefs to a fortieth of it), and the
# steady-state allocation tests are left out (they check the workspace, not the target's arithmetic, and the x86-64
# runs have them for every target). The tests go in GoogleTest shards, as many side by side as the machine has
# cores. Under qemu every instruction is emulated: the times it prints are not measurements of ARM speed (for an
# estimate, scripts/count_instructions.sh counts the instructions of a pre-warp on each target). Also builds
# rtm-warp-run (apps/warp_run.cpp); RTM_ARM_BUILD_ONLY=1 installs and builds, and runs nothing.
set -euo pipefail
cd "$(dirname "$0")/.."

# Packages: the cross compiler, the arm64 builds of Highway, oneTBB and GoogleTest (multiarch; glm is header-only
# and architecture-independent), and qemu-user.
packages=(g++-aarch64-linux-gnu libhwy-dev:arm64 libtbb-dev:arm64 libgtest-dev:arm64 libglm-dev qemu-user cmake
          ninja-build)
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
if ! dpkg --print-foreign-architectures | grep -qx arm64; then
  echo "arm: adding the arm64 architecture to dpkg"
  $SUDO dpkg --add-architecture arm64
  need_update=1
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "arm: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get -o DPkg::Lock::Timeout=600 update -qq
  $SUDO apt-get -o DPkg::Lock::Timeout=600 install -y -qq --no-install-recommends "${missing[@]}"
elif [ "${need_update:-0}" = 1 ]; then
  $SUDO apt-get -o DPkg::Lock::Timeout=600 update -qq
fi

echo "== aarch64 cross build of warp/ and tests/warp (build-arm/)"
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S . -B build-arm -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake \
  -DRTM_WARP_ONLY=ON "${launcher[@]}" >/dev/null
cmake --build build-arm -j"$(nproc)" --target warp_tests rtm-warp-run
# RTM_ARM_BUILD_ONLY=1: stop here (scripts/count_instructions.sh runs build-arm/bin/rtm-warp-run itself).
[ "${RTM_ARM_BUILD_ONLY:-0}" = 1 ] && exit 0

# The arm64 loader and C library of multiarch (libc6:arm64), not QEMU_LD_PREFIX=/usr/aarch64-linux-gnu: see
# cmake/aarch64-linux-gnu.cmake.
unset QEMU_LD_PREFIX
export RTM_SWEEP_CASES=${RTM_SWEEP_CASES:-200}
filter=${RTM_ARM_TESTS:-'*FastKernels*:IsaTest.*:FastPrewarpCovers.*-*AllocatesNothing*'}
# One emulated process keeps about one core busy (most of the tests run on one thread): the tests go in GoogleTest
# shards (GTEST_TOTAL_SHARDS, GTEST_SHARD_INDEX: every shard-th test of the filter), as many processes side by side
# as the machine has cores.
cores=$(nproc)
# Runs filter $2 under QEMU_CPU=$1 in $3 shards, $cores at a time; prints each shard's output in order and fails if
# any shard fails.
run_shards() {
  local cpu=$1 f=$2 shards=$3 dir i rc failed=0
  dir=$(mktemp -d)
  for ((i = 0; i < shards; ++i)); do
    while (($(jobs -rp | wc -l) >= cores)); do wait -n || true; done
    (
      rc=0
      GTEST_TOTAL_SHARDS=$shards GTEST_SHARD_INDEX=$i QEMU_CPU=$cpu qemu-aarch64 build-arm/bin/warp_tests \
        --gtest_brief=1 --gtest_filter="$f" >"$dir/$i.log" 2>&1 || rc=$?
      echo "$rc" >"$dir/$i.rc"
    ) &
  done
  wait
  for ((i = 0; i < shards; ++i)); do
    cat "$dir/$i.log"
    rc=$(cat "$dir/$i.rc")
    [ "$rc" = 0 ] || { echo "arm: QEMU_CPU=$cpu shard $i of $shards failed (exit status $rc)"; failed=1; }
  done
  rm -rf "$dir"
  return "$failed"
}

# The CPU without SVE runs the target choice's tests and the main sweep (the neon target chosen by dispatch); the
# one with SVE everything in the filter, for both targets.
# The SVE run goes in ten shards a core, so that its longest tests (up to 40 s emulated) leave no core idle for long
# at the end: on 2 cores it took 205 s in one process, 121 s to 156 s in 10 shards, 132 s in 20.
for cpu in cortex-a72 max,sve=on; do
  f=$filter
  shards=$((10 * cores))
  if [ "$cpu" = cortex-a72 ]; then
    shards=$cores
    [ -z "${RTM_ARM_TESTS:-}" ] && f='IsaTest.*:*FastKernels.MatchTheReference*'
  fi
  echo "== tests/warp ($f) under qemu-aarch64, QEMU_CPU=$cpu, RTM_SWEEP_CASES=$RTM_SWEEP_CASES, $shards shards"
  start=$SECONDS
  run_shards "$cpu" "$f" "$shards"
  echo "arm: QEMU_CPU=$cpu passed in $((SECONDS - start)) s (emulated: not a speed measurement)"
done
