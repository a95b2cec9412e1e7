#!/usr/bin/env bash
# Six-face objects on the command line: rtm render --object and rtm prewarp --object (docs/OBJECTS.md), their
# --json fields, and hostile object manifests (one line naming the file and the field, exit 1, no output file).
. "$(dirname "$0")/lib.bash"
O=$SRC/media/cross-box.object.json

# One-, two- and three-face views; every method; the JSON names the faces drawn and the per-face times.
for view in 0,0,3 45,0,3; do
  expect_ok render --object "$O" --orbit $view --size 96x96 --out "$T/r_$view.png" --json "$T/r_$view.json"
done
for m in pipelined flat micromesh; do
  expect_ok render --object "$O" --orbit 30,-40,3 --size 96x96 --method $m --exact --out "$T/r_$m.png"
done
expect_ok render --object "$O" --orbit 45,35,3 --size 96x96 --depth-correction --level auto --out "$T/r.png" \
  --json "$T/r.json"
if ! python3 - "$T/r.json" <<'PY'; then
import json, sys
j = json.load(open(sys.argv[1]))
assert j["faces_drawn"] == ["+x", "+y", "+z"], j["faces_drawn"]
assert j["visible_faces"] == ["+x", "+y", "+z"]
assert "back-facing" in j["skips"], j["skips"]
for f in j["faces"]:
    assert f["prewarp_ms"]["min"] > 0 and len(f["adjacent"]) == 2, f
for k in ("prewarp_ms", "upload_ms", "texture_map_ms", "total_ms"):
    assert j[k]["median"] >= 0, k
assert j["texels"] == 6 * 64 * 64
PY
  echo "FAIL: render --object --json fields"; fails=$((fails + 1))
else passes=$((passes + 1)); fi
# The whole object behind the camera: every visible face outside the frustum, nothing drawn.
expect_ok render --object "$O" --eye 0,0,5 --look-at 0,0,10 --size 32x32 --json "$T/away.json"
grep -q '"outside-frustum"' "$T/away.json" && passes=$((passes + 1)) || { echo "FAIL: outside-frustum skip"; \
    fails=$((fails + 1)); }

# prewarp --object writes one texture per visible face, OUT_+x.png ..., and says which.
expect_ok prewarp --object "$O" --eye 3,0.2,4 --out "$T/pw.png" --json "$T/pw.json"
for f in +x +z; do
  [ -s "$T/pw_$f.png" ] && passes=$((passes + 1)) || { echo "FAIL: prewarp --object did not write pw_$f.png"; \
      fails=$((fails + 1)); }
done
[ ! -e "$T/pw_+y.png" ] && [ ! -e "$T/pw.png" ] && passes=$((passes + 1)) || { echo "FAIL: unexpected output"; \
    fails=$((fails + 1)); }
grep -q '"out"' "$T/pw.json" && grep -q '"adjacent"' "$T/pw.json" && passes=$((passes + 1)) ||
  { echo "FAIL: prewarp --object --json"; fails=$((fails + 1)); }
# --isa picks the kernels (the faces carry discontinuity marks): every target gives the same textures.
expect_ok prewarp --object "$O" --eye 3,0.2,4 --isa generic --out "$T/pg.png"
for f in +x +z; do
  cmp -s "$T/pw_$f.png" "$T/pg_$f.png" && passes=$((passes + 1)) ||
    { echo "FAIL: prewarp --object --isa generic differs on face $f"; fails=$((fails + 1)); }
done
expect_fail 2 'isa' -- prewarp --object "$O" --eye 3,0.2,4 --isa bogus --out "$T/x.png"

# Bad usage and bad input.
expect_fail 2 'relief.*object|object.*relief' -- prewarp --eye 3,0,4 --out "$T/x.png"
expect_fail 2 'raycast' -- render --object "$O" --orbit 0,0,3 --method raycast --out "$T/x.png"
expect_fail 1 'inside' -- prewarp --object "$O" --eye 0,0,0 --out "$T/x.png"
mkdir -p "$T/o"
cp "$SRC"/media/cross-box_* "$T/o/"
python3 - "$O" "$T/o" <<'PY'
import json, sys, re
text = open(sys.argv[1]).read()
d = sys.argv[2]
open(d + "/missing.object.json", "w").write(re.sub(r'\s*"\+y": \{[^}]*\},', "", text))
open(d + "/nan.object.json", "w").write(text.replace('"displacement_range": [-2.0, 0.0]', \
    '"displacement_range": [NaN, 0.0]', 1))
open(d + "/hi.object.json", "w").write(text.replace('"displacement_range": [-2.0, 0.0]', \
    '"displacement_range": [-2.0, 0.5]', 1))
open(d + "/sizes.object.json", "w").write(text.replace("cross-box_px_color.png", \
    "small.png").replace("cross-box_px_disp.png", "small_d.png"))
PY
oiiotool --pattern constant:color=1,0,0,1 32x32 4 -d uint8 -o "$T/o/small.png" 2>/dev/null
oiiotool --pattern constant:color=0.5 32x32 1 -d uint16 -o "$T/o/small_d.png" 2>/dev/null
expect_fail 1 'missing\.object\.json.*faces.*"\+y"' -- render --object "$T/o/missing.object.json" --orbit 0,0,3 --out \
    "$T/m.png"
expect_fail 1 'nan\.object\.json' -- render --object "$T/o/nan.object.json" --orbit 0,0,3 --out "$T/m.png"
expect_fail 1 'hi\.object\.json.*"\+x".*displacement_range' -- prewarp --object "$T/o/hi.object.json" --eye 3,0,4 \
    --out "$T/m.png"
if command -v oiiotool >/dev/null; then
  expect_fail 1 'sizes\.object\.json.*"\+x".*spacing|sizes\.object\.json.*spacing.*"\+x"' -- render --object \
      "$T/o/sizes.object.json" --orbit 0,0,3 --out "$T/m.png"
fi
[ ! -e "$T/m.png" ] && [ ! -e "$T/m_+x.png" ] && passes=$((passes + 1)) || { echo "FAIL: output left behind"; \
    fails=$((fails + 1)); }
finish
