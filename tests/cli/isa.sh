#!/usr/bin/env bash
# rtm prewarp --isa, rtm bench --isa and RTM_ISA: every target this CPU runs gives the generic kernels' image byte
# for byte and --json names the target that ran; an unknown target, or one this CPU lacks, is exit 2 with one line
# and no output file.
. "$(dirname "$0")/lib.bash"
R=$SRC/media/bumps.relief.json

expect_ok prewarp --relief "$R" --eye 0.3,0.2,2 --out "$T/generic.png" --isa generic --json "$T/generic.json"
grep -q '"isa": "generic"' "$T/generic.json" ||
  { echo "FAIL: generic.json does not name generic"; fails=$((fails + 1)); }
ran=0
for isa in avx512 avx3 avx2 sse4 neon sve; do
  if "$RTM" prewarp --relief "$R" --eye 0.3,0.2,2 --out "$T/$isa.png" --isa $isa --json "$T/$isa.json" \
      2>"$T/stderr"; then
    ran=$((ran + 1))
    if cmp -s "$T/generic.png" "$T/$isa.png" && grep -q "\"isa\": \"$isa\"" "$T/$isa.json"; then
      passes=$((passes + 1))
    else
      echo "FAIL: --isa $isa: image differs from generic or --json does not name $isa"
      fails=$((fails + 1))
    fi
  else
    # A target this CPU or build lacks: exit 2, one line naming it, no image.
    expect_fail 2 "isa.*cannot run.*\"$isa\"" -- prewarp --relief "$R" --eye 0.3,0.2,2 --out "$T/no_$isa.png" \
      --isa $isa
    [ ! -e "$T/no_$isa.png" ] || { echo "FAIL: --isa $isa left an image"; fails=$((fails + 1)); }
  fi
done
[ "$ran" -ge 1 ] || { echo "FAIL: no SIMD target ran"; fails=$((fails + 1)); }
# The environment variable chooses for "auto".
RTM_ISA=generic "$RTM" prewarp --relief "$R" --eye 0.3,0.2,2 --out "$T/env.png" --json "$T/env.json" &&
  grep -q '"isa": "generic"' "$T/env.json" && passes=$((passes + 1)) ||
  { echo "FAIL: RTM_ISA=generic"; fails=$((fails + 1)); }
expect_fail 2 'isa.*unknown target "mmx"' -- prewarp --relief "$R" --eye 0.3,0.2,2 --out "$T/o1.png" --isa mmx
[ ! -e "$T/o1.png" ] || { echo "FAIL: --isa mmx left an image"; fails=$((fails + 1)); }
RTM_ISA=mmx expect_fail 2 'RTM_ISA.*"mmx"' -- prewarp --relief "$R" --eye 0.3,0.2,2 --out "$T/o2.png"
expect_fail 2 'isa.*unknown target "avx1024"' -- bench --isa generic,avx1024 --sizes 16 --reliefs bumps --no-table1
# bench --isa: the report has a row per target and the SIMD targets section.
expect_ok bench --isa sse4,generic --sizes 32 --reliefs bumps --methods two-pass --threads 1 --no-exact \
  --no-table1 --min-time 0 --json "$T/bench.json"
if "$RTM" prewarp --relief "$R" --eye 0.3,0.2,2 --out "$T/s.png" --isa sse4 2>/dev/null; then
  grep -q "### SIMD targets" "$T/stdout" && grep -q '"isa": "sse4"' "$T/bench.json" && passes=$((passes + 1)) ||
    { echo "FAIL: bench --isa sse4,generic: no SIMD targets section or no sse4 row"; fails=$((fails + 1)); }
fi
finish
