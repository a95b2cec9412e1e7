#!/usr/bin/env bash
# rtm render --scene: the default camera, a CAMERA, a frame of the camera path, every frame into a folder, the
# --json counts, the shipped room with every method, object and mesh items, and the errors (one line, exit 1 for
# bad files, 2 for bad usage, no partial output).
. "$(dirname "$0")/lib.bash"
cat >"$T/s.scene.json" <<JSON
{ "name": "s",
  "items": [ { "type": "relief", "relief": "$SRC/media/bumps.relief.json" },
             { "type": "relief", "relief": "$SRC/media/bricks.relief.json",
               "transform": { "translate": [1.2, 0, 0], "rotate": [0, 1, 0, -30], "scale": 0.8 } },
             { "type": "polygon", "vertices": [[-1, -0.6, 1], [2, -0.6, 1], [2, -0.6, -1], [-1, -0.6, -1]],
               "color": [0.4, 0.4, 0.4] } ],
  "camera": { "eye": [0.5, 0.4, 2.5], "look_at": [0.5, 0, 0] },
  "camera_path": { "frames": 3, "keys": [ { "eye": [0, 0.3, 2], "look_at": [0, 0, 0] },
                                          { "eye": [1.5, 0.3, 2], "look_at": [1, 0, 0], "fov": 50 } ] } }
JSON
S=$T/s.scene.json
expect_ok render --scene "$S" --size 96x64 --level 0 --out "$T/default.png" --json "$T/default.json"
# --level auto, per quad: 256^2 reliefs in a 96x64 view are pre-warped at coarser levels; a scene's default.
expect_ok render --scene "$S" --size 96x64 --json "$T/auto.json" --level auto
expect_ok render --scene "$S" --size 96x64 --json "$T/unset.json"
expect_ok render --scene "$S" --orbit 20,10,2 --size 96x64 --method flat --out "$T/flat.png"
expect_ok render --scene "$S" --camera-path 1 --size 96x64 --method micromesh --out "$T/truth.png"
expect_ok render --scene "$S" --size 96x64 --frames "$T/frames" --json "$T/frames.json"
for k in 0 1 2; do
  if [ -s "$T/frames/frame_000$k.png" ]; then passes=$((passes + 1))
  else echo "FAIL: frame $k missing"; fails=$((fails + 1)); fi
done
# `prewarp --level auto` picks the level `render --level auto` draws from the same eye (objects/level_choice.h);
# by texel density alone it picked 2, 1 and 2 at these eyes, where the facade's parallax keeps render at level 0.
for e in 0.3,0.2,12 3,0.3,6 6,0.5,10 2,1,30; do
  F=$SRC/media/facade.relief.json
  expect_ok prewarp --relief "$F" --eye "$e" --level auto --out "$T/lp.png" --json "$T/lp.json"
  expect_ok render --relief "$F" --eye "$e" --level auto --size 512x512 --out "$T/lr.png" --json "$T/lr.json"
  level() { python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["level"])' "$1"; }
  if [ "$(level "$T/lp.json")" = "$(level "$T/lr.json")" ]; then passes=$((passes + 1))
  else echo "FAIL: prewarp and render --level auto differ at eye $e"; fails=$((fails + 1)); fi
done
# The JSON: counts per frame, stage times over the frames.
if python3 - "$T/default.json" "$T/frames.json" "$T/auto.json" "$T/unset.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); f = json.load(open(sys.argv[2])); a = json.load(open(sys.argv[3]))
u = json.load(open(sys.argv[4]))
assert u["quads_by_level"] == a["quads_by_level"] and u["texels_warped"] == a["texels_warped"], (u, a)
assert sum(a["quads_by_level"].values()) == a["quads_drawn"] and d["quads_by_level"] == {"0": d["quads_drawn"]}, a
assert 0 < a["texels_warped"] < d["texels_warped"], (a, d)
assert all(int(level) > 0 for level in a["quads_by_level"]), a
assert d["quads"] == 2 and d["quads_drawn"] <= 2 and d["quads_prewarped"] <= d["quads_drawn"], d
assert d["texels_warped"] in (0, 256 * 256, 2 * 256 * 256), d["texels_warped"]
for k in ("prewarp_ms", "upload_ms", "texture_map_ms", "total_ms"):
    assert d[k]["count"] == 1 and f[k]["count"] == 3, k
assert len(f["frames"]) == 3 and all(x["quads"] == 2 for x in f["frames"])
PY
then passes=$((passes + 1)); else echo "FAIL: scene JSON"; fails=$((fails + 1)); fi

# micromesh_triangles: frame 20 of the town's path has the eye inside three quads' slabs; each draws the tiles of its
# mesh in view, fewer than its 2 * 255 * 255 micro-polygons (the whole mesh of a 256^2 quad) and more than none.
expect_ok render --scene "$SRC/media/town.scene.json" --camera-path 20 --size 160x120 --out "$T/town20.png" \
  --json "$T/town20.json"
if python3 - "$T/town20.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
n = j["quads_skipped"].get("inside-slab-micromesh", 0)
assert n >= 1 and 0 < j["micromesh_triangles"] < n * 2 * 255 * 255, (n, j["micromesh_triangles"])
PY
then passes=$((passes + 1)); else echo "FAIL: scene JSON micromesh_triangles"; fails=$((fails + 1)); fi

# The shipped room (media/room.scene.json): every method draws it; raycast is refused as for every scene.
ROOM=$SRC/media/room.scene.json
for m in flat two-pass pipelined micromesh parallax parallax-offset-limiting steep-parallax parallax-occlusion \
  relief-mapping interval-mapping protruded-displacement quadric-silhouettes; do
  expect_ok render --scene "$ROOM" --size 64x48 --method "$m" --out "$T/room_$m.png"
done
expect_ok render --scene "$ROOM" --camera-path 40 --size 64x48 --json "$T/room.json"
if python3 - "$T/room.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
assert d["quads"] == 4 and 1 <= d["quads_drawn"] <= 4, d
PY
then passes=$((passes + 1)); else echo "FAIL: room JSON"; fails=$((fails + 1)); fi
# Object and mesh items, placed by transforms; a missing object or mesh file is one line naming it, exit 1.
cat >"$T/items.scene.json" <<JSON
{ "items": [ { "type": "mesh", "mesh": "$SRC/media/room.ply", "transform": { "scale": 0.5 } },
             { "type": "object", "object": "$SRC/media/sphere.object.json",
               "transform": { "translate": [0, 0.5, 0], "rotate": [0, 1, 0, 30], "scale": 0.1 } } ],
  "camera": { "eye": [0.6, 0.7, 0.6], "look_at": [0, 0.5, 0] } }
JSON
for m in flat two-pass micromesh relief-mapping; do
  expect_ok render --scene "$T/items.scene.json" --size 64x48 --method "$m" --out "$T/items_$m.png" \
    --json "$T/items_$m.json"
done
if python3 - "$T/items_two-pass.json" "$T/items_micromesh.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1])); t = json.load(open(sys.argv[2]))
assert r["quads"] == 0 and 1 <= r["object_faces_drawn"] <= 3, r  # at most three faces of a box are seen
assert t["object_faces_drawn"] == 6, t  # the truth draws all six faces' meshes
PY
then passes=$((passes + 1)); else echo "FAIL: object items JSON"; fails=$((fails + 1)); fi
printf '{"items": [{"type": "object", "object": "nope.object.json"}]}' >"$T/noobj.scene.json"
expect_fail 1 "nope.object.json" -- render --scene "$T/noobj.scene.json" --eye 0,0,3 --out "$T/x.png"
printf '{"items": [{"type": "mesh", "mesh": "nope.ply"}]}' >"$T/nomesh.scene.json"
expect_fail 1 "nope.ply" -- render --scene "$T/nomesh.scene.json" --eye 0,0,3 --out "$T/x.png"
printf '{"items": [{"type": "mesh", "mesh": "m.ply"}, {"type": "teapot"}]}' >"$T/kind.scene.json"
expect_fail 1 "kind.scene.json: item 1: .*type" -- render --scene "$T/kind.scene.json" --eye 0,0,3 --out "$T/x.png"

# --repeat N times one camera's frame N times after a warm-up (it was ignored for scenes: one frame); --exact and
# --filter coverage reach the scene's pre-warps (they were ignored: the same picture); what a scene does not take
# gets a warning line each.
expect_ok render --scene "$S" --size 96x64 --level 0 --repeat 3 --out "$T/rep.png" --json "$T/rep.json"
expect_ok render --scene "$S" --size 96x64 --level 0 --exact --out "$T/exact.png"
expect_ok render --scene "$S" --size 96x64 --level 0 --filter coverage --out "$T/coverage.png"
if python3 - "$T/rep.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
assert len(j["frames"]) == 3 and j["total_ms"]["count"] == 3, j["total_ms"]
assert j["quads"] == 2 and j["quads_skipped"] == j["frames"][-1]["quads_skipped"], j
PY
then passes=$((passes + 1)); else echo "FAIL: scene --repeat JSON"; fails=$((fails + 1)); fi
if ! cmp -s "$T/rep.png" "$T/default.png"; then echo "FAIL: --repeat's last frame differs from one frame"
  fails=$((fails + 1)); else passes=$((passes + 1)); fi
for f in exact coverage; do
  if cmp -s "$T/$f.png" "$T/default.png"; then echo "FAIL: --$f left the scene's picture as it was"
    fails=$((fails + 1)); else passes=$((passes + 1)); fi
done
expect_fail 2 "repeat.*frames" -- render --scene "$S" --frames "$T/f3" --repeat 2
expect_fail 2 "filter coverage.*pipelined" -- render --scene "$S" --method pipelined --filter coverage --out "$T/x.png"
"$RTM" render --scene "$S" --size 32x32 --out "$T/w.png" --depth-correction --discontinuity 0.1 2>"$T/warn.txt"
if [ "$(grep -c 'warning: --depth-correction is always on' "$T/warn.txt")" = 1 ] &&
  [ "$(grep -c 'warning: --discontinuity applies to --relief and --object' "$T/warn.txt")" = 1 ]; then
  passes=$((passes + 1)); else echo "FAIL: scene warnings: $(cat "$T/warn.txt")"; fails=$((fails + 1)); fi
# scripts/scene_memory.sh (docs/BENCHMARKS.md, "Scenes of many placements") runs and writes its row.
row='^\| 3 \| [0-9]+ MiB \| [0-9.]+ s \| [0-9]+ ms \|$'
if RTM=$RTM bash "$SRC/scripts/scene_memory.sh" 3 2>/dev/null | grep -Eq "$row"; then passes=$((passes + 1))
else echo "FAIL: scripts/scene_memory.sh"; fails=$((fails + 1)); fi
expect_fail 2 "raycast" -- render --scene "$S" --method raycast --out "$T/x.png"
expect_fail 2 "level" -- render --scene "$S" --level x --out "$T/x.png"
expect_fail 2 "camera-path" -- render --scene "$S" --camera-path 3 --out "$T/x.png"
expect_fail 2 "frames" -- render --scene "$S" --frames "$T/f2" --eye 0,0,3
expect_fail 2 "scene" -- render --relief "$SRC/media/bumps.relief.json" --camera-path 0 --out "$T/x.png"
expect_fail 1 "missing.scene.json" -- render --scene "$T/missing.scene.json" --out "$T/x.png"
printf '{"items": [{"type": "polygon", "vertices": [[0,0,0],[1,0,0]]}]}' >"$T/bad.scene.json"
expect_fail 1 "bad.scene.json: item 0: .*vertices" -- render --scene "$T/bad.scene.json" --out "$T/x.png"
printf '{"items": [{"type": "relief", "relief": "nope.relief.json"}]}' >"$T/nofile.scene.json"
# (with a camera: a scene without one is refused first, before its items are loaded)
expect_fail 1 "nofile.scene.json: item 0: .*nope.relief.json" -- render --scene "$T/nofile.scene.json" --orbit 0,30,2 \
  --out "$T/x.png"
expect_fail 2 "nofile.scene.json has no default camera" -- render --scene "$T/nofile.scene.json" --out "$T/x.png"
printf '{"items": [{"type": "polygon", "vertices": [[0,0,0],[1,0,0],[1,1,0]]}]}' >"$T/nocam.scene.json"
expect_fail 2 "no default camera" -- render --scene "$T/nocam.scene.json" --out "$T/x.png"
[ ! -e "$T/x.png" ] && passes=$((passes + 1)) || { echo "FAIL: partial output left"; fails=$((fails + 1)); }
finish
