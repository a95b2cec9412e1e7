#!/usr/bin/env bash
# rtm on the CPUs people have (issue #18), emulated by qemu-x86_64: the x86-64 baseline without SSE4 (qemu64), SSE4
# with AES and CLMUL (Westmere: Highway's SSE4 target needs all three) and AVX2 (Haswell). The kernels' tests force
# each target on this machine (hwy::SetSupportedTargetsForTest); this runs the program itself, so that the choice
# comes from the emulated CPU's CPUID as on a real one. On each: `--isa auto` picks that CPU's target, and the
# pre-warped texture (both reconstructions, two threads) is the reference kernels' to the byte; a target the CPU
# lacks, by --isa or RTM_ISA, is exit 2 and one line; and `rtm render`, which also runs the texture mapping (Mesa's
# llvmpipe, which compiles its shaders for the CPU it finds), succeeds. A SIGILL anywhere in rtm, for example an
# inline function compiled with the kernel files' SSE4 baseline (warp/CMakeLists.txt) and kept by the linker for
# the other callers too, fails here on the baseline CPU.
. "$(dirname "$0")/lib.bash"

if [ "$(uname -m)" != x86_64 ] || ! command -v qemu-x86_64 >/dev/null; then
  echo "skipped: not an x86-64 machine with qemu-x86_64 (apt-get install qemu-user)"
  finish
  exit
fi
# Not in the sanitizer build: qemu-user backs AddressSanitizer's shadow memory with real memory (tests/cli/warp_run.sh).
if ldd "$RTM" | grep -q libasan; then
  echo "skipped: sanitizer build"
  finish
  exit
fi

EYE=0.45,0.3,1.2  # oblique enough that the bricks' rows fold over (both row orders run)
# run_on MODEL OUT ARGS...: rtm under the emulated CPU MODEL, its stderr in $T/stderr (qemu's own warnings about
# features its emulator lacks left out).
run_on() {
  local model=$1 out=$2
  shift 2
  local got=0
  qemu-x86_64 -cpu "$model" "$RTM" "$@" >"$out" 2>"$T/stderr.raw" || got=$?
  grep -v '^qemu-x86_64: warning: TCG' "$T/stderr.raw" >"$T/stderr" || true
  return "$got"
}

for relief in bumps bricks; do
  for method in two-pass pipelined; do
    "$RTM" prewarp --relief "$SRC/media/$relief.relief.json" --eye $EYE --method $method --isa generic \
      --out "$T/$relief-$method-ref.png" >/dev/null 2>&1 || echo "reference run failed" >"$T/$relief-$method-ref.png"
  done
done

for pair in qemu64:generic Westmere:sse4 Haswell:avx2; do
  model=${pair%%:*} want=${pair##*:}
  for relief in bumps bricks; do
    for method in two-pass pipelined; do
      out="$T/$model-$relief-$method"
      what="rtm prewarp ($relief, $method) on $model"
      if ! run_on "$model" "$T/stdout" prewarp --relief "$SRC/media/$relief.relief.json" --eye $EYE \
        --method $method --threads 2 --out "$out.png" --json "$out.json"; then
        echo "FAIL: $what: exit status not 0: $(cat "$T/stderr")"
        fails=$((fails + 1))
        continue
      fi
      isa=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["isa"])' "$out.json" 2>&1)
      if [ "$isa" != "$want" ]; then
        echo "FAIL: $what: --isa auto ran \"$isa\", want \"$want\""
        fails=$((fails + 1))
      elif ! cmp -s "$out.png" "$T/$relief-$method-ref.png"; then
        echo "FAIL: $what: the texture differs from the reference kernels' ($("$RTM" diff "$T/$relief-$method-ref.png" \
          "$out.png" 2>&1 | tr '\n' ' '))"
        fails=$((fails + 1))
      else
        passes=$((passes + 1))
      fi
    done
  done
done

# A target the CPU lacks: exit 2, one line naming it (--isa), or naming RTM_ISA and its value.
refused_on() {  # refused_on MODEL PATTERN ARGS...
  local model=$1 pattern=$2
  shift 2
  local got=0
  run_on "$model" "$T/stdout" "$@" || got=$?
  if [ "$got" = 2 ] && [ "$(grep -c '' "$T/stderr")" = 1 ] && grep -Eq -- "$pattern" "$T/stderr"; then
    passes=$((passes + 1))
  else
    echo "FAIL: rtm $* on $model: want exit 2 and one line /$pattern/; got exit $got: $(cat "$T/stderr")"
    fails=$((fails + 1))
  fi
}
M="$SRC/media/bumps.relief.json"
refused_on qemu64 'cannot run target "sse4"' prewarp --relief "$M" --eye $EYE --isa sse4 --out "$T/x.png"
refused_on Westmere 'cannot run target "avx2"' prewarp --relief "$M" --eye $EYE --isa avx2 --out "$T/x.png"
refused_on Haswell 'cannot run target "avx512"' prewarp --relief "$M" --eye $EYE --isa avx512 --out "$T/x.png"
RTM_ISA=avx2 refused_on Westmere 'RTM_ISA: this CPU cannot run target "avx2"' \
  prewarp --relief "$M" --eye $EYE --out "$T/x.png"
if [ -e "$T/x.png" ]; then
  echo "FAIL: a refused run wrote its output"
  fails=$((fails + 1))
fi

# The whole frame on the baseline CPU: pre-warp and llvmpipe's texture mapping. llvmpipe's code differs with the CPU's
# vector width (its rasterization rounds differently: a few pixels of the edge, values up to about 5 of 255 measured
# against this machine's AVX-512 run), so the frame is compared by coverage, not to the byte.
"$RTM" render --relief "$M" --orbit 30,20,2 --size 256x256 --out "$T/render-native.png" >/dev/null 2>&1
if ! run_on qemu64 "$T/stdout" render --relief "$M" --orbit 30,20,2 --size 256x256 --out "$T/render-qemu64.png"; then
  echo "FAIL: rtm render on qemu64: exit status not 0: $(cat "$T/stderr")"
  fails=$((fails + 1))
else
  iou=$("$RTM" diff "$T/render-native.png" "$T/render-qemu64.png" 2>&1 | awk '$1 == "iou" {print $2}')
  if python3 -c 'import sys; sys.exit(0 if float(sys.argv[1]) >= 0.999 else 1)' "${iou:-0}" 2>/dev/null; then
    passes=$((passes + 1))
  else
    echo "FAIL: rtm render on qemu64: coverage against this machine's frame iou ${iou:-?}, want >= 0.999"
    fails=$((fails + 1))
  fi
fi
finish
