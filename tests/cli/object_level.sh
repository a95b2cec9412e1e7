#!/usr/bin/env bash
# Six-face objects at `--level auto`: each face takes the relief quad's parallax-bounded level
# (objects/level_choice.h, plan_object_face), and `prewarp --object --level auto` picks the levels
# `render --object --level auto` draws from the same eye (its default 512x512, 45-degree camera).
# By texel density alone, the rule before, both picked +x 1, +y 3, +z 1 at eye 30,5,40 and +x 1, +y 4, +z 4 at
# 60,2,3, where the cross-box's arms stand parallax of more than half a pixel out of their faces.
. "$(dirname "$0")/lib.bash"
O=$SRC/media/cross-box.object.json
levels() {
  python3 -c 'import json, sys
print(" ".join(f["face"] + ":" + str(f["level"]) for f in json.load(open(sys.argv[1]))["faces"]))' "$1"
}
for e in 30,5,40 60,2,3 9,9,9 3,0.2,4; do
  expect_ok prewarp --object "$O" --eye "$e" --level auto --out "$T/p.png" --json "$T/p.json"
  expect_ok render --object "$O" --eye "$e" --level auto --out "$T/r.png" --json "$T/r.json"
  p=$(levels "$T/p.json"); r=$(levels "$T/r.json")
  if [ "$p" = "$r" ]; then passes=$((passes + 1))
  else echo "FAIL: prewarp ($p) and render ($r) --level auto differ at eye $e"; fails=$((fails + 1)); fi
  case $e in
    30,5,40) want="+x:0 +y:0 +z:0" ;;
    60,2,3) want="+x:1 +y:0 +z:0" ;;
    *) want=$r ;;
  esac
  if [ "$r" = "$want" ]; then passes=$((passes + 1))
  else echo "FAIL: render --level auto at eye $e drew $r, want $want"; fails=$((fails + 1)); fi
done
finish
