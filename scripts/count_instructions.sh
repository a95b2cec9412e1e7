#!/usr/bin/env bash
# Instructions per pre-warp on each SIMD target, counted under qemu-user: an estimate of the ARM targets' speed, where
# there is no ARM machine to time them on. Each count is one pre-warp of a procedural relief (rtm-warp-run,
# apps/warp_run.cpp, after a warm-up, one thread), every instruction of every translated block run between its two
# markers (scripts/count_instructions.py runs it under qemu and counts). The x86-64 targets qemu emulates (avx2, sse4
# and the generic kernels; not AVX-512) are counted too and timed natively, so that the table shows how well a ratio of
# instructions predicts a ratio of times on a CPU where both are known. Counts are exact (every pre-warp of a run counts
# the same); the native times are the minimum of RTM_COUNT_ROUNDS (default 5) interleaved rounds of 100 pre-warps each.
#
#   bash scripts/count_instructions.sh > counts.md     # progress on stderr; about 22 minutes on 2 cores
#
# RTM_COUNT_RELIEFS (default "bumps ridges bricks"), RTM_COUNT_METHODS (default "two-pass pipelined"),
# RTM_COUNT_SIZE (default 256). Uses build/ (configured as scripts/test.sh does if absent) and build-arm/
# (scripts/arm.sh with RTM_ARM_BUILD_ONLY=1 installs what it needs and builds it). ARM CPUs: neon and generic on
# QEMU_CPU=cortex-a72; sve on QEMU_CPU=max with 128-bit and 256-bit vectors (sve-default-vector-length: Neoverse V2
# and N2 have 128, V1 256).
set -euo pipefail
cd "$(dirname "$0")/.."
reliefs=${RTM_COUNT_RELIEFS:-bumps ridges bricks}
methods=${RTM_COUNT_METHODS:-two-pass pipelined}
size=${RTM_COUNT_SIZE:-256}
rounds=${RTM_COUNT_ROUNDS:-5}

echo "count: building rtm-warp-run for x86-64 (build/) and aarch64 (build-arm/)" >&2
[ -f build/build.ninja ] || cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build --target rtm-warp-run >/dev/null
RTM_ARM_BUILD_ONLY=1 bash scripts/arm.sh >&2
unset QEMU_LD_PREFIX  # scripts/arm.sh: the arm64 loader of multiarch

dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

# One count: arch, QEMU_CPU, relief, method, target; writes $dir/arch.cpu.relief.method.target.
count() {
  local arch=$1 cpu=$2 relief=$3 method=$4 isa=$5 bin=build-arm/bin/rtm-warp-run qemu=qemu-aarch64
  [ "$arch" = x86-64 ] && bin=build/bin/rtm-warp-run qemu=qemu-x86_64
  # GenuineIntel: the avx2 kernels store as on Intel's cores and Zen 5 (qemu's max CPU says AMD, of a family before
  # Zen 5: avx2_masked_store_slow, warp/isa.h).
  python3 scripts/count_instructions.py rtm_warp_run_begin rtm_warp_run_end -- "$qemu" -cpu "$cpu" "$bin" "$relief" \
    "$size" "$method" "$isa" 1 >"$dir/$arch.$cpu.$relief.$method.$isa"
}

jobs_list=()
for r in $reliefs; do
  for m in $methods; do
    for isa in avx2 sse4 generic; do jobs_list+=("x86-64 max,vendor=GenuineIntel $r $m $isa"); done
    jobs_list+=("aarch64 cortex-a72 $r $m neon" "aarch64 cortex-a72 $r $m generic")
    for vl in 16 32; do jobs_list+=("aarch64 max,sve=on,sve-default-vector-length=$vl $r $m sve"); done
  done
done
cores=$(nproc)
n=0
for j in "${jobs_list[@]}"; do
  while (($(jobs -rp | wc -l) >= cores)); do wait -n; done
  n=$((n + 1))
  echo "count: $n of ${#jobs_list[@]}: $j" >&2
  # shellcheck disable=SC2086
  count $j &
done
wait
for j in "${jobs_list[@]}"; do
  read -r a c r m i <<<"$j"
  [ -s "$dir/$a.$c.$r.$m.$i" ] || { echo "count: no count for $j" >&2; exit 1; }
done

# Native times of the x86-64 targets, interleaved rounds.
echo "count: timing the x86-64 targets natively ($rounds rounds)" >&2
native=(avx512 avx2 sse4 generic)
for ((k = 0; k < rounds; ++k)); do
  for r in $reliefs; do
    for m in $methods; do
      for isa in "${native[@]}"; do
        if build/bin/rtm-warp-run "$r" "$size" "$m" "$isa" 100 >"$dir/t" 2>/dev/null; then
          sed -E 's/.*min ([0-9.]+) ms.*/\1/' "$dir/t" >>"$dir/native.$r.$m.$isa"
        fi
      done
    done
  done
done

python3 - "$dir" "$size" "$reliefs" "$methods" "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | xargs)" <<'EOF'
import os, sys
d, size, reliefs, methods, cpu = sys.argv[1], int(sys.argv[2]), sys.argv[3].split(), sys.argv[4].split(), sys.argv[5]
texels = size * size
def cnt(a, c, r, m, i):
    return int(open(os.path.join(d, f"{a}.{c}.{r}.{m}.{i}")).read())
def native(r, m, i):
    p = os.path.join(d, f"native.{r}.{m}.{i}")
    return min(float(x) for x in open(p)) if os.path.exists(p) else None
x86 = "max,vendor=GenuineIntel"
print(f"Instructions per pre-warp, {size}^2, one thread (rtm-warp-run under qemu-user 7.2); native times on {cpu}.\n")
print("| relief | method | target | CPU (qemu) | instructions | per texel | generic / target, instructions | "
      "generic / target, native time | time ratio / instruction ratio |")
print("|---|---|---|---|---:|---:|---:|---:|---:|")
for r in reliefs:
    for m in methods:
        g86 = cnt("x86-64", x86, r, m, "generic")
        tg = native(r, m, "generic")
        for i in ("avx2", "sse4", "generic"):
            c = cnt("x86-64", x86, r, m, i)
            t = native(r, m, i)
            ir = g86 / c
            tr = tg / t if (t and tg) else None
            print(f"| {r} | {m} | {i} | x86-64 `max` | {c:,} | {c / texels:.1f} | {ir:.2f}x | "
                  + (f"{tr:.2f}x | {tr / ir:.2f} |" if tr else "- | - |"))
        t5 = native(r, m, "avx512")
        if t5 and tg:
            print(f"| {r} | {m} | avx512 | (not emulated) | - | - | - | {tg / t5:.2f}x | - |")
        ga = cnt("aarch64", "cortex-a72", r, m, "generic")
        for c_, i, label in (("cortex-a72", "neon", "cortex-a72"),
                             ("max,sve=on,sve-default-vector-length=16", "sve", "`max`, SVE 128-bit"),
                             ("max,sve=on,sve-default-vector-length=32", "sve", "`max`, SVE 256-bit"),
                             ("cortex-a72", "generic", "cortex-a72")):
            c = cnt("aarch64", c_, r, m, i)
            print(f"| {r} | {m} | {i} | aarch64 {label} | {c:,} | {c / texels:.1f} | {ga / c:.2f}x | - | - |")
EOF
