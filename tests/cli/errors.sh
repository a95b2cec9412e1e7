#!/usr/bin/env bash
# Bad input on the command line: exit 1 (runtime) or 2 (usage), one line naming the problem, no output file.
. "$(dirname "$0")/lib.bash"
make_small_relief "$T/r"
R=$T/r/ok.relief.json

# The valid relief works.
expect_ok prewarp --relief "$R" --eye 0.5,0.5,3 --out "$T/ok.png"
expect_ok render --relief "$R" --eye 0.5,0.5,3 --size 64x64 --out "$T/ok_render.png"

# Missing file.
expect_fail 1 'nope\.relief\.json' -- prewarp --relief "$T/nope.relief.json" --eye 0,0,1 --out "$T/o1.png"
# Unreadable image: a manifest whose colour file is text.
cp "$R" "$T/r/badimg.relief.json"
echo "not an image" >"$T/r/text.png"
sed -i 's/"c.ppm"/"text.png"/' "$T/r/badimg.relief.json"
expect_fail 1 'text\.png' -- prewarp --relief "$T/r/badimg.relief.json" --eye 0,0,1 --out "$T/o2.png"
# Colour and displacement of different sizes.
printf 'P2\n3 4\n255\n' >"$T/r/d34.pgm"; for i in $(seq 12); do echo 5 >>"$T/r/d34.pgm"; done
sed 's/"d.pgm"/"d34.pgm"/' "$R" >"$T/r/sizes.relief.json"
expect_fail 1 '3x4.*4x4|4x4.*3x4' -- prewarp --relief "$T/r/sizes.relief.json" --eye 0,0,1 --out "$T/o3.png"
# Non-finite displacement range.
sed 's/\[0.0, 0.5\]/[0.0, 1e999]/' "$R" >"$T/r/inf.relief.json"
expect_fail 1 'inf\.relief\.json.*displacement_range' -- prewarp --relief "$T/r/inf.relief.json" --eye 0,0,1 --out \
    "$T/o4.png"
# Degenerate a/b: zero and parallel.
sed 's/"a": \[0.25, 0, 0\]/"a": [0, 0, 0]/' "$R" >"$T/r/zero.relief.json"
expect_fail 1 'zero\.relief\.json.*\ba\b' -- prewarp --relief "$T/r/zero.relief.json" --eye 0,0,1 --out "$T/o5.png"
sed 's/"b": \[0, 0.25, 0\]/"b": [0.5, 0, 0]/' "$R" >"$T/r/par.relief.json"
expect_fail 1 'par\.relief\.json.*parallel' -- prewarp --relief "$T/r/par.relief.json" --eye 0,0,1 --out "$T/o6.png"
# Unknown method.
expect_fail 2 'method.*bogus' -- render --relief "$R" --eye 0,0,1 --method bogus --out "$T/o7.png"
expect_fail 2 'method.*bogus' -- prewarp --relief "$R" --eye 0,0,1 --method bogus --out "$T/o8.png"
# Filters: unknown, and coverage with the pipelined reconstruction (two-pass only).
expect_fail 2 'filter.*blur' -- prewarp --relief "$R" --eye 0,0,1 --filter blur --out "$T/o8b.png"
expect_fail 2 'coverage.*pipelined' -- render --relief "$R" --eye 0,0,1 --method pipelined --filter coverage --out \
    "$T/o8c.png"
expect_ok prewarp --relief "$R" --eye 0.5,0.5,3 --filter coverage --out "$T/ok_cov.png"
expect_ok render --relief "$R" --eye 0.5,0.5,3 --size 64x64 --filter coverage --out "$T/ok_render_cov.png"
expect_fail 2 'samples.*0' -- bench-filter --samples 0
expect_fail 2 'reliefs.*moon' -- bench-filter --reliefs moon
# Malformed --eye.
expect_fail 2 'eye.*1,2' -- prewarp --relief "$R" --eye 1,2 --out "$T/o9.png"
expect_fail 2 'eye.*a,b,c' -- render --relief "$R" --eye a,b,c --out "$T/o10.png"
expect_fail 2 'eye.*nan' -- render --relief "$R" --eye nan,0,1 --out "$T/o11.png"
# Missing required flags and unknown flags are usage errors.
expect_fail 2 'out' -- prewarp --relief "$R" --eye 0,0,1
expect_fail 2 'frobnicate' -- prewarp --relief "$R" --eye 0,0,1 --out "$T/o12.png" --frobnicate
expect_fail 2 'size.*0x5' -- render --relief "$R" --eye 0,0,1 --size 0x5 --out "$T/o13.png"

# No output file was left behind by any failure.
for i in $(seq 1 13); do
  if [ -e "$T/o$i.png" ]; then echo "FAIL: partial output $T/o$i.png left behind"; fails=$((fails + 1)); fi
done
ls "$T" | grep -q '\.tmp' && { echo "FAIL: temporary file left behind"; fails=$((fails + 1)); }
# --json of prewarp: the zero-displacement copy is reported for the brick wall (its bricks sit at displacement 0).
B="$2/media/bricks.relief.json"
expect_ok prewarp --relief "$B" --eye 0.3,0.2,1.5 --out "$T/bricks_pre.png" --json "$T/bricks_pre.json"
if grep -q '"zero-displacement-runs"' "$T/bricks_pre.json" &&
  grep -Eq '"still_texels": *[1-9]' "$T/bricks_pre.json"; then
  passes=$((passes + 1))
else
  echo "FAIL: prewarp --json on the brick wall does not report zero-displacement-runs: $(cat "$T/bricks_pre.json")"
  fails=$((fails + 1))
fi
# Output scale: a factor from 1 to 8 (usage error otherwise, before any file is read), --relief only; the pre-warped
# texture of a 4x4 relief at scale 2 is 8x8.
expect_fail 2 'output-scale.*found 0' -- prewarp --relief "$T/nope.relief.json" --eye 0,0,1 --output-scale 0 --out \
    "$T/o_s0.png"
expect_fail 2 'output-scale.*found 9' -- render --relief "$R" --eye 0,0,1 --output-scale 9 --out "$T/o_s9.png"
expect_fail 2 'output-scale.*--relief' -- render --object "$T/nope.object.json" --orbit 0,0,2 --output-scale 2 --out \
    "$T/o_s2.png"
expect_ok prewarp --relief "$R" --eye 0.5,0.5,3 --output-scale 2 --out "$T/ok_s2.png" --json "$T/ok_s2.json"
if grep -q '"width": 8' "$T/ok_s2.json" && grep -q '"output_scale": 2' "$T/ok_s2.json"; then
  echo "ok: prewarp --output-scale 2 writes 8x8 for a 4x4 relief"
else
  echo "FAIL: prewarp --output-scale 2: $(cat "$T/ok_s2.json")"
  fails=$((fails + 1))
fi
expect_ok render --relief "$R" --eye 0.5,0.5,3 --size 64x64 --output-scale 4 --out "$T/ok_render_s4.png"

# The image module (formats/image_backend.h): rtm does not link OpenImageIO, loads the module on its first image
# read, and says which module it could not load.
if ldd "$RTM" | grep -q OpenImageIO; then
  echo "FAIL: rtm links OpenImageIO at start: $(ldd "$RTM" | grep OpenImageIO)"
  fails=$((fails + 1))
fi
RTM_IMAGEIO_MODULE=$T/no_module.so expect_ok --version
# PNG files of the usual kinds need no module (formats/png_io.h): a relief of PNG images pre-warped to a PNG.
RTM_IMAGEIO_MODULE=$T/no_module.so expect_ok prewarp --relief "$SRC/media/bumps.relief.json" --eye 0.5,0.5,3 \
  --out "$T/o_png.png"
[ -s "$T/o_png.png" ] || { echo "FAIL: o_png.png not written without the image module"; fails=$((fails + 1)); }
RTM_IMAGEIO_MODULE=$T/no_module.so expect_fail 1 'c\.ppm: cannot load the image module \(.*no_module\.so' -- \
  prewarp --relief "$R" --eye 0.5,0.5,3 --out "$T/o_mod.png"
[ -e "$T/o_mod.png" ] && { echo "FAIL: o_mod.png written without an image module"; fails=$((fails + 1)); }
# A copy of rtm outside the build tree finds the module where the build put it.
mkdir -p "$T/elsewhere"
cp "$RTM" "$T/elsewhere/rtm"
if ! "$T/elsewhere/rtm" prewarp --relief "$R" --eye 0.5,0.5,3 --out "$T/o_copy.png" 2>"$T/err"; then
  echo "FAIL: a copy of rtm in $T/elsewhere cannot read images: $(cat "$T/err")"
  fails=$((fails + 1))
fi
printf 'not a module' >"$T/bad_module.so"
RTM_IMAGEIO_MODULE=$T/bad_module.so expect_fail 1 'cannot load the image module \(.*bad_module\.so' -- \
  prewarp --relief "$R" --eye 0.5,0.5,3 --out "$T/o_mod.png"
other=$(ldd "$RTM" | awk '/libstdc\+\+/ {print $3}')  # a shared library, but not the image module
RTM_IMAGEIO_MODULE=$other expect_fail 1 'module .*libstdc.* is not this version.s \(no rtm_image_backend_v1\)' -- \
  prewarp --relief "$R" --eye 0.5,0.5,3 --out "$T/o_mod.png"

# --- A new user's audit (session 41): each of these crashed, hung, wrote something or gave the wrong exit.
# --size numbers past int are refused, not wrapped (4294967297 was read as 1 and a 1x1 image written).
expect_fail 2 'size.*4294967297x1' -- render --relief "$R" --eye 0.5,0.5,3 --size 4294967297x1 --out "$T/a1.png"
# --threads: 0 to 1024 in every subcommand (compare --threads 100000 crashed in TBB; render took -1).
expect_fail 2 'threads.*100000' -- compare --relief "$R" --quick --threads 100000 --out "$T/a2"
expect_fail 2 'threads.*-1' -- render --relief "$R" --eye 0.5,0.5,3 --threads -1 --out "$T/a3.png"
expect_fail 2 'threads.*2147483647' -- prewarp --relief "$R" --eye 0.5,0.5,3 --threads 2147483647 --out "$T/a4.png"
# Whole numbers take one rule in every flag (decimal digits only): CLI11 read "+2" and "0x2" and called "1e3"
# "not in range", --size refused "+8x8" while bake --size took "+8", and bench --sizes took "+64".
for v in 1e3 +2 0x2 2.0 " 2"; do
    expect_fail 2 "threads: expected a whole number.*\"${v//+/\\+}\"" -- render --relief "$R" --eye 0.5,0.5,3 \
        --threads "$v" --out "$T/wn.png"
done
expect_fail 2 'repeat: expected a whole number.*"\+1"' -- prewarp --relief "$R" --eye 0.5,0.5,3 --repeat +1 \
    --out "$T/wn.png"
expect_fail 2 'output-scale: expected a whole number.*"0x2"' -- render --relief "$R" --eye 0.5,0.5,3 \
    --output-scale 0x2 --out "$T/wn.png"
expect_fail 2 'size: expected a whole number.*"\+8"' -- bake --size +8 --out "$T/wn_bake" "$R"
expect_fail 2 'level.*"\+1"' -- render --relief "$R" --eye 0.5,0.5,3 --level +1 \
    --out "$T/wn.png"
expect_fail 2 'sizes.*"\+64"' -- bench --sizes +64 --no-table1 --no-scene
expect_fail 2 'wall-rounds: expected a whole number.*"1e1"' -- bench-skips --wall-only --wall-rounds 1e1
expect_fail 2 'frames: expected a whole number.*"-0"' -- view --relief "$R" --frames -0
if [ -e "$T/wn.png" ]; then
    echo "FAIL: a refused whole number still wrote $T/wn.png"
    fails=$((fails + 1))
fi
# A bad RTM_ISA is exit 2 before any work in every subcommand that pre-warps (compare left pictures behind).
RTM_ISA=nonsense expect_fail 2 'RTM_ISA.*nonsense' -- render --relief "$R" --eye 0.5,0.5,3 --out "$T/a5.png"
RTM_ISA=nonsense expect_fail 2 'RTM_ISA.*nonsense' -- compare --relief "$R" --quick --out "$T/a6"
# An unwritable --json fails before the image is written (render, prewarp, diff).
expect_fail 1 'json.*nofolder' -- render --relief "$R" --eye 0.5,0.5,3 --out "$T/a7.png" --json "$T/nofolder/j.json"
expect_fail 1 'json.*nofolder' -- prewarp --relief "$R" --eye 0.5,0.5,3 --out "$T/a8.png" --json "$T/nofolder/j.json"
expect_fail 1 'json.*nofolder' -- diff "$T/ok_render.png" "$T/ok_render.png" --heatmap "$T/a9.png" \
  --json "$T/nofolder/j.json"
expect_fail 2 'needs --out or --json' -- render --relief "$R" --eye 0.5,0.5,3
for f in a1.png a2 a3.png a4.png a5.png a6 a7.png a8.png a9.png; do
  [ -e "$T/$f" ] && { echo "FAIL: $T/$f left behind"; fails=$((fails + 1)); }
done
# --json through a link to a folder is refused and the link stays; through a link to a file, the file is written.
mkdir -p "$T/realdir"
ln -s realdir "$T/linkdir"
expect_fail 1 'linkdir' -- render --relief "$R" --eye 0.5,0.5,3 --size 16x16 --out "$T/a10.png" --json "$T/linkdir"
[ -L "$T/linkdir" ] || { echo "FAIL: the link to a folder was replaced"; fails=$((fails + 1)); }
: >"$T/target.json"
ln -s target.json "$T/link.json"
expect_ok render --relief "$R" --eye 0.5,0.5,3 --size 16x16 --out "$T/a11.png" --json "$T/link.json"
if [ -L "$T/link.json" ] && grep -q '"command"' "$T/target.json"; then
  passes=$((passes + 1))
else
  echo "FAIL: --json through a link to a file: the link was replaced or the file not written"
  fails=$((fails + 1))
fi
# A FIFO as a planes file or a camera path is refused at once (both waited for ever).
mkfifo "$T/fifo.json"
timeout 60 "$RTM" bake --mesh "$2/media/room.ply" --planes "$T/fifo.json" --out "$T/a12" 2>"$T/err"
rc=$?
if [ "$rc" != 1 ] || ! grep -q 'fifo.json: is not a regular file' "$T/err"; then
  echo "FAIL: bake --planes FIFO: exit $rc (124: hung), $(cat "$T/err")"
  fails=$((fails + 1))
fi
# Unknown subcommands are named; per-pixel methods on an object are a usage error.
expect_fail 2 'unknown subcommand "frobnicate"' -- frobnicate
expect_fail 2 'relief-mapping is not available for --object' -- render --object "$T/nope.object.json" \
  --orbit 30,20,2.5 --method relief-mapping --out "$T/a13.png"
# The eye is checked against the camera's +-1e30 limit in prewarp too; an eye in the relief's plane is a warning.
expect_fail 2 'eye.*beyond' -- prewarp --relief "$R" --eye 1e300,0,1 --out "$T/a14.png"
"$RTM" prewarp --relief "$R" --eye 0.2,0.1,0 --out "$T/a15.png" 2>"$T/err" && grep -q "relief's plane" "$T/err" ||
  { echo "FAIL: prewarp with the eye in the relief plane: no warning ($(cat "$T/err"))"; fails=$((fails + 1)); }
# A manifest's "name" names compare's image folder: "../../x" wrote pictures outside --out.
mkdir -p "$T/esc/r" "$T/esc/out"
cp "$T/r/c.ppm" "$T/r/d.pgm" "$T/esc/r/"
sed 's/^{ /{ "name": "..\/..\/escaped", /' "$R" >"$T/esc/r/e.relief.json"
expect_ok compare --relief "$T/esc/r/e.relief.json" --quick --size 16x16 --out "$T/esc/out/run"
if [ -e "$T/esc/out/escaped" ] || [ ! -d "$T/esc/out/run/images/______escaped" ]; then
  echo "FAIL: compare wrote outside --out for a manifest named ../../escaped: $(find "$T/esc" -maxdepth 4 -type d)"
  fails=$((fails + 1))
fi
# Out of memory is one line naming the subcommand (it said only "std::bad_alloc"). Not under AddressSanitizer,
# whose shadow memory needs more address space than the limit leaves.
if ! ldd "$RTM" | grep -q libasan; then
  (
    ulimit -v 900000
    "$RTM" render --relief "$R" --eye 0.5,0.5,3 --size 16384x16384 --method raycast --out "$T/a16.png"
  ) 2>"$T/err"
  rc=$?
  if [ "$rc" != 1 ] || ! grep -q '^rtm render: out of memory' "$T/err" || [ "$(grep -c '' "$T/err")" != 1 ]; then
    echo "FAIL: out of memory: exit $rc, $(cat "$T/err")"
    fails=$((fails + 1))
  fi
fi
# A coordinate that underflows to a denormal is finite and accepted (stod refused 1e-320 as not finite).
expect_ok prewarp --relief "$R" --eye 1e-320,0.5,3 --out "$T/a17.png"
# Pre-warp flags with a method that pre-warps nothing: a warning each, the image still written.
if "$RTM" render --relief "$R" --eye 0.5,0.5,3 --size 16x16 --method flat --exact --out "$T/a18.png" 2>"$T/err" &&
  grep -q '^rtm: warning: --exact applies to the pre-warp, which --method flat does not do$' "$T/err"; then
  passes=$((passes + 1))
else
  echo "FAIL: render --method flat --exact: no warning ($(cat "$T/err"))"
  fails=$((fails + 1))
fi
# An output that is a FIFO (or a device) is refused, not replaced by a regular file (as root, --json /dev/null replaced
# the system's /dev/null); a loop of links is refused too.
mkfifo "$T/out_fifo.json"
ln -s loop_b "$T/loop_a"
ln -s loop_a "$T/loop_b"
expect_fail 1 'out_fifo.json: cannot write: it is not a regular file' -- render --relief "$R" --eye 0.5,0.5,3 \
  --size 16x16 --out "$T/a19.png" --json "$T/out_fifo.json"
expect_fail 1 'out_fifo.json: cannot write: it is not a regular file' -- diff "$T/ok_render.png" "$T/ok_render.png" \
  --heatmap "$T/out_fifo.json"
expect_fail 1 'loop_a: cannot write: too many levels of symbolic links' -- render --relief "$R" --eye 0.5,0.5,3 \
  --size 16x16 --out "$T/loop_a"
if [ ! -p "$T/out_fifo.json" ] || [ ! -L "$T/loop_a" ]; then
  echo "FAIL: the FIFO or the link was replaced"
  fails=$((fails + 1))
fi
# An unknown option before the subcommand is named; a threshold that underflows is a threshold.
expect_fail 2 'unknown option "--frobnicate" before the subcommand' -- --frobnicate
expect_ok render --relief "$R" --eye 0.5,0.5,3 --size 16x16 --discontinuity 1e-320 --out "$T/a20.png"
# Relief options with --mesh: a warning each.
if "$RTM" render --mesh "$2/media/room.ply" --orbit 30,20,2.5 --size 16x16 --level 2 --out "$T/a21.png" 2>"$T/err" &&
  grep -q '^rtm: warning: --level applies to reliefs' "$T/err"; then
  passes=$((passes + 1))
else
  echo "FAIL: render --mesh --level: no warning ($(cat "$T/err"))"
  fails=$((fails + 1))
fi
# Every flag a method or an input leaves unused: a warning line each (they were silent), or exit 2 where the request
# cannot be met (they were ignored): an audit's findings, each command as it found it.
O=$2/media/sphere.object.json
S=$2/media/room.scene.json
warns() {  # warns N PATTERN -- ARGS...: rtm exits 0 with N warning lines on stderr, each matching PATTERN
  local n=$1 pattern=$2
  shift 3
  if "$RTM" "$@" >/dev/null 2>"$T/err" && [ "$(grep -c '' "$T/err")" = "$n" ] &&
    [ "$(grep -Ec "^rtm: warning: ($pattern)" "$T/err")" = "$n" ]; then
    passes=$((passes + 1))
  else
    echo "FAIL: rtm $*: want $n warnings /$pattern/, got: $(cat "$T/err")"
    fails=$((fails + 1))
  fi
}
warns 1 '--level picks a level of the relief texture, which --method micromesh does not draw' -- render --relief "$R" \
  --eye 0.5,0.5,3 --size 16x16 --method micromesh --level 3 --out "$T/u1.png"
unused='--(output-scale|depth-correction) applies to the pre-warp|--no-skips turns off|--discontinuity marks'
warns 6 "$unused|--progress shows|--level picks" -- render --relief "$R" --eye 0.5,0.5,3 --size 16x16 \
  --method relief-mapping --output-scale 2 --depth-correction --no-skips --discontinuity 0.1 --progress --level 1 \
  --out "$T/u2.png"
warns 2 '--no-sidewalls applies to relief quads; a six-face object|--progress shows' -- render --object "$O" \
  --orbit 30,20,2.5 --size 16x16 --no-sidewalls --progress --out "$T/u3.png"
warns 2 '--(threads|progress) applies to reliefs; a mesh' -- render --mesh "$2/media/room.ply" --orbit 30,20,2.5 \
  --size 16x16 --threads 2 --progress --out "$T/u4.png"
warns 1 '--no-skips turns off' -- render --scene "$S" --size 16x16 --method micromesh --no-skips --out "$T/u5.png"
expect_fail 2 'frames and --camera-path need --scene' -- render --object "$O" --orbit 30,20,2.5 --frames "$T/uf"
expect_fail 2 'one of --relief M, --object O, --scene S and --mesh FILE' -- render --object "$O" --mesh \
  "$2/media/room.ply" --orbit 30,20,2.5 --out "$T/u6.png"
expect_fail 2 'one of --relief M, --object O, --scene S and --mesh FILE' -- render --scene "$S" --mesh \
  "$2/media/room.ply" --out "$T/u6.png"
expect_fail 2 '--out writes one image; --frames' -- render --scene "$S" --size 16x16 --frames "$T/uf" --out "$T/u6.png"
expect_fail 2 '--fov needs --eye or --orbit with --scene' -- render --scene "$S" --size 16x16 --fov 20 --out "$T/u6.png"
expect_fail 2 '--look-at needs --eye or --orbit with --scene: the scene.s camera path' -- render --scene "$S" \
  --size 16x16 --camera-path 3 --look-at 0,0,0 --out "$T/u6.png"
[ -e "$T/u6.png" ] || [ -e "$T/uf" ] && { echo "FAIL: a refused render wrote its output"; fails=$((fails + 1)); }
# A target asked for by name that the pre-warp could not run on: a warning (the JSON said "generic" alone).
warns 1 '--isa sse4: this pre-warp ran on the generic kernels \(--exact runs' -- prewarp --relief "$R" --eye 0.5,0.5,3 \
  --exact --isa sse4 --out "$T/u10.png"
warns 1 '--isa sse4: this pre-warp ran on the generic kernels \(--exact runs' -- prewarp --object "$O" --eye 2,1.5,3 \
  --exact --isa sse4 --out "$T/u11.png" --json "$T/u11.json"
python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); assert d["isa"] == "generic" and all(
    f["isa"] == "generic" for f in d["faces"]), d' "$T/u11.json" && passes=$((passes + 1)) ||
  { echo "FAIL: prewarp --object --json isa"; fails=$((fails + 1)); }
# --output-scale with a method that does not pre-warp changes nothing (it resampled the relief); --repeat times a mesh.
expect_ok render --relief "$R" --eye 0.5,0.5,3 --size 16x16 --method flat --out "$T/u7.png"
expect_ok render --relief "$R" --eye 0.5,0.5,3 --size 16x16 --method flat --output-scale 2 --out "$T/u8.png"
cmp -s "$T/u7.png" "$T/u8.png" && passes=$((passes + 1)) ||
  { echo "FAIL: --output-scale changed a flat render"; fails=$((fails + 1)); }
expect_ok render --mesh "$2/media/room.ply" --orbit 30,20,2.5 --size 16x16 --repeat 3 --json "$T/u9.json"
python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); assert d["total_ms"]["count"] == 3, d' "$T/u9.json" &&
  passes=$((passes + 1)) || { echo "FAIL: render --mesh --repeat 3"; fails=$((fails + 1)); }
finish
