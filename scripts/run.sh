#!/usr/bin/env bash
# The main job: installs what is missing, builds, and renders the shipped relief textures with every method at
# eight views, writing the pictures and a table of run time against error (vs the ray-cast truth) to out/:
# out/NAME/*.png, out/NAME/compare.{md,json}, and everything in out/REPORT.md; then the relief town with flat and
# relief texture mapping (out/town/, the paper's Figures 1 and 2) and its frame counts and stage times.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
mkdir -p out
report=out/REPORT.md
echo "# rtm: every method on the shipped media" >"$report.tmp"
for name in bricks facade bumps ridges; do
  m=media/$name.relief.json
  echo "== $name" >&2
  build/bin/rtm compare --relief "$m" --out "out/$name" >/dev/null
  { echo; cat "out/$name/compare.md"; } >>"$report.tmp"
done
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
echo "wrote $report and the pictures in out/*/"
