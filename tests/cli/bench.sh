#!/usr/bin/env bash
# rtm bench: a small run end to end (every section of the report, the JSON's figures and their invariants) and the
# errors of its flags.
. "$(dirname "$0")/lib.bash"

# Two sizes, three reliefs, both reconstructions; the fast kernels on 1 and 2 threads, the reference and the exact
# path; Table 1 through OSMesa. --min-time 0: the fewest repeats (3 per measurement, 50 frames in Table 1).
# The scene section on a small scene of two reliefs with a 5-frame path (the default, media/town.scene.json, takes
# minutes).
cat >"$T/s.scene.json" <<JSON
{ "items": [ { "type": "relief", "relief": "$SRC/media/bumps.relief.json" },
             { "type": "relief", "relief": "$SRC/media/bricks.relief.json",
               "transform": { "translate": [1.2, 0, 0], "rotate": [0, 1, 0, -30] } } ],
  "camera_path": { "frames": 5, "keys": [ { "eye": [0, 0.3, 2], "look_at": [0, 0, 0] },
                                          { "eye": [1.5, 0.3, 2], "look_at": [1, 0, 0] } ] } }
JSON
expect_ok bench --sizes 16,32 --reliefs bumps,bricks,ridges --threads 1,2 --min-time 0 --json "$T/b.json" \
  --scene "$T/s.scene.json"
cp "$T/stdout" "$T/b.md"
for section in '### Pre-warp throughput' '### Pipelined against two-pass' '### Table 1: one relief quad' \
  '### A scene along its camera path'; do
  if grep -q -- "^$section" "$T/b.md"; then passes=$((passes + 1)); else
    echo "FAIL: the report lacks '$section'"; fails=$((fails + 1)); fi
done
if python3 - "$T/b.json" <<'PY'; then passes=$((passes + 1)); else fails=$((fails + 1)); fi
import json, math, sys
d = json.load(open(sys.argv[1]))
bad = []
def check(ok, what):
    if not ok: bad.append(what)
rows = d["rows"]
# 2 sizes x 3 reliefs x 2 methods x (fast 1 thread, fast 2 threads, reference, exact)
check(len(rows) == 48, f"{len(rows)} rows, want 48")
for r in rows:
    name = f'{r["relief"]} {r["size"]} {r["method"]} {r["path"]} {r["kernel"]} {r["threads"]}'
    check(r["texels"] == r["size"] ** 2, name + ": texels")
    med = r["prewarp_ms"]["median"]
    check(0 < r["prewarp_ms"]["min"] <= med, name + ": min <= median")
    check(abs(r["mtexels_per_s"] - r["texels"] / (med * 1e3)) <= 1e-9 * r["mtexels_per_s"], name + ": Mtexel/s")
    check(abs(r["prewarps_per_s"] - 1000 / med) <= 1e-9 * r["prewarps_per_s"], name + ": pre-warps/s")
    check(r["bound_ms"] > 0 and r["bytes_read"] > 0 and r["bytes_written"] > 0, name + ": bound")
    check(r["repeats"] >= 3, name + ": repeats")
    counted = r["kernel"] == "reference"
    check((r["row_pixels"] > 0) == counted and (r["column_samples"] > 0) == counted, name + ": work counts")
ratios = d["pipelined_vs_two_pass"]
check(len(ratios) == 6, f"{len(ratios)} pipelined/two-pass rows, want 6")
for p in ratios:
    name = f'{p["relief"]} {p["size"]}'
    check(p["pipelined_column_samples_per_texel"] >= p["two_pass_column_samples_per_texel"] > 0, name + ": samples")
    check(p["pipelined_column_samples_per_texel"] <= p["row_pixels_per_texel"], name + ": samples <= row pixels")
    check(sorted(t["threads"] for t in p["time_ratio"]) == [1, 2], name + ": thread counts")
    check(all(t["ratio"] > 0 for t in p["time_ratio"]), name + ": ratios")
t1 = d["table1"]
check(len(t1) == 6, f"{len(t1)} Table 1 rows, want 6")
for t in t1:
    name = f'table 1 {t["relief"]} {t["method"]}'
    check(t["frames"] >= 50 and t["size"] == 256, name + ": frames and size")
    parts = t["prewarp_ms"] + t["upload_ms"] + t["texture_map_ms"] + t["other_ms"]
    check(t["total_ms"] > 0 and parts >= t["total_ms"] * (1 - 1e-9), name + ": the parts make the frame")
    check(abs(t["fps"] - 1000 / t["total_ms"]) <= 1e-9 * t["fps"], name + ": frames/s")
ob = d["objects"]
check(len(ob) == 6, f"{len(ob)} object rows, want 6 (two objects, three views)")
for o in ob:
    name = f'object {o["object"]} {o["view"]}'
    check(o["frames"] >= 20 and o["faces_drawn"] == len(o["faces"]) >= 1, name + ": frames and faces")
    # The relief frame measured between the view's frames, and the ratio of the two medians.
    check(o["relief_ms"] > 0, name + ": relief frame")
    check(abs(o["relief_frame_ratio"] - o["total_ms"] / o["relief_ms"]) <= 1e-9 * o["relief_frame_ratio"],
          name + ": ratio to the relief frame")
sc = d["scene"]
check(sc["quads"] == 2 and sc["path_frames"] == 5 and sc["size"] == [640, 480], "scene: quads, path, size")
check([r["variant"] for r in sc["rows"]][0] == "skips" and len(sc["rows"]) == 12, "scene: variants")
for r in sc["rows"]:
    name = "scene " + r["variant"]
    check(r["frames"] == len(range(0, 5, r["stride"])), name + ": frames")
    check(r["total_ms"] > 0 and abs(r["fps"] - 1000 / r["total_ms"]) <= 1e-9 * r["fps"], name + ": frames/s")
    check(abs(r["ratio_to_first"] - r["total_ms"] / sc["rows"][0]["total_ms"]) <= 1e-9, name + ": ratio")
    check(0 <= r["quads_prewarped"] <= r["quads_drawn"] <= 2, name + ": counts")
    check(r["cpu_ms"] > 0, name + ": CPU time")
for b in bad: print("FAIL: bench JSON:", b)
sys.exit(1 if bad else 0)
PY
# bench-skips --scene-only: all skips, without each in turn, none.
expect_ok bench-skips --scene-only --scene "$T/s.scene.json" --json "$T/k.json"
if python3 - "$T/k.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
v = [r["variant"] for r in d["scene"]["rows"]]
sys.exit(not (d["rows"] == [] and len(v) == 7 and v[0] == "all skips" and v[-1] == "no skips"))
PY
then passes=$((passes + 1)); else echo "FAIL: bench-skips --scene-only JSON"; fails=$((fails + 1)); fi
# --scene-variants: only the variants named, in the bench's order; an unknown name is a usage error naming it.
expect_ok bench --scene-only --scene "$T/s.scene.json" --scene-variants "floor;skips" --json "$T/v.json"
if python3 - "$T/v.json" <<'PY'
import json, sys
sys.exit([r["variant"] for r in json.load(open(sys.argv[1]))["scene"]["rows"]] != ["skips", "floor"])
PY
then passes=$((passes + 1)); else echo "FAIL: bench --scene-variants"; fails=$((fails + 1)); fi
expect_fail 2 "no scene variant \"fast\"" -- bench --scene-only --scene "$T/s.scene.json" --scene-variants "skips;fast"

# bench-skips --wall-only: the brick wall on the fast kernels (a small one, one round), no GL, no scene; every
# row's picture the reference kernels' (4 rows per target: two reconstructions, 1 and 2 threads; the targets are the
# automatic one, then avx2 after another, where the CPU has it).
expect_ok bench-skips --wall-only --wall-size 64 --wall-rounds 1 --json "$T/w.json"
cp "$T/stdout" "$T/w.md"
if grep -q -- '^### The brick wall on the fast kernels' "$T/w.md" && python3 - "$T/w.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
w = d["wall"]
ok = d["rows"] == [] and d["scene"] is None and len(w) in (4, 8)
ok = ok and all(r["same_as_reference"] and r["size"] == 64 and r["rounds"] == 1 for r in w)
ok = ok and all(r[k] > 0 for r in w for k in ("ms_bricks", "ms_lifted", "ms_sunk", "cpu_ms_moving_alone"))
sys.exit(not ok)
PY
then passes=$((passes + 1)); else echo "FAIL: bench-skips --wall-only"; fails=$((fails + 1)); fi

# Without the reference kernels the work columns stay empty (null in the JSON).
expect_ok bench --sizes 16 --reliefs ridges --threads 1 --min-time 0 --no-reference --no-exact --no-table1 \
  --json "$T/n.json"
if python3 - "$T/n.json" <<'PY'
import json, sys
p = json.load(open(sys.argv[1]))["pipelined_vs_two_pass"]
sys.exit(not (len(p) == 1 and p[0]["row_pixels_per_texel"] is None and p[0]["time_ratio"][0]["threads"] == 1))
PY
then
  passes=$((passes + 1)); else echo "FAIL: --no-reference work columns"; fails=$((fails + 1)); fi

# --discontinuity: the throughput reliefs carry marks, which the fast kernels of both reconstructions take (the row
# names the SIMD target that ran, not the reference's "generic", the same for both).
expect_ok bench --sizes 16 --reliefs bricks --threads 1 --min-time 0 --no-exact --no-table1 --discontinuity 0.05 \
  --json "$T/m.json"
if grep -q '^Discontinuity marks: .* 0.05 of their displacement range' "$T/stdout" && python3 - "$T/m.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
two = [r for r in d["rows"] if r["method"] == "two-pass"]
pipe = [r for r in d["rows"] if r["method"] == "pipelined"]
ok = d["discontinuity"] == 0.05 and len(two) == 2 and len(pipe) == 2
fast_first = lambda rows: [r["isa"] != "generic" for r in rows] == [True, False]
ok = ok and fast_first(two) and fast_first(pipe)
ok = ok and pipe[0]["isa"] == two[0]["isa"]
sys.exit(not ok)
PY
then passes=$((passes + 1)); else echo "FAIL: bench --discontinuity"; fails=$((fails + 1)); fi

# Errors: usage (2) names the flag and the value; an unwritable --json fails (1) before the run, naming the file.
expect_fail 2 'sizes.*"0"' -- bench --sizes 0
expect_fail 2 'sizes.*"16,x"' -- bench --sizes 16,x
expect_fail 2 'threads.*"0"' -- bench --threads 0
expect_fail 2 'reliefs.*moon' -- bench --reliefs moon
expect_fail 2 'methods.*foo' -- bench --methods foo
expect_fail 2 'min-time.*-2' -- bench --min-time -2
expect_fail 2 'min-time.*nan' -- bench --min-time nan
expect_fail 2 'discontinuity.*found 0$' -- bench --discontinuity 0
expect_fail 2 'discontinuity.*found 1.5' -- bench --discontinuity 1.5
expect_fail 2 'discontinuity.*found nan' -- bench --discontinuity nan
expect_fail 1 'nowhere/b\.json.*does not exist' -- bench --json "$T/nowhere/b.json"
expect_fail 1 'json.*folder' -- bench --json "$T"
expect_fail 1 'nowhere/f\.json' -- bench-filter --json "$T/nowhere/f.json"
expect_fail 1 'nowhere/s\.json' -- bench-skips --json "$T/nowhere/s.json"
expect_fail 2 'no-scene' -- bench --no-scene --scene-only
# A flag of a section the others leave out is exit 2 (it was ignored: --scene-only ran the scene alone whatever
# --sizes said, and a wrong --scene-variants went unnoticed without the scene).
expect_fail 2 '--sizes applies to the pre-warp sections, which --scene-only' -- bench --scene-only --sizes 8
expect_fail 2 '--scene-variants applies to the scene.s path, which does not run \(--no-scene\)' -- bench --no-scene \
  --scene-variants bogus --sizes 16
expect_fail 2 '--adjacent-whole applies to the six-face objects. frames, which --no-table1' -- bench --no-table1 \
  --adjacent-whole --no-scene --sizes 16
expect_fail 2 '--isa generic: the generic kernels run as the reference rows, which --no-reference' -- bench \
  --isa generic --no-reference --no-scene --sizes 16
expect_fail 2 '--frames sets the skips. scenarios, which --wall-only' -- bench-skips --wall-only --frames 7
expect_fail 2 '--wall-rounds applies to the brick wall, which --scene-only' -- bench-skips --scene-only \
  --scene "$T/s.scene.json" --wall-rounds 3
expect_fail 2 '--scene-sequential applies to the scene.s path, which --wall-only' -- bench-skips --wall-only \
  --scene-sequential
expect_fail 1 'missing\.scene\.json' -- bench-skips --scene-only --scene "$T/missing.scene.json"
expect_fail 2 'wall-size.*8' -- bench-skips --wall-only --wall-size 8
expect_fail 2 'wall-rounds.*0' -- bench-skips --wall-only --wall-rounds 0
expect_fail 2 'wall-only' -- bench-skips --wall-only --scene-only
finish
