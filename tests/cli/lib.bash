# Shared by the command-line tests: RTM is the binary, SRC the source tree, T a fresh temporary folder.
set -u
RTM=$1
SRC=$2
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fails=0
passes=0

# expect_fail STATUS PATTERN -- ARGS...: rtm must exit with STATUS, print exactly one line on stderr matching
# PATTERN (grep -E), and not crash.
expect_fail() {
  local want=$1 pattern=$2
  shift 3
  local err
  "$RTM" "$@" >"$T/stdout" 2>"$T/stderr"
  local got=$?
  err=$(cat "$T/stderr")
  local lines
  lines=$(grep -c '' "$T/stderr")
  if [ "$got" != "$want" ] || ! grep -Eq -- "$pattern" "$T/stderr" || [ "$lines" != 1 ]; then
    echo "FAIL: rtm $*"
    echo "  want exit $want and one line matching /$pattern/; got exit $got, $lines line(s): $err"
    fails=$((fails + 1))
  else
    passes=$((passes + 1))
  fi
}

expect_ok() {
  if ! "$RTM" "$@" >"$T/stdout" 2>"$T/stderr"; then
    echo "FAIL: rtm $* exited $?: $(cat "$T/stderr")"
    fails=$((fails + 1))
  else
    passes=$((passes + 1))
  fi
}

finish() {
  echo "$passes passed, $fails failed"
  [ "$fails" = 0 ]
}

# A valid 4x4 relief in $T/ok.relief.json, built with rtm-make-media's images replaced by tiny ones via PPM/PGM.
make_small_relief() {
  local dir=$1
  mkdir -p "$dir"
  printf 'P3\n4 4\n255\n' >"$dir/c.ppm"
  for i in $(seq 16); do printf '200 100 50\n' >>"$dir/c.ppm"; done
  printf 'P2\n4 4\n255\n' >"$dir/d.pgm"
  for i in $(seq 16); do printf '%d\n' $((i * 10)) >>"$dir/d.pgm"; done
  cat >"$dir/ok.relief.json" <<JSON
{ "color": "c.ppm", "displacement": "d.pgm", "displacement_range": [0.0, 0.5],
  "origin": [0, 0, 0], "a": [0.25, 0, 0], "b": [0, 0.25, 0] }
JSON
}
