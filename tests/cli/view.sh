#!/usr/bin/env bash
# The interactive viewer under Xvfb (one server for the whole script): each kind of file, screenshots equal to the
# headless render of the same camera and settings, the keys and panel toggles changing what is drawn where they
# should (and only there), the camera path frame by frame, and a missing display.
. "$(dirname "$0")/lib.bash"
M=$SRC/media/facade.relief.json
S=320x240
if ! command -v Xvfb >/dev/null || ! command -v oiiotool >/dev/null; then
  echo "Xvfb or oiiotool is missing (scripts/setup.sh installs them)"
  exit 1
fi

# Without a display the viewer says so in one line naming DISPLAY, exits 1 and writes nothing.
env -u DISPLAY -u WAYLAND_DISPLAY "$RTM" view --relief "$M" --frames 1 --screenshot "$T/x.png" 2>"$T/err"
st=$?
if [ "$st" != 1 ] || ! grep -q "DISPLAY" "$T/err" || [ "$(grep -c '' "$T/err")" != 1 ] || [ -e "$T/x.png" ]; then
  echo "FAIL: no display: exit $st, $(cat "$T/err")"; fails=$((fails + 1))
else passes=$((passes + 1)); fi

Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp 3>"$T/display" 2>/dev/null &
XVFB=$!
trap 'kill $XVFB 2>/dev/null; rm -rf "$T"' EXIT
for _ in $(seq 100); do [ -s "$T/display" ] && break; sleep 0.1; done
export DISPLAY=:$(head -1 "$T/display")

# view NAME ARGS...: a scripted run writing $T/NAME.png (and $T/NAME.json).
view() {
  local name=$1
  shift
  if "$RTM" view "$@" --frames "${FRAMES:-2}" --screenshot "$T/$name.png" --json "$T/$name.json" 2>"$T/err"; then
    passes=$((passes + 1))
  else
    echo "FAIL: rtm view $* exited $?: $(cat "$T/err")"; fails=$((fails + 1))
  fi
}
render() {
  local name=$1
  shift
  expect_ok render --relief "$M" --size $S --out "$T/$name.png" "$@"
}
# psnr_of A B: the PSNR of B against A ("inf" when equal), with the coverage IoU in $iou.
compare() {
  "$RTM" diff "$T/$1.png" "$T/$2.png" >"$T/diff" || { echo "FAIL: diff $1 $2"; fails=$((fails + 1)); }
  psnr=$(awk '/^psnr/ {print $2}' "$T/diff")
  iou=$(awk '/^iou/ {print $2}' "$T/diff")
}
# same A B [MIN_PSNR]: equal up to llvmpipe's rounding (the issue's bar: PSNR >= 40 dB over common pixels,
# IoU >= 0.99); "exact" asks for identical images.
same() {
  compare "$1" "$2"
  local min=${3:-40}
  if [ "$min" = exact ]; then
    if [ "$psnr" = inf ] && [ "$iou" = 1 ]; then passes=$((passes + 1)); return; fi
  elif awk -v p="$psnr" -v i="$iou" -v m="$min" 'BEGIN { exit !((p == "inf" || p >= m) && i >= 0.99) }'; then
    passes=$((passes + 1)); return
  fi
  echo "FAIL: $1 and $2 should be the same ($min): psnr $psnr iou $iou"; fails=$((fails + 1))
}
differ() {
  compare "$1" "$2"
  if [ "$psnr" = inf ] && [ "$iou" = 1 ]; then
    echo "FAIL: $1 and $2 should differ"; fails=$((fails + 1))
  else passes=$((passes + 1)); fi
}
# blank IN OUT X Y W H: IN with the rectangle painted opaque black (whole pixels covering it).
blank() {
  local x y w h
  read -r x y w h <<<"$(awk -v x="$3" -v y="$4" -v w="$5" -v h="$6" 'BEGIN {
    x0 = int(x); y0 = int(y); x1 = int(x + w); if (x1 < x + w) x1++; y1 = int(y + h); if (y1 < y + h) y1++;
    print x0, y0, x1 - x0, y1 - y0 }')"
  oiiotool "$T/$1.png" --fill:color=0,0,0,1 "${w}x${h}+${x}+${y}" -o "$T/$2.png"
}
rect() { python3 -c "import json,sys; print(*json.load(open(sys.argv[1]))[sys.argv[2]])" "$T/$1.json" "$2"; }

# A relief, given by flag and by its kind: the same pixels as rtm render, for each method.
for m in two-pass flat pipelined micromesh raycast; do
  view "v_$m" --relief "$M" --orbit 30,20,2.2 --size $S --method "$m"
  render "r_$m" --orbit 30,20,2.2 --method "$m"
  same "r_$m" "v_$m"
done
view file "$M" --orbit 30,20,2.2 --size $S
same v_two-pass file exact
view eye --relief "$M" --eye 1.9,1.6,2.4 --size $S --level auto --depth-correction
render r_eye --eye 1.9,1.6,2.4 --level auto --depth-correction
same r_eye eye
# A per-pixel method draws as rtm render --method NAME draws it.
view v_rm --relief "$M" --orbit 30,20,2.2 --size $S --method relief-mapping
render r_rm --orbit 30,20,2.2 --method relief-mapping
same r_rm v_rm
# Quadric silhouettes on a sphere patch with the exact distance: the viewer takes render's flags.
view v_qs --relief "$M" --orbit 30,20,2.2 --size $S --method quadric-silhouettes --curved-base sphere \
  --quadric-distance exact
render r_qs --orbit 30,20,2.2 --method quadric-silhouettes --curved-base sphere --quadric-distance exact
same r_qs v_qs
render r_qc --orbit 30,20,2.2 --method quadric-silhouettes
differ r_qc v_qs
# Protruded displacement mapping's steep slopes, the built-in texture and an image: as rtm render draws them.
F=$SRC/media/facade.relief.json
for tex in builtin "$SRC/media/bricks_color.png"; do
  view v_pd --relief "$F" --orbit 40,15,2.2 --size $S --method protruded-displacement --steep-texture "$tex"
  expect_ok render --relief "$F" --orbit 40,15,2.2 --size $S --method protruded-displacement --steep-texture "$tex" \
    --out "$T/r_pd.png"
  same r_pd v_pd exact
done
expect_fail 1 'nowhere.png' -- view --relief "$F" --method protruded-displacement --steep-texture "$T/nowhere.png" \
  --frames 1
# The panel's per-pixel section (each method's parameters, shading, the quadric settings) draws.
for m in quadric-silhouettes interval-mapping parallax; do
  view "v_panel_$m" --relief "$M" --size $S --method "$m" --panel
done

# A six-face object, given by flag and by its kind: the same pixels as rtm render --object.
O=$SRC/media/sphere.object.json
for m in two-pass flat micromesh; do
  view "vo_$m" --object "$O" --orbit 30,20,2.2 --size $S --method "$m"
  expect_ok render --object "$O" --orbit 30,20,2.2 --size $S --method "$m" --out "$T/ro_$m.png"
  same "ro_$m" "vo_$m"
done
view vo_cross "$SRC/media/cross-box.object.json" --orbit -40,25,2 --size $S --level auto
expect_ok render --object "$SRC/media/cross-box.object.json" --orbit -40,25,2 --size $S --level auto \
  --out "$T/ro_cross.png"
same ro_cross vo_cross
# The insets show the pre-warped faces (some drawn this frame), inside their rectangle only.
view vo_insets --object "$O" --orbit 30,20,2.2 --size 640x480 --insets
view vo_plain --object "$O" --orbit 30,20,2.2 --size 640x480
differ vo_plain vo_insets
read -r ix iy iw ih <<<"$(rect vo_insets insets)"
blank vo_insets vo_insets_out "$ix" "$iy" "$iw" "$ih"
blank vo_plain vo_plain_out "$ix" "$iy" "$iw" "$ih"
same vo_plain_out vo_insets_out exact
# A still camera: the object's faces are pre-warped on frame 0 only, then reused (objects/object_plan.h, through the
# viewer's object path): the texels warped per frame are 0 on frames 1 and 2 (their median), not on frame 0 (max).
FRAMES=3 view vo_still --object "$O" --orbit 30,20,2.2 --size $S
tw=$(python3 -c "import json,sys; t=json.load(open(sys.argv[1]))['texels_warped']; print(t['median'], t['max'] > 0)" \
  "$T/vo_still.json")
if [ "$tw" = "0.0 True" ] || [ "$tw" = "0 True" ]; then passes=$((passes + 1))
else echo "FAIL: a still object's texels warped (median, max > 0): $tw, expected 0 True"; fails=$((fails + 1)); fi

# The town scene: its own camera, an orbit, and its camera path frame by frame (--camera-path given the scene), at
# the default level of both (auto for a scene: the viewer's was 0) and at level 0.
TOWN=$SRC/media/town.scene.json
view vs_own --scene "$TOWN" --size $S
expect_ok render --scene "$TOWN" --size $S --out "$T/rs_own.png"
same rs_own vs_own
view vs_orbit "$TOWN" --orbit 20,35,1.6 --size $S --level 0
expect_ok render --scene "$TOWN" --orbit 20,35,1.6 --size $S --level 0 --out "$T/rs_orbit.png"
same rs_orbit vs_orbit
# --orbit with --look-at starts at render's view (the eye about the centre, looking at the point; the viewer then
# orbits that point: tests/viewer/cameras_test.cpp).
view vs_orbit_at "$TOWN" --orbit 20,35,1.6 --look-at 3,0.5,2 --size $S --level 0
expect_ok render --scene "$TOWN" --orbit 20,35,1.6 --look-at 3,0.5,2 --size $S --level 0 --out "$T/rs_orbit_at.png"
same rs_orbit_at vs_orbit_at
FRAMES=41 view vs_path --scene "$TOWN" --size $S --camera-path "$TOWN"
expect_ok render --scene "$TOWN" --size $S --camera-path 40 --out "$T/rs_path.png"
same rs_path vs_path
# A per-pixel method draws a scene as rtm render --scene draws it (the viewer drew nothing).
view vs_rm --scene "$TOWN" --size $S --method relief-mapping
expect_ok render --scene "$TOWN" --size $S --method relief-mapping --out "$T/rs_rm.png"
same rs_rm vs_rm
# What a scene, an object or an orbit does not use at the start: a warning line each.
"$RTM" view --scene "$TOWN" --size 64x48 --frames 1 --depth-correction --discontinuity 0 --fov 30 2>"$T/w1"
"$RTM" view --object "$SRC/media/sphere.object.json" --size 64x48 --frames 1 --no-sidewalls --method parallax \
  --orbit 30,20,2 --curved-base sphere --steep-texture builtin 2>"$T/w2"
want='warning: --depth-correction is always on in a scene
warning: --discontinuity applies to reliefs and objects
warning: --no-sidewalls applies to relief quads
warning: --method parallax draws single reliefs
warning: --fov without --eye or --orbit: a scene starts at its own camera
warning: --curved-base applies to a relief with --method quadric-silhouettes
warning: --steep-texture applies to a relief with --method protruded-displacement'
if [ "$(cat "$T/w1" "$T/w2" | grep -c -F "$want")" = 7 ] && [ "$(cat "$T/w1" "$T/w2" | grep -c '')" = 7 ]; then
  passes=$((passes + 1)); else echo "FAIL: view warnings: $(cat "$T/w1" "$T/w2")"; fails=$((fails + 1)); fi

# A mesh (a box with a pyramid on top, written here) is baked on the fly: the same pixels as rtm bake then
# rtm render --object of the result.
cat >"$T/hut.obj" <<'OBJ'
v 0 0 0
v 1 0 0
v 1 0 1
v 0 0 1
v 0 1 0
v 1 1 0
v 1 1 1
v 0 1 1
v 0.5 1.6 0.5
f 1 2 3 4
f 5 8 7 6
f 1 5 6 2
f 2 6 7 3
f 3 7 8 4
f 4 8 5 1
f 5 9 6
f 6 9 7
f 7 9 8
f 8 9 5
OBJ
view vm "$T/hut.obj" --orbit 30,20,2.2 --size $S
expect_ok bake --mesh "$T/hut.obj" --out "$T/hut"
expect_ok render --object "$T/hut/hut.object.json" --orbit 30,20,2.2 --size $S --out "$T/rm.png"
same rm vm

# Files that cannot be opened: one line naming the file, exit 1.
echo '{}' >"$T/a.object.json"
echo '{}' >"$T/a.scene.json"
: >"$T/a.obj"
echo '{}' >"$T/a.json"
for f in "$T/a.object.json" "$T/a.scene.json" "$T/a.obj" "$T/a.json"; do
  expect_fail 1 "a\.(object\.json|scene\.json|obj|json)" -- view "$f" --frames 1
done
expect_fail 1 "has no camera_path" -- view --object "$O" --camera-path "$O" --frames 1
expect_fail 2 "^rtm: --keys: unknown key \"nope\"" -- view --relief "$M" --keys nope --frames 1
expect_fail 2 "^rtm: --split: raycast" -- view --relief "$M" --split raycast --frames 1
expect_fail 2 "^rtm: --panel-refresh-ms: expected a time >= 0, found -1$" -- view --relief "$M" \
  --panel-refresh-ms -1 --frames 1
expect_fail 2 "^rtm: --content-scale: expected a scale in \\[0.25, 8\\], found \"100\" \\(try --help\\)$" -- \
  view --relief "$M" --content-scale 100 --frames 1
# 0, the default meaning "not given", is refused when typed
expect_fail 2 "^rtm: --content-scale: expected a scale in \\[0.25, 8\\], found \"0\" \\(try --help\\)$" -- \
  view --relief "$M" --content-scale 0 --frames 1
echo '{"keys": []}' >"$T/bad_path.json"
expect_fail 1 "bad_path.json: \"keys\"" -- view --relief "$M" --camera-path "$T/bad_path.json" --frames 1

# Keys do what the flags do.
view k1 --relief "$M" --orbit 30,20,2.2 --size $S --keys 1
same v_flat k1 exact
view k3 --relief "$M" --orbit 30,20,2.2 --size $S --keys 3
same v_pipelined k3 exact
view kG --relief "$M" --orbit 30,20,2.2 --size $S --keys G
view nowalls --relief "$M" --orbit 30,20,2.2 --size $S --no-sidewalls
same nowalls kG exact
differ v_two-pass kG

# The panel changes the image inside its rectangle only.
view panel --relief "$M" --orbit 30,20,2.2 --size 640x480 --panel
view plain --relief "$M" --orbit 30,20,2.2 --size 640x480
view kH --relief "$M" --orbit 30,20,2.2 --size 640x480 --keys H
differ plain panel
read -r px py pw ph <<<"$(rect panel panel)"
if awk -v w="$pw" -v h="$ph" 'BEGIN { exit !(w > 100 && w < 640 && h > 100) }'; then passes=$((passes + 1))
else echo "FAIL: panel rectangle $px $py $pw $ph"; fails=$((fails + 1)); fi
blank panel panel_out "$px" "$py" "$pw" "$ph"
blank plain plain_out "$px" "$py" "$pw" "$ph"
same plain_out panel_out exact
blank kH kH_out "$px" "$py" "$pw" "$ph"
same plain_out kH_out exact
# The panel from its cache (viewer/panel_cache.h): with a refresh interval longer than the run it is rendered on frame 1
# (on frame 0 Dear ImGui only sizes the window) and copied onto frame 2 without being rendered. The copy lands on the
# panel's rectangle only (outside it, the plain image exactly), and its lower half (settings, skips, camera: no
# measured number) equals that of frame 1's panel rendered directly.
FRAMES=3 view pcache --relief "$M" --orbit 30,20,2.2 --size 640x480 --panel --panel-refresh-ms 1000000
FRAMES=2 view pdirect --relief "$M" --orbit 30,20,2.2 --size 640x480 --panel --panel-refresh-ms 0
counts() {
  python3 -c "import json,sys; j=json.load(open(sys.argv[1])); print(j['panel_renders'], j['panel_blits'])" "$T/$1.json"
}
if [ "$(counts pcache)" = "1 1" ] && [ "$(counts pdirect)" = "1 0" ]; then passes=$((passes + 1))
else
  echo "FAIL: panel renders, blits: cached $(counts pcache) (expected 1 1), direct $(counts pdirect) (1 0)"
  fails=$((fails + 1))
fi
read -r cx cy cw ch <<<"$(rect pcache panel)"
blank pcache pcache_out "$cx" "$cy" "$cw" "$ch"
blank plain plain_out3 "$cx" "$cy" "$cw" "$ch"
same plain_out3 pcache_out exact
half=$(awk -v y="$cy" -v h="$ch" 'BEGIN { print int(y + h / 2) }')
low=$(awk -v w="$cw" -v h="$ch" 'BEGIN { print int(w) "x" int(h / 2) }')
oiiotool "$T/pcache.png" --cut "${low}+0+$half" -o "$T/pcache_low.png"
oiiotool "$T/pdirect.png" --cut "${low}+0+$half" -o "$T/pdirect_low.png"
same pdirect_low pcache_low exact
# The window moved to a monitor of content scale 2 (the content-scale callback's path, run before the first frame):
# the panel's font and sizes double, so does its width.
view pscale2 --relief "$M" --orbit 30,20,2.2 --size 640x480 --panel --content-scale 2
read -r _ _ sw _ <<<"$(rect pscale2 panel)"
if awk -v a="$pw" -v b="$sw" 'BEGIN { exit !(b == 2 * a) }'; then passes=$((passes + 1))
else echo "FAIL: panel width at content scale 2: $sw, expected 2 x $pw"; fails=$((fails + 1)); fi
# The insets likewise, in their rectangle; the key I shows the same insets as --insets.
view insets --relief "$M" --orbit 30,20,2.2 --size 640x480 --insets
view kI --relief "$M" --orbit 30,20,2.2 --size 640x480 --keys I
same insets kI exact
differ plain insets
read -r ix iy iw ih <<<"$(rect insets insets)"
blank insets insets_out "$ix" "$iy" "$iw" "$ih"
blank plain plain_out2 "$ix" "$iy" "$iw" "$ih"
same plain_out2 insets_out exact
view outlines --relief "$M" --orbit 30,20,2.2 --size 640x480 --outlines
differ plain outlines

# The split view: the left half is the current method, the right half the other one.
view split --relief "$M" --orbit 30,20,2.2 --size $S --split flat
blank split split_left 159 0 161 240
blank v_two-pass r2_left 159 0 161 240
same r2_left split_left
blank split split_right 0 0 161 240
blank v_flat flat_right 0 0 161 240
same flat_right split_right
view kX --relief "$M" --orbit 30,20,2.2 --size $S --keys X
view split_mm --relief "$M" --orbit 30,20,2.2 --size $S --split micromesh
same split_mm kX exact
view truth --relief "$M" --orbit 30,20,2.2 --size $S --split truth
blank truth truth_left 159 0 161 240
same r2_left truth_left
differ split truth

# The screenshot key writes a PNG named by the time in the working folder, the same image as --screenshot.
mkdir "$T/shots"
rtm_abs=$(cd "$(dirname "$RTM")" && pwd)/$(basename "$RTM")
m_abs=$(cd "$(dirname "$M")" && pwd)/$(basename "$M")
if (cd "$T/shots" && "$rtm_abs" view --relief "$m_abs" --orbit 30,20,2.2 --size $S --keys P --frames 1 2>"$T/err") &&
    f=$(ls "$T/shots"/rtm-view-*.png 2>/dev/null | head -1) && [ -n "$f" ]; then
  passes=$((passes + 1))
  cp "$f" "$T/keyP.png"
  same v_two-pass keyP
else
  echo "FAIL: the screenshot key wrote no rtm-view-*.png: $(cat "$T/err")"; fails=$((fails + 1))
fi

# The fly camera starts where the orbit camera is; a W press moves it.
view fly --relief "$M" --orbit 30,20,2.2 --size $S --fly
same v_two-pass fly
view flyW --relief "$M" --orbit 30,20,2.2 --size $S --fly --keys W
differ fly flyW
view kC --relief "$M" --orbit 30,20,2.2 --size $S --keys C,W
same flyW kC exact

# The camera path: frame i shows time i / fps, the same from run to run; frame 10 (t = 9/30 s) is the second key.
cat >"$T/path.json" <<'JSON'
{ "fps": 30, "keys": [ { "t": 0, "orbit": [30, 20, 2.2] },
                       { "t": 0.3, "eye": [0.4, 1.9, 3.1], "look_at": [1.28, 1.28, 0.1] } ] }
JSON
FRAMES=10 view path1 --relief "$M" --size $S --camera-path "$T/path.json"
FRAMES=10 view path2 --relief "$M" --size $S --camera-path "$T/path.json"
same path1 path2 exact
render r_path --eye 0.4,1.9,3.1 --look-at 1.28,1.28,0.1
same r_path path1
FRAMES=1 view path0 --relief "$M" --size $S --camera-path "$T/path.json"
same v_two-pass path0
FRAMES=5 view path_mid --relief "$M" --size $S --camera-path "$T/path.json"
differ path0 path_mid
differ path1 path_mid
finish
