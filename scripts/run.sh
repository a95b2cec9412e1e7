#!/usr/bin/env bash
# The main job: installs what is missing, builds, and compares every method at every quality setting on the four
# shipped relief textures at eight views from frontal to grazing (rtm compare, docs/COMPARE.md): the page
# out/compare/index.html, with results.csv, results.json, compare.md and the pictures beside it. 384x384 pixels and
# 2 timed frames per method and view keep it to a few minutes on two cores (the README's figures are 512x512).
# Then the relief town with flat and relief texture mapping (out/town/, the paper's Figures 1 and 2) and its frame
# counts and stage times. Everything in out/REPORT.md.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
mkdir -p out
report=out/REPORT.md
echo "# rtm: every method on the shipped media" >"$report.tmp"
echo "== compare: bricks, facade, bumps, ridges" >&2
build/bin/rtm compare --relief media/bricks.relief.json --relief media/facade.relief.json \
  --relief media/bumps.relief.json --relief media/ridges.relief.json --size 384x384 --repeat 2 \
  --out out/compare >/dev/null
{ echo; cat out/compare/compare.md; } >>"$report.tmp"
echo "== town" >&2
mkdir -p out/town
{
  echo
  echo "## The relief town (media/town.scene.json, 640x480, its default camera)"
  echo
  echo "| method | quads drawn | quads pre-warped | texels warped | frame ms |"
  echo "|---|---:|---:|---:|---:|"
} >>"$report.tmp"
for method in flat two-pass; do
  build/bin/rtm render --scene media/town.scene.json --method "$method" --size 640x480 \
    --out "out/town/town_$method.png" --json "out/town/town_$method.json"
  python3 - "out/town/town_$method.json" "$method" >>"$report.tmp" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
print(f"| {sys.argv[2]} | {j['quads_drawn']} of {j['quads']} | {j['quads_prewarped']} | {j['texels_warped']} | "
      f"{j['total_ms']['median']:.1f} |")
PY
done
echo >>"$report.tmp"
echo "Pictures: out/town/town_flat.png, out/town/town_two-pass.png." >>"$report.tmp"
mv "$report.tmp" "$report"
echo "wrote $report; the comparison page: $(pwd)/out/compare/index.html"
