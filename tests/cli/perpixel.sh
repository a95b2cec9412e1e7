#!/usr/bin/env bash
# rtm render --method NAME for every per-pixel method at its default settings: an image of the right size with
# the relief in it, against the ray caster (rtm diff); an unknown method name is a usage error that lists them.
. "$(dirname "$0")/lib.bash"

R="$SRC/media/bumps.relief.json"
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
expect_fail 2 'method.*relief-maping.*relief-mapping' -- render --relief "$R" --eye 0,0,1 --method relief-maping \
  --out "$T/bad.png"
[ -e "$T/bad.png" ] && { echo "FAIL: an output file after a usage error"; fails=$((fails + 1)); }
finish
