#!/usr/bin/env bash
# Formatting: the C++ sources against the root .clang-format, and no line over 120 columns in C++, CMake and shell
# files (Markdown is left out: its tables cannot wrap).
#   scripts/format.sh --check   lists the C++ files clang-format would change and every line over 120 columns;
#                               exit 1 if there is any, 0 if none
#   scripts/format.sh --fix     formats the C++ files in place, then checks as --check does (a line clang-format
#                               cannot wrap, in a string, a shell or a CMake file, is left for a hand to wrap)
# CLANG_FORMAT picks the binary (default clang-format, Debian 12's clang-format 14: other versions format some
# constructs differently).
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:-}
if [ $# -ne 1 ] || { [ "$mode" != --check ] && [ "$mode" != --fix ]; }; then
  echo "usage: scripts/format.sh --check|--fix" >&2
  exit 2
fi
CLANG_FORMAT=${CLANG_FORMAT:-clang-format}
if ! command -v "$CLANG_FORMAT" >/dev/null; then
  echo "format.sh: $CLANG_FORMAT not found (Debian package clang-format; scripts/setup.sh installs it)" >&2
  exit 1
fi

# The project's files: tracked and new ones, not ignored (build trees and the generated glad loader are ignored).
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git ls-files -co --exclude-standard | sort -u)
else
  mapfile -t files < <(find . -path ./build\* -prune -o -type f -print | sed 's|^\./||' | sort)
fi
cxx=()
text=()
for f in "${files[@]}"; do
  [ -f "$f" ] || continue  # deleted but still in the index
  case "$f" in
    *.h | *.hpp | *.c | *.cpp) cxx+=("$f") ;;
  esac
  case "$f" in
    *.h | *.hpp | *.c | *.cpp | *.in | *.cmake | CMakeLists.txt | */CMakeLists.txt | *.sh | *.bash | .ci/*)
      text+=("$f") ;;
  esac
done

if [ "$mode" = --fix ]; then
  "$CLANG_FORMAT" -i --style=file "${cxx[@]}"
fi

bad=0
for f in "${cxx[@]}"; do
  if ! "$CLANG_FORMAT" --style=file --dry-run --Werror "$f" >/dev/null 2>&1; then
    echo "$f: differs from .clang-format (scripts/format.sh --fix)"
    bad=$((bad + 1))
  fi
done
# Columns are characters, not bytes (the sources hold UTF-8 such as an em dash).
long=$(LC_ALL=C.UTF-8 grep -Hn '.\{121,\}' "${text[@]}" | cut -d: -f1,2 || true)
if [ -n "$long" ]; then
  sed 's/$/: over 120 columns/' <<<"$long"
  bad=$((bad + $(grep -c '' <<<"$long")))
fi
if [ "$bad" -gt 0 ]; then
  echo "format.sh: $bad problem(s) ($("$CLANG_FORMAT" --version | head -n 1))" >&2
  exit 1
fi
echo "format.sh: ${#cxx[@]} C++ files formatted, ${#text[@]} files within 120 columns"
