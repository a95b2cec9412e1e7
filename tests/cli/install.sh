#!/usr/bin/env bash
# cmake --install and the exported CMake package: installs this build to a temporary prefix, configures and builds
# examples/prewarp_relief against it (find_package(rtm), rtm::warp, rtm::formats), and checks that the example's
# pre-warped texture of media/bumps.relief.json equals `rtm prewarp`'s for the same eye, pixel for pixel (both run
# the same code on the same input, so the output is exact).
. "$(dirname "$0")/lib.bash"
BUILD=$(cd "$(dirname "$RTM")/.." && pwd)  # the build puts rtm in BUILD/bin
cache_value() { sed -n "s/^$1:[A-Z]*=//p" "$BUILD/CMakeCache.txt"; }

check() {  # check DESCRIPTION COMMAND...: one pass or one failure
  local what=$1
  shift
  if "$@" >"$T/check.out" 2>&1; then
    passes=$((passes + 1))
  else
    echo "FAIL: $what: $(tail -n 20 "$T/check.out")"
    fails=$((fails + 1))
  fi
}

version=$(sed -n 's/^project(rtm VERSION \([0-9.]*\) .*/\1/p' "$SRC/CMakeLists.txt")  # tests/cli/version.sh

PREFIX="$T/prefix"
LIB=$(cache_value CMAKE_INSTALL_LIBDIR)  # lib, or lib/x86_64-linux-gnu when configured for the prefix /usr
check "cmake --install" cmake --install "$BUILD" --prefix "$PREFIX"
for f in bin/rtm bin/rtm-make-media "$LIB"/rtm/librtm_imageio.so "$LIB"/librtm_warp.a "$LIB"/librtm_formats.a \
  "$LIB"/librtm_measure.a include/rtm/warp/prewarp.h include/rtm/formats/relief_manifest.h include/rtm/rtm_version.h \
  "$LIB"/cmake/rtm/rtmConfig.cmake "$LIB"/cmake/rtm/rtmConfigVersion.cmake "$LIB"/cmake/rtm/rtmTargets.cmake; do
  check "installed $f" test -f "$PREFIX/$f"
done
check "installed rtm --version" grep -qx "rtm $version" <("$PREFIX/bin/rtm" --version)
# The installed rtm reads and writes images other than PNG through its image module in $PREFIX/$LIB/rtm, not the
# build tree's (formats/image_backend.h; the dynamic loader's log names the file it loaded): a TIFF output here.
check "installed rtm reads and writes images" env LD_DEBUG=files LD_DEBUG_OUTPUT="$T/ld" "$PREFIX/bin/rtm" prewarp \
  --relief "$SRC/media/bumps.relief.json" --eye 0.3,0.4,1.5 --out "$T/installed.tif"
check "installed rtm loads $PREFIX/$LIB/rtm/librtm_imageio.so" grep -q "file=$PREFIX/$LIB/rtm/librtm_imageio.so" \
  "$T"/ld.*

# The example, against the installed package only (not the build tree), with the build's compiler.
gen=()
command -v ninja >/dev/null && gen=(-G Ninja)
check "configure examples/prewarp_relief against $PREFIX" \
  cmake -S "$SRC/examples/prewarp_relief" -B "$T/example" "${gen[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$PREFIX" -DCMAKE_CXX_COMPILER="$(cache_value CMAKE_CXX_COMPILER)" \
  -DCMAKE_CXX_COMPILER_LAUNCHER="$(cache_value CMAKE_CXX_COMPILER_LAUNCHER)"
check "the example found rtm in $PREFIX, not elsewhere" \
  grep -qx "rtm_DIR:PATH=$PREFIX/$LIB/cmake/rtm" "$T/example/CMakeCache.txt"
check "build examples/prewarp_relief" cmake --build "$T/example"

EX="$T/example/prewarp_relief"
for eye in 0.3,0.4,1.5 -0.6,0.1,0.8; do
  # The example links the image code itself (rtm::formats), so it needs no module: RTM_IMAGEIO_MODULE would fail it.
  check "prewarp_relief eye $eye" env RTM_IMAGEIO_MODULE="$T/no_module.so" "$EX" "$SRC/media/bumps.relief.json" \
    "$eye" "$T/example.png"
  expect_ok prewarp --relief "$SRC/media/bumps.relief.json" --eye "$eye" --out "$T/rtm.png"
  # idiff -a: every channel, alpha included; -fail 0 -warn 0: any differing pixel fails.
  check "example and rtm prewarp differ for eye $eye" idiff -q -a -fail 0 -warn 0 "$T/rtm.png" "$T/example.png"
  expect_ok diff "$T/rtm.png" "$T/example.png"
  check "pre-warp for eye $eye covers pixels" grep -qx 'iou 1' "$T/stdout"
done

# Bad input to the example: one line naming the value, exit 2 (usage) or 1 (unreadable file), no output file.
"$EX" "$SRC/media/bumps.relief.json" 1,2 "$T/bad.png" 2>"$T/err"
check "bad eye: exit 2, one line naming it" test $? = 2 -a "$(grep -c '' "$T/err")" = 1 -a ! -e "$T/bad.png"
check "bad eye message" grep -q '"1,2"' "$T/err"
"$EX" "$T/missing.relief.json" 1,2,3 "$T/bad.png" 2>"$T/err"
check "missing manifest: exit 1, one line naming it" test $? = 1 -a "$(grep -c '' "$T/err")" = 1 -a ! -e "$T/bad.png"
check "missing manifest message" grep -q 'missing.relief.json' "$T/err"

finish
