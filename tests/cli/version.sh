#!/usr/bin/env bash
# rtm --version: one line "rtm X.Y.Z" on stdout, X.Y.Z being project(rtm VERSION X.Y.Z) of CMakeLists.txt, nothing on
# stderr, exit 0; and rtm --help lists --version.
. "$(dirname "$0")/lib.bash"
version=$(sed -n 's/^project(rtm VERSION \([0-9]*\.[0-9]*\.[0-9]*\) .*/\1/p' "$SRC/CMakeLists.txt")
if [ -z "$version" ]; then
  echo "FAIL: no project(rtm VERSION X.Y.Z ...) in $SRC/CMakeLists.txt"
  fails=$((fails + 1))
fi
expect_ok --version
if [ "$(cat "$T/stdout")" = "rtm $version" ] && [ ! -s "$T/stderr" ]; then
  passes=$((passes + 1))
else
  echo "FAIL: rtm --version: want 'rtm $version' alone on stdout, got '$(cat "$T/stdout")', stderr '$(cat "$T/stderr")'"
  fails=$((fails + 1))
fi
expect_ok --help
if grep -q -- '--version' "$T/stdout"; then
  passes=$((passes + 1))
else
  echo "FAIL: rtm --help does not list --version"
  fails=$((fails + 1))
fi
finish
