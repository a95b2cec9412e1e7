#!/usr/bin/env bash
# rtm render --method NAME for every per-pixel method at its default settings: an image of the right size with
# the relief in it, against the ray caster (rtm diff); an unknown method name is a usage error that lists them.
. "$(dirname "$0")/lib.bash"

R="$SRC/media/bumps.relief.json"
# expect_warning MESSAGE FLAGS...: render --method relief-mapping with FLAGS writes its image and warns "--MESSAGE".
expect_warning() {
  local message=$1
  shift
  if "$RTM" render --relief "$R" --eye 0,0,3 --size 32x32 --method relief-mapping "$@" --out "$T/rm.png" 2>"$T/err" &&
    grep -q -- "^rtm: warning: --$message\$" "$T/err"; then
    passes=$((passes + 1))
  else
    echo "FAIL: render --method relief-mapping $*: no warning --$message ($(cat "$T/err"))"; fails=$((fails + 1))
  fi
}
expect_ok render --relief "$R" --orbit 30,35,2.0 --size 96x96 --method raycast --out "$T/ray.png"
for m in parallax parallax-offset-limiting steep-parallax parallax-occlusion relief-mapping interval-mapping \
    protruded-displacement quadric-silhouettes; do
  expect_ok render --relief "$R" --orbit 30,35,2.0 --size 96x96 --method "$m" --out "$T/$m.png" --json "$T/$m.json"
  expect_ok diff "$T/ray.png" "$T/$m.png"
  # The relief covers most of what the ray caster covers (the top polygon loses the rays entering through the
  # slab's sides: bumps at this view, about 8%), so the IoU is far from 0. quadric-silhouettes bends the relief
  # onto a cylinder patch, so its bound is lower.
  iou=$(awk '$1 == "iou" { print $2 }' "$T/stdout")
  min=0.85; [ "$m" = quadric-silhouettes ] && min=0.5
  if awk -v x="$iou" -v min="$min" 'BEGIN { exit !(x > min) }'; then passes=$((passes + 1)); else
    echo "FAIL: $m: iou $iou against the ray caster"; fails=$((fails + 1)); fi
done
# Quadric silhouettes on a sphere patch and with the exact distance: the JSON names both; each differs from the
# default picture; an unknown value is exit 2 naming it; the flags on another method warn.
expect_ok render --relief "$R" --orbit 30,35,2.0 --size 96x96 --method quadric-silhouettes --curved-base sphere \
  --quadric-distance exact --out "$T/sphere.png" --json "$T/sphere.json"
if python3 -c 'import json, sys; j = json.load(open(sys.argv[1])); d = json.load(open(sys.argv[2]))
sys.exit(not (j["curved_base"] == "sphere" and j["quadric_distance"] == "exact" and d["curved_base"] == "cylinder"
              and d["quadric_distance"] == "approximate"))' "$T/sphere.json" "$T/quadric-silhouettes.json"; then
  passes=$((passes + 1))
else
  echo "FAIL: render --curved-base sphere --quadric-distance exact: JSON $(cat "$T/sphere.json")"
  fails=$((fails + 1))
fi
expect_ok diff "$T/quadric-silhouettes.png" "$T/sphere.png"
if awk '$1 == "iou" { exit !($2 < 0.99) }' "$T/stdout"; then passes=$((passes + 1)); else
  echo "FAIL: the sphere patch drew the cylinder's picture: $(cat "$T/stdout")"; fails=$((fails + 1)); fi
expect_fail 2 'curved-base.*"cone"' -- render --relief "$R" --eye 0,0,3 --method quadric-silhouettes \
  --curved-base cone --out "$T/bad.png"
expect_fail 2 'quadric-distance.*"exactly"' -- render --relief "$R" --eye 0,0,3 --method quadric-silhouettes \
  --quadric-distance exactly --out "$T/bad.png"
expect_warning 'curved-base applies to --relief with --method quadric-silhouettes' --curved-base sphere
# Protruded displacement mapping's steep slopes: the built-in wall texture or an image changes the picture where the
# relief is steep, the JSON names it, a missing image is exit 1 naming it, another method warns.
F="$SRC/media/facade.relief.json"
expect_ok render --relief "$F" --orbit 40,15,2.2 --size 96x96 --method protruded-displacement --out "$T/pd.png"
for tex in builtin "$SRC/media/bricks_color.png"; do
  expect_ok render --relief "$F" --orbit 40,15,2.2 --size 96x96 --method protruded-displacement \
    --steep-texture "$tex" --out "$T/pd_steep.png" --json "$T/pd_steep.json"
  expect_ok diff "$T/pd.png" "$T/pd_steep.png"
  # The same coverage (only colours change) and not the same picture.
  if awk '$1 == "iou" { i = $2 } $1 == "psnr" { p = $2 } END { exit !(i == 1 && p != "inf") }' "$T/stdout" &&
    grep -q "\"steep_texture\": \"$tex\"" "$T/pd_steep.json"; then
    passes=$((passes + 1))
  else
    echo "FAIL: --steep-texture $tex: $(cat "$T/stdout") $(grep steep "$T/pd_steep.json")"; fails=$((fails + 1))
  fi
done
expect_fail 1 'nowhere.png' -- render --relief "$F" --eye 0,0,3 --method protruded-displacement \
  --steep-texture "$T/nowhere.png" --out "$T/bad.png"
expect_warning 'steep-texture applies to --relief with --method protruded-displacement' --steep-texture builtin
expect_fail 2 'method.*relief-maping.*relief-mapping' -- render --relief "$R" --eye 0,0,1 --method relief-maping \
  --out "$T/bad.png"
[ -e "$T/bad.png" ] && { echo "FAIL: an output file after a usage error"; fails=$((fails + 1)); }
finish
