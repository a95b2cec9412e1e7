#!/usr/bin/env bash
# rtm bake and rtm render --mesh: a generated OBJ, the duck of assimp-testmodels, height maps, hostile inputs.
. "$(dirname "$0")/lib.bash"

# A "box with a bump" (two quads facing +z, known colours), as in tests/mesh.
mkdir -p "$T/m"
printf 'newmtl floor\nKd 0.2 0.4 0.6\nnewmtl bump\nKd 1 0.8 0\n' >"$T/m/bump.mtl"
cat >"$T/m/bump.obj" <<'OBJ'
mtllib bump.mtl
v 0 0 0.25
v 1 0 0.25
v 1 1 0.25
v 0 1 0.25
v 0.25 0.25 0.75
v 0.75 0.25 0.75
v 0.75 0.75 0.75
v 0.25 0.75 0.75
usemtl floor
f 1 2 3
f 1 3 4
usemtl bump
f 5 6 7
f 5 7 8
OBJ

# render --mesh: from +z the bump's colour in the middle, black in the corner.
expect_ok render --mesh "$T/m/bump.obj" --orbit 0,0,3 --size 64x64 --out "$T/bump.png" --json "$T/bump.json"
if ! grep -q '"triangles": 4' "$T/bump.json"; then
  echo "FAIL: render --mesh json: $(cat "$T/bump.json")"; fails=$((fails + 1))
fi
if command -v oiiotool >/dev/null; then
  centre=$(oiiotool "$T/bump.png" --cut 1x1+32+32 --printstats 2>/dev/null | grep -i "stats max" | head -1)
  case "$centre" in *"1.000000 0.800000 0.000000"*) passes=$((passes + 1)) ;;
    *) echo "FAIL: render --mesh centre pixel: $centre"; fails=$((fails + 1)) ;; esac
fi

# bake --mesh: the object manifest and twelve images, nothing else.
expect_ok bake --mesh "$T/m/bump.obj" --size 8 --out "$T/b"
n=$(ls "$T/b" | wc -l)
if [ "$n" != 13 ] || [ ! -f "$T/b/bump.object.json" ]; then
  echo "FAIL: bake wrote $n files: $(ls "$T/b")"; fails=$((fails + 1))
fi
for key in '"+x"' '"-x"' '"+y"' '"-y"' '"+z"' '"-z"' '"box"'; do
  grep -q -- "$key" "$T/b/bump.object.json" || { echo "FAIL: bump.object.json lacks $key"; fails=$((fails + 1)); }
done

# The duck, with its texture, and rendered from an orbit.
DUCK=/usr/share/assimp/models/Collada/duck.dae
if [ -f "$DUCK" ]; then
  expect_ok bake --mesh "$DUCK" --size 32 --out "$T/duck"
  [ -f "$T/duck/duck.object.json" ] && [ -f "$T/duck/duck_px_color.png" ] && [ -f "$T/duck/duck_nz_disp.png" ] ||
    { echo "FAIL: duck bake files: $(ls "$T/duck")"; fails=$((fails + 1)); }
  if grep -q warning "$T/stderr"; then echo "FAIL: duck bake warned: $(cat "$T/stderr")"; fails=$((fails + 1)); fi
  expect_ok render --mesh "$DUCK" --orbit 30,20,2.5 --size 64x64 --out "$T/duck.png"
  # Each face, as a relief texture rendered by the pre-warp (two-pass) from straight in front of it, against the
  # mesh rendered from the same eye: the object's frames and texel centres agree with the mesh. Measured at
  # --size 128, 128x128 images: +x psnr 35.3 iou 0.978, +z psnr 39.0 iou 0.983 (llvmpipe). The bounds leave
  # room for rasterization differences at the outline and the 8-bit displacement of the pre-warp; a frame off by
  # a texel or mirrored falls far below them.
  expect_ok bake --mesh "$DUCK" --size 128 --out "$T/duck128"
  for key in +x +z; do
    cam=$(python3 - "$T/duck128" "$key" <<'PY'
import json, sys
d, key = sys.argv[1], sys.argv[2]
j = json.load(open(d + '/duck.object.json'))
lo, hi = j['box']['min'], j['box']['max']
f = j['faces'][key]
w, h = f['size']
e = [hi[k] - lo[k] for k in range(3)]
o, a, b, n = {'+x': ([hi[0], lo[1], hi[2]], [0, 0, -e[2] / w], [0, e[1] / h, 0], [1, 0, 0]),
              '+z': ([lo[0], lo[1], hi[2]], [e[0] / w, 0, 0], [0, e[1] / h, 0], [0, 0, 1])}[key]
json.dump({'color': f['color'], 'displacement': f['displacement'], 'displacement_range': f['displacement_range'],
           'origin': o, 'a': a, 'b': b}, open(d + '/face.relief.json', 'w'))
c = [(lo[k] + hi[k]) / 2 for k in range(3)]
print('--eye', ','.join(str(c[k] + 3 * n[k]) for k in range(3)), '--look-at', ','.join(map(str, c)))
PY
)
    # shellcheck disable=SC2086
    expect_ok render --relief "$T/duck128/face.relief.json" $cam --size 128x128 --method two-pass --out "$T/face.png"
    # shellcheck disable=SC2086
    expect_ok render --mesh "$DUCK" $cam --size 128x128 --out "$T/face_mesh.png"
    "$RTM" diff "$T/face_mesh.png" "$T/face.png" >"$T/diff.txt" 2>&1
    psnr=$(awk '$1 == "psnr" {print $2}' "$T/diff.txt")
    iou=$(awk '$1 == "iou" {print $2}' "$T/diff.txt")
    echo "face $key against the mesh: psnr $psnr iou $iou"
    if ! awk -v p="$psnr" -v i="$iou" 'BEGIN { exit !(p >= 28 && i >= 0.95) }'; then
      echo "FAIL: face $key against the mesh: psnr $psnr iou $iou (want >= 28, >= 0.95)"; fails=$((fails + 1))
    fi
  done
fi

# compare --mesh: bake, render both over the ring of views, a summary per method (docs/ACCURACY.md).
expect_ok compare --mesh "$T/m/bump.obj" --texels 16 --size 32x32 --no-images --out "$T/cmp"
python3 - "$T/cmp/compare.json" <<'PY' || { echo "FAIL: compare --mesh json"; fails=$((fails + 1)); }
import json, sys
j = json.load(open(sys.argv[1]))
assert [s['method'] for s in j['summary']] == ['two-pass', 'pipelined'], j['summary']
assert all(s['views'] == 32 for s in j['summary'])
assert len(j['rows']) == 64
PY
expect_fail 2 'one kind of source.*--mesh FILE' -- compare --out "$T/o_cmp"
expect_fail 2 'apply to --mesh' -- compare --relief x.relief.json --texels 8 --out "$T/o_cmp"
expect_fail 2 '--mesh takes' -- compare --mesh x.obj --relief x.relief.json --out "$T/o_cmp"
expect_fail 1 'nothere\.obj' -- compare --mesh "$T/m/nothere.obj" --out "$T/o_cmp"

# Flat meshes still bake, with a one-line warning.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$T/m/flat.obj"
expect_ok bake --mesh "$T/m/flat.obj" --size 16 --out "$T/flat"
grep -q 'warning:.*flat along z' "$T/stderr" || { echo "FAIL: flat mesh: $(cat "$T/stderr")"; fails=$((fails + 1)); }
# A missing texture: the material colour, a warning.
printf 'newmtl m\nKd 1 0 0\nmap_Kd gone.png\n' >"$T/m/notex.mtl"
printf 'mtllib notex.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 1\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3\n' \
  >"$T/m/notex.obj"
expect_ok bake --mesh "$T/m/notex.obj" --size 16 --out "$T/notex"
grep -q 'warning:.*gone\.png' "$T/stderr" || { echo "FAIL: missing texture: $(cat "$T/stderr")"; fails=$((fails + 1)); }

# Hostile meshes: one line, exit 1, no output.
printf 'v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n' >"$T/m/point.obj"
expect_fail 1 'point\.obj.*one point' -- bake --mesh "$T/m/point.obj" --out "$T/o_point"
printf 'garbage \001\002\003' >"$T/m/garbage.obj"
expect_fail 1 'garbage\.obj' -- bake --mesh "$T/m/garbage.obj" --out "$T/o_garbage"
expect_fail 1 'nothere\.dae' -- bake --mesh "$T/m/nothere.dae" --out "$T/o_missing"
expect_fail 1 'garbage\.obj' -- render --mesh "$T/m/garbage.obj" --orbit 0,0,3 --out "$T/o_garbage.png"
# Files on which assimp itself aborts or loops without end (tests/mesh/mesh_loader_test.cpp says where they come
# from): read in a child process, each is one line naming the file and saying what happened.
printf 'Caligari \0\0\0\0\0\0\0L\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0BitM\0\0\0\0\0\0\0\0\0\0\0\0\0\023\0\0' \
  >"$T/m/abort.cob"
expect_fail 1 'abort\.cob: cannot read mesh: the mesh reader \(assimp\) crashed on it \(signal 6, Aborted; it said' \
  -- render --mesh "$T/m/abort.cob" --orbit 0,0,3 --out "$T/o_abort.png"
expect_fail 1 'abort\.cob: cannot read mesh: the mesh reader \(assimp\) crashed' -- bake --mesh "$T/m/abort.cob" \
  --out "$T/o_abort"
printf 'nodes\n0  1.0 0.' >"$T/m/loop.smd"
RTM_MESH_READER_SECONDS=1 expect_fail 1 'loop\.smd: .*was stopped after the 1 s of processor time it may use' \
  -- render --mesh "$T/m/loop.smd" --orbit 0,0,3 --out "$T/o_loop.png"
RTM_MESH_READER_MB=0 expect_fail 1 'RTM_MESH_READER_MB "0" is not a whole number' \
  -- render --mesh "$T/m/loop.smd" --orbit 0,0,3 --out "$T/o_loop.png"
# A reader that loops ends with rtm: rtm killed, its child goes too (it would loop for the 100 s it may use).
RTM_MESH_READER_SECONDS=100 "$RTM" render --mesh "$T/m/loop.smd" --orbit 0,0,3 --out "$T/o_loop.png" 2>/dev/null &
parent=$!
sleep 1
kill -9 "$parent"
wait "$parent" 2>/dev/null
sleep 1
if pgrep -f -- "--mesh $T/m/loop.smd" >/dev/null; then
  echo "FAIL: the mesh reader's child outlived rtm: $(pgrep -af -- "--mesh $T/m/loop.smd")"
  pkill -9 -f -- "--mesh $T/m/loop.smd"
  fails=$((fails + 1))
else
  passes=$((passes + 1))
fi
# A FIFO is refused without being opened (reading it would wait for a writer).
mkfifo "$T/m/fifo.obj"
expect_fail 1 'fifo\.obj: cannot read mesh: not a regular file' -- render --mesh "$T/m/fifo.obj" --orbit 0,0,3 \
  --out "$T/o_fifo.png"
printf 'ply\nformat binary_little_endian 1.0\nelement vertex 8' >"$T/m/cut.ply"
expect_fail 1 'cut\.ply: cannot read mesh: header has no "end_header" line' \
  -- render --mesh "$T/m/cut.ply" --orbit 0,0,3 --out "$T/o_cut.png"
for d in o_point o_garbage o_missing o_garbage.png o_abort.png o_abort o_loop.png o_cut.png o_fifo.png; do
  [ -e "$T/$d" ] && { echo "FAIL: $d left behind"; fails=$((fails + 1)); }
done
touch "$T/a_file"
expect_fail 1 'a_file.*not a folder' -- bake --mesh "$T/m/bump.obj" --out "$T/a_file"
# Usage errors: exit 2.
expect_fail 2 'size' -- bake --mesh "$T/m/bump.obj" --size 0 --out "$T/o_size"
expect_fail 2 'one of --mesh' -- bake --out "$T/o_none"
expect_fail 2 'one of --mesh' -- bake --mesh "$T/m/bump.obj" --height "$T/h.png" --out "$T/o_both"
expect_fail 2 'range' -- bake --height "$T/h.png" --range 1,0 --out "$T/o_range"
expect_fail 2 'relief.*mesh|mesh.*relief' -- render --mesh "$T/m/bump.obj" --relief x.relief.json --orbit 0,0,3
# A mesh is drawn conventionally: --method flat (or none) is accepted, any other method refused.
expect_ok render --mesh "$T/m/bump.obj" --method flat --orbit 0,0,3 --size 16x16 --out "$T/bump_flat.png"
for m in two-pass pipelined micromesh raycast relief-mapping nonsense; do
  expect_fail 2 "--method $m: a mesh is drawn conventionally" -- render --mesh "$T/m/bump.obj" --method $m --orbit 0,0,3
done

# bake --planes: one relief per rectangle, readable by render --relief; malformed planes exit 1; --size exit 2.
cat >"$T/planes.json" <<'JSON'
{ "planes": [ { "name": "top", "origin": [0, 0, 0.75], "a": [0.125, 0, 0], "b": [0, 0.125, 0], "size": [8, 8] } ] }
JSON
expect_ok bake --mesh "$T/m/bump.obj" --planes "$T/planes.json" --out "$T/pl"
[ -f "$T/pl/bump_top.relief.json" ] || { echo "FAIL: no bump_top.relief.json: $(ls "$T/pl")"; fails=$((fails + 1)); }
expect_ok render --relief "$T/pl/bump_top.relief.json" --orbit 0,60,3 --size 32x32 --out "$T/pl.png"
echo '{ "planes": [ { "name": "top", "origin": [0, 0], "a": [1, 0, 0], "b": [0, 1, 0], "size": [8, 8] } ] }' \
  >"$T/bad_planes.json"
expect_fail 1 'bad_planes\.json.*origin' -- bake --mesh "$T/m/bump.obj" --planes "$T/bad_planes.json" --out "$T/o_pl"
[ -e "$T/o_pl" ] && { echo "FAIL: o_pl left behind"; fails=$((fails + 1)); }
expect_fail 2 'size' -- bake --mesh "$T/m/bump.obj" --planes "$T/planes.json" --size 8 --out "$T/o_pl2"

# bake --height: a 4x2 grey PGM and a colour; the manifest the relief reader takes.
printf 'P2\n4 2\n255\n0 51 102 255\n255 102 51 0\n' >"$T/h.pgm"
printf 'P3\n4 2\n255\n' >"$T/c.ppm"; for i in $(seq 8); do printf '10 20 30\n' >>"$T/c.ppm"; done
expect_ok bake --height "$T/h.pgm" --color "$T/c.ppm" --range -0.5,0.5 --texel 0.25 --out "$T/hm"
# A range every reader refuses is refused here (0,1e35 was written, then refused by every command).
expect_fail 2 'range.*beyond the coordinate limit' -- bake --height "$T/h.pgm" --range 0,1e35 --out "$T/o_range"
expect_fail 2 'range.*beyond the coordinate limit' -- bake --height "$T/h.pgm" --range 0,1e300 --out "$T/o_range"
expect_fail 2 'texel.*too small' -- bake --height "$T/h.pgm" --texel 1e-300 --out "$T/o_range"
[ -f "$T/hm/h.relief.json" ] || { echo "FAIL: no h.relief.json: $(ls "$T/hm")"; fails=$((fails + 1)); }
expect_ok render --relief "$T/hm/h.relief.json" --orbit 0,30,3 --size 32x32 --out "$T/hm.png"
# --size N resamples the height map and the colour to N texels along the longer side (tent filter, docs/BAKE.md)
# and keeps the relief's world size: 4x2 at texel 0.25 -> 8x4 at texel 0.125; 2x1 at texel 0.5.
for n in 8 2; do
  expect_ok bake --height "$T/h.pgm" --color "$T/c.ppm" --size $n --texel 0.25 --out "$T/hm$n"
  got=$(python3 - "$T/hm$n/h.relief.json" <<'PY'
import json, sys, os
import subprocess
j = json.load(open(sys.argv[1]))
d = os.path.dirname(sys.argv[1])
def size(f):
    out = subprocess.run(['oiiotool', '--info', os.path.join(d, f)], capture_output=True, text=True).stdout
    return out.split(':', 1)[1].split(',')[0].strip().replace(' ', '')
print(j['a'][0], j['b'][1], size(j['color']), size(j['displacement']))
PY
)
  want=$( [ $n = 8 ] && echo "0.125 0.125 8x4 8x4" || echo "0.5 0.5 2x1 2x1")
  [ "$got" = "$want" ] || { echo "FAIL: bake --height --size $n: got '$got', want '$want'"; fails=$((fails + 1)); }
done
expect_ok render --relief "$T/hm8/h.relief.json" --orbit 0,30,3 --size 32x32 --out "$T/hm8.png"
expect_fail 2 'size' -- bake --height "$T/h.pgm" --size 0 --out "$T/o_size0"
printf 'P3\n3 2\n255\n' >"$T/c32.ppm"; for i in $(seq 6); do printf '10 20 30\n' >>"$T/c32.ppm"; done
expect_fail 1 'c32\.ppm.*3x2.*4x2' -- bake --height "$T/h.pgm" --color "$T/c32.ppm" --out "$T/o_c32"
[ -e "$T/o_c32" ] && { echo "FAIL: o_c32 left behind"; fails=$((fails + 1)); }

finish
