#!/usr/bin/env bash
# scripts/compare_builds.py: two rtm builds' pre-warp times interleaved (here one build against itself, on the
# generic kernels and the SSE4 target, which every x86-64 machine that runs the suite has; on others the script's
# refusal of a missing target is what is checked). The report's shape (a row per relief, size, reconstruction and
# thread count, in order; the summary line; the progress on stderr), not its figures: no test asserts a time. Bad
# arguments and failing runs: exit 1, one line naming the value or the command (after the progress of the runs
# before it).
. "$(dirname "$0")/lib.bash"
CMP="$SRC/scripts/compare_builds.py"
small=(--rounds 2 --sizes 32,48 --reliefs bumps --methods two-pass,pipelined --threads 1 --min-time 0.01)

# A run that must exit 1 and print nothing, its last line on stderr matching PATTERN, the lines before it (if any)
# its progress.
cmp_refuses() {
  local pattern=$1 got=0
  shift
  python3 "$CMP" "$@" >"$T/stdout" 2>"$T/stderr" || got=$?
  if [ "$got" = 1 ] && tail -n 1 "$T/stderr" | grep -Eq -- "^compare_builds: .*$pattern" &&
    [ "$(head -n -1 "$T/stderr" | grep -vc '^compare_builds: round ')" = 0 ] && [ ! -s "$T/stdout" ]; then
    passes=$((passes + 1))
  else
    echo "FAIL: compare_builds.py $*: want exit 1 and a last line /$pattern/; got exit $got:" \
      "$(cat "$T/stdout" "$T/stderr")"
    fails=$((fails + 1))
  fi
}

if "$RTM" bench --isa sse4 --sizes 32 --reliefs bumps --methods two-pass --threads 1 --min-time 0.01 --no-exact \
  --no-reference --no-table1 --no-scene >/dev/null 2>&1; then
  # Four rows (sizes 32 and 48, in that order, each two-pass then pipelined), every figure a number, the lowest
  # round's ratio at most the highest; the summary counts the four rows; eight runs (2 rounds x 2 sizes x 2 builds).
  if python3 "$CMP" "${small[@]}" "$RTM" generic "$RTM" sse4 >"$T/report" 2>"$T/progress"; then
    num='[0-9.]+'
    row="^\\| bumps \\| (32|48)\\^2 \\| (two-pass|pipelined) \\| 1 \\| $num \\| $num \\| $num \\| $num, $num \\|\$"
    rows=$(grep -E "$row" "$T/report" | cut -d'|' -f3,4 | tr -d ' ' | paste -sd' ')
    if [ "$rows" = "32^2|two-pass 32^2|pipelined 48^2|two-pass 48^2|pipelined" ] &&
      grep -Eq '^4 rows: B speed / A from [0-9.]+ to [0-9.]+, median [0-9.]+; >= 0.95 in [0-4]$' "$T/report" &&
      head -1 "$T/report" | grep -q "^A: $RTM --isa generic; B: $RTM --isa sse4; 2 rounds$" &&
      [ "$(grep -c '^compare_builds: round [12] of 2, \(32\|48\)^2, [AB]$' "$T/progress")" = 8 ] &&
      awk -F'|' '/^\| bumps/ { split($9, r, ", "); if (r[1] + 0 > r[2] + 0) bad = 1 } END { exit bad }' \
        "$T/report"; then
      passes=$((passes + 1))
    else
      echo "FAIL: compare_builds.py generic against sse4: rows '$rows'; $(cat "$T/report" "$T/progress")"
      fails=$((fails + 1))
    fi
  else
    echo "FAIL: compare_builds.py generic against sse4 exited $?: $(cat "$T/progress")"
    fails=$((fails + 1))
  fi
else
  cmp_refuses "gave no row of target sse4|exited 2: .*sse4" "${small[@]}" "$RTM" generic "$RTM" sse4
fi

cmp_refuses "'$T/none' is not an executable file" "${small[@]}" "$T/none" generic "$RTM" generic
cmp_refuses "size 'x' is not a positive integer \(in '32,x'\)" --sizes 32,x "$RTM" generic "$RTM" generic
cmp_refuses "method 'flat' is none of two-pass, pipelined" --methods flat "$RTM" generic "$RTM" generic
cmp_refuses "\-\-rounds '0' is not a positive number" --rounds 0 "$RTM" generic "$RTM" generic
cmp_refuses "\-\-min-time 'soon' is not a positive number" --min-time soon "$RTM" generic "$RTM" generic
cmp_refuses "required: .*b_isa" "$RTM" generic "$RTM"
# A run that fails: rtm bench refuses an unknown target (exit 2), named with the command.
cmp_refuses "'$RTM bench --sizes 32 --isa avx1024 .*' exited 2: " "${small[@]}" "$RTM" avx1024 "$RTM" generic
# A program that runs but is not rtm (true writes no JSON), run after rtm wrote its report: the run's own report or
# nothing, never the one before.
cmp_refuses "'$(type -P true) bench .*' wrote no report of rows to .*bench.json \(FileNotFoundError" "${small[@]}" \
  "$RTM" generic "$(type -P true)" generic
finish
