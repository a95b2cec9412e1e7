#!/usr/bin/env bash
# Builds the libFuzzer targets of fuzz/ with clang, AddressSanitizer and UndefinedBehaviorSanitizer (build-fuzz/),
# and runs them for a bounded time, side by side. Exit status non-zero on any finding.
#
#   RTM_FUZZ_SECONDS  seconds each target runs (default 60)
#   RTM_FUZZ_TARGETS  which targets (default: "fuzz_relief_manifest fuzz_relief_loader")
#
# Each target starts from its seeds (fuzz/corpus/relief_manifest/, checked in; the loader's are written here, one
# small image per format) plus what earlier runs kept in build-fuzz/corpus/<target>/. A finding leaves the input that
# caused it in build-fuzz/findings/<target>/ (crash-*, leak-*, timeout-*, oom-*) and the report at the end of
# build-fuzz/logs/<target>.log. Replay one:  build-fuzz/bin/<target> build-fuzz/findings/<target>/crash-...
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${RTM_FUZZ_SECONDS:-60}
targets=${RTM_FUZZ_TARGETS:-"fuzz_relief_manifest fuzz_relief_loader fuzz_object_manifest fuzz_scene_manifest"}
B=build-fuzz

echo "== libFuzzer targets (clang, address + undefined), ${seconds} s each"
cmake -S . -B $B -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DRTM_FUZZ=ON -DRTM_BUILD_TESTS=OFF >/dev/null
# shellcheck disable=SC2086
cmake --build $B -j"$(nproc)" --target $targets

# The loader's seeds: byte 0 selects colour (bit 0 clear) or displacement (set) and the extension (bits 1..4, the
# order of kExtensions in fuzz/fuzz_relief_loader.cpp); the rest is a small valid image of that format, 6x4 like
# the target's partner images, so that mutations which keep the size reach past the size check.
seeds=$B/seeds/relief_loader
rm -rf "$seeds"
mkdir -p "$seeds"
exts=(png ppm pgm pfm jpg tif exr bmp tga hdr gif sgi webp psd dds "")
prefixed() { # prefixed SELECTOR FILE OUT
  { printf "\\x$(printf %02x "$1")"; cat "$2"; } >"$3"
}
{ printf 'P3\n6 4\n255\n'; for i in $(seq 24); do echo "$((i * 10)) $((250 - i * 10)) 90"; done; } >"$B/seeds/c.ppm"
{ printf 'P2\n6 4\n255\n'; for i in $(seq 24); do echo "$((i * 10))"; done; } >"$B/seeds/d.pgm"
{ printf 'Pf\n6 4\n-1.0\n'; head -c 96 /dev/zero; } >"$B/seeds/d.pfm" # 24 zeros, little endian float
prefixed $((1 << 1)) "$B/seeds/c.ppm" "$seeds/ppm_color"
prefixed $(((2 << 1) | 1)) "$B/seeds/d.pgm" "$seeds/pgm_disp"
prefixed $(((3 << 1) | 1 | 32)) "$B/seeds/d.pfm" "$seeds/pfm_disp_threshold"
if command -v oiiotool >/dev/null; then
  for i in "${!exts[@]}"; do
    ext=${exts[$i]}
    [ -n "$ext" ] || continue
    # Formats OpenImageIO cannot write (psd, dds, ...) simply get no seed.
    if oiiotool --pattern checker:width=2:height=2 6x4 3 -d uint8 -o "$B/seeds/rgb.$ext" >/dev/null 2>&1; then
      prefixed $((i << 1)) "$B/seeds/rgb.$ext" "$seeds/${ext}_color"
      prefixed $(((i << 1) | 32 | 64)) "$B/seeds/rgb.$ext" "$seeds/${ext}_color_options"
    fi
    if oiiotool --pattern fill:left=0:right=1 6x4 1 -o "$B/seeds/grey.$ext" >/dev/null 2>&1; then
      prefixed $(((i << 1) | 1)) "$B/seeds/grey.$ext" "$seeds/${ext}_disp"
      prefixed $(((15 << 1) | 1)) "$B/seeds/grey.$ext" "$seeds/${ext}_disp_no_extension"
    fi
  done
  oiiotool --pattern checker:width=1:height=1 6x4 4 -d uint8 -o "$B/seeds/rgba.png" >/dev/null 2>&1 &&
    prefixed 0 "$B/seeds/rgba.png" "$seeds/png_rgba"
  oiiotool --pattern fill:left=0:right=1 6x4 1 -d uint16 -o "$B/seeds/grey16.png" >/dev/null 2>&1 &&
    prefixed 1 "$B/seeds/grey16.png" "$seeds/png16_disp"
  oiiotool --pattern fill:left=0:right=1 6x4 1 -d half -o "$B/seeds/half.exr" >/dev/null 2>&1 &&
    prefixed $(((6 << 1) | 1)) "$B/seeds/half.exr" "$seeds/exr_half_disp"
else
  echo "note: oiiotool (openimageio-tools) not found: the loader starts from PNM seeds only"
fi

seed_dir() {
  case $1 in
    fuzz_relief_manifest) echo fuzz/corpus/relief_manifest ;;
    fuzz_relief_loader) echo "$seeds" ;;
    fuzz_object_manifest) echo fuzz/corpus/object_manifest ;;
    fuzz_scene_manifest) echo fuzz/corpus/scene_manifest ;;
  esac
}
extra_flags() {
  case $1 in
    fuzz_relief_manifest) echo "-dict=fuzz/relief_manifest.dict" ;;
    fuzz_object_manifest) echo "-dict=fuzz/object_manifest.dict" ;;
    fuzz_scene_manifest) echo "-dict=fuzz/scene_manifest.dict" ;;
  esac
}

# One target per core, side by side. -timeout: one input taking longer is a hang (a finding); -rss_limit_mb: so is
# needing more memory (an image within kMaxImagePixels needs at most ~1 GiB per buffer).
pids=()
for t in $targets; do
  mkdir -p "$B/corpus/$t" "$B/findings/$t" "$B/logs"
  # shellcheck disable=SC2046
  LSAN_OPTIONS=suppressions=$PWD/fuzz/lsan.supp UBSAN_OPTIONS=print_stacktrace=1 \
    "$B/bin/$t" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=30 \
    -print_final_stats=1 -artifact_prefix="$B/findings/$t/" $(extra_flags "$t") \
    "$B/corpus/$t" "$(seed_dir "$t")" >"$B/logs/$t.log" 2>&1 &
  pids+=($!)
done

status=0
i=0
for t in $targets; do
  if wait "${pids[$i]}"; then
    runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$B/logs/$t.log" | grep -o '[0-9]*$' || echo '?')
    corpus=$(find "$B/corpus/$t" -type f | wc -l)
    echo "$t: no findings in ${seconds} s ($runs inputs run; corpus $corpus files)"
  else
    status=1
    # The file's prefix says what happened: crash-, leak-, timeout-, oom-. (libFuzzer's own lines can be missing from
    # the log when the finding came while OpenImageIO ran, with stderr sent to /dev/null: formats/image_io_oiio.cpp.)
    # The seed and the input (Base64) are printed, so that a finding of a CI run can be replayed elsewhere:
    #   echo '<Base64>' | base64 -d > input && build-fuzz/bin/<target> input
    echo "$t: FINDING (log: $B/logs/$t.log): $(ls "$B/findings/$t" | tr '\n' ' ')"
    grep -E 'INFO: Seed|FINDING|ERROR|SUMMARY|runtime error|Test unit written|^Base64' "$B/logs/$t.log" |
      head -20 || true
  fi
  i=$((i + 1))
done
exit $status
