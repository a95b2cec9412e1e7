#!/usr/bin/env bash
# Regenerates the README's pictures in docs/images/ from the shipped media (needs a build in build/).
set -euo pipefail
cd "$(dirname "$0")/.."
R=build/bin/rtm
D=docs/images
mkdir -p "$D"
view="--orbit 50,15,2.0 --size 384x384"
for m in flat two-pass raycast; do
  $R render --relief media/facade.relief.json $view --method "$m" --out "$D/facade_$m.png"
done
$R render --relief media/bricks.relief.json --orbit 60,25,1.6 --size 384x384 --method flat --out "$D/bricks_flat.png"
$R render --relief media/bricks.relief.json --orbit 60,25,1.6 --size 384x384 --method two-pass --out \
    "$D/bricks_two-pass.png"
# The pre-warped texture for the same eye as the facade view (Figure 9c).
eye=$($R render --relief media/facade.relief.json $view --method flat --json /tmp/rtm_eye.json >/dev/null &&
      sed -n '/"eye"/,/]/p' /tmp/rtm_eye.json | tr -d ' \n' | sed 's/"eye":\[\(.*\)\],*/\1/')
$R prewarp --relief media/facade.relief.json --eye "$eye" --out "$D/facade_prewarped.png"
cp media/facade_color.png "$D/facade_source.png"
# The viewer with its panel, the insets (the visible faces' pre-warps, Figure 17) and the outlines, of an object.
xvfb-run -a -s "-screen 0 1280x720x24" $R view media/rounded-cube.object.json --orbit 35,25,1.7 --size 1280x720 \
    --panel --insets --outlines --frames 20 --screenshot "$D/viewer.png"
echo "figures written to $D"
