#!/usr/bin/env bash
# rtm-warp-run (apps/warp_run.cpp) and the instruction counter of scripts/count_instructions.sh: the program runs a
# procedural relief on each target this CPU has and refuses bad arguments with one line naming the value; under
# qemu-x86_64 the counter finds the work between the program's two markers, the same count for every pre-warp, and
# refuses a program that never runs them, one that fails, and a missing qemu.
. "$(dirname "$0")/lib.bash"
RUN=$(dirname "$RTM")/rtm-warp-run

# A run that must succeed and print PATTERN.
expect_run() {
  local pattern=$1
  shift
  if "$RUN" "$@" >"$T/stdout" 2>"$T/stderr" && grep -Eq -- "$pattern" "$T/stdout"; then
    passes=$((passes + 1))
  else
    echo "FAIL: rtm-warp-run $*: want /$pattern/; got $(cat "$T/stdout" "$T/stderr")"
    fails=$((fails + 1))
  fi
}
# A run that must exit 1 with one line on stderr matching PATTERN and print nothing.
expect_refused() {
  local pattern=$1
  shift
  local got=0
  "$RUN" "$@" >"$T/stdout" 2>"$T/stderr" || got=$?
  if [ "$got" = 1 ] && [ "$(grep -c '' "$T/stderr")" = 1 ] && grep -Eq -- "$pattern" "$T/stderr" &&
    [ ! -s "$T/stdout" ]; then
    passes=$((passes + 1))
  else
    echo "FAIL: rtm-warp-run $*: want exit 1 and one line /$pattern/; got exit $got: $(cat "$T/stdout" "$T/stderr")"
    fails=$((fails + 1))
  fi
}

expect_run '^bumps 32 two-pass isa generic: 3 pre-warps after a warm-up, min [0-9.]+ ms, median [0-9.]+ ms$' \
  bumps 32 two-pass generic 3
expect_run '^ridges 48 pipelined isa [a-z0-9]+: 0 pre-warps after a warm-up$' ridges 48 pipelined auto 0
for isa in avx512 avx3 avx2 sse4 neon sve; do
  if "$RUN" bricks 32 two-pass "$isa" 1 >/dev/null 2>&1; then
    expect_run "^bricks 32 pipelined isa $isa: 1 pre-warps" bricks 32 pipelined "$isa" 1 2
  else
    expect_refused "target \"$isa\"" bricks 32 pipelined "$isa" 1
  fi
done
expect_run '^lifted-bricks 32 two-pass isa generic: 1 pre-warps after a warm-up, min [0-9.]+ ms' \
  lifted-bricks 32 two-pass generic 1
expect_refused 'unknown procedural relief "wall"' wall 32 two-pass generic 1
expect_refused "SIZE '8' is not an integer from 16 to 4096" bumps 8 two-pass generic 1
expect_refused "SIZE '32x' is not" bumps 32x two-pass generic 1
expect_refused "METHOD 'flat' is neither" bumps 32 flat generic 1
expect_refused "ISA 'avx1024' is none of" bumps 32 two-pass avx1024 1
expect_refused "REPEAT '-1' is not" bumps 32 two-pass generic -1
expect_refused "THREADS 'x' is not" bumps 32 two-pass generic 1 x
expect_refused '^usage: rtm-warp-run' bumps 32

# The counter, on the generic kernels (the same instructions whatever the CPU qemu emulates). Not in the sanitizer
# build: qemu-user backs AddressSanitizer's shadow memory with real memory (tried: the 32^2 run filled this machine's
# 24 GB and was killed). The Release suite tests the counter; the arguments above are checked in both.
if ldd "$RUN" | grep -q libasan; then
  finish
  exit
fi
# Three pre-warps with --top 2: three counts, one a pre-warp, all the same (the same work counts the same: the clock
# reads around each lie outside its markers) and far above nothing; then the two functions that ran the most of them,
# the first a function of rtm's (most of a pre-warp of the generic kernels is in their row and column warps).
python3 "$SRC/scripts/count_instructions.py" --top 2 rtm_warp_run_begin rtm_warp_run_end -- \
  qemu-x86_64 -cpu max,vendor=GenuineIntel "$RUN" bumps 32 two-pass generic 3 >"$T/top" || echo failed >>"$T/top"
mapfile -t c < <(head -n 3 "$T/top")
if [ "$(grep -c '' "$T/top")" = 5 ] && [[ ${c[0]} =~ ^[0-9]+$ ]] && ((c[0] > 100000)) && [ "${c[1]}" = "${c[0]}" ] &&
  [ "${c[2]}" = "${c[0]}" ] && sed -n 4p "$T/top" | grep -Eq '^ *[0-9]+ +[0-9.]+% _ZN3rtm'; then
  passes=$((passes + 1))
else
  echo "FAIL: count_instructions.py --top 2 of 3 pre-warps: $(cat "$T/top")"
  fails=$((fails + 1))
fi
# A program that never runs the markers (true): exit 1, one line naming the marker. A program that fails (false):
# exit 1, one line naming the command and its status. No qemu; no command.
counter_refuses() {  # counter_refuses PATTERN -- COMMAND...
  local pattern=$1 got=0
  shift 2
  python3 "$SRC/scripts/count_instructions.py" rtm_warp_run_begin rtm_warp_run_end -- "$@" >"$T/stdout" \
    2>"$T/stderr" || got=$?
  if [ "$got" = 1 ] && [ "$(grep -c '' "$T/stderr")" = 1 ] && grep -Eq -- "$pattern" "$T/stderr" &&
    [ ! -s "$T/stdout" ]; then
    passes=$((passes + 1))
  else
    echo "FAIL: count_instructions.py -- $*: want exit 1 and one line /$pattern/; got exit $got:" \
      "$(cat "$T/stdout" "$T/stderr")"
    fails=$((fails + 1))
  fi
}
counter_refuses '^count_instructions: rtm_warp_run_begin ran 0 times and rtm_warp_run_end 0' -- qemu-x86_64 \
  "$(type -P true)"
counter_refuses "^count_instructions: qemu-x86_64 $(type -P false) exited with status 1\$" -- qemu-x86_64 \
  "$(type -P false)"
counter_refuses "^count_instructions: no-such-qemu: No such file or directory" -- no-such-qemu "$RUN"
counter_refuses '^count_instructions: usage:' --
finish
