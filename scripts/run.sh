#!/usr/bin/env bash
# The main job: installs what is missing, builds, and compares every method at every quality setting on the four
# shipped relief textures at eight views from frontal to grazing (rtm compare, docs/COMPARE.md): the page
# out/compare/index.html, with results.csv, results.json, compare.md and the pictures beside it. 384x384 pixels and
# 2 timed frames per method and view keep it to a few minutes on two cores (the README's figures are 512x512).
# Then the relief town and the registered room with flat and relief texture mapping (out/town/ and out/room/, the
# paper's Figures 1-2 and 22-23) and their frame counts and stage times. Everything in out/REPORT.md.
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
# A shipped scene from its default camera at 640x480, flat and with relief: pictures in out/NAME/, a table of its
# frame counts and stage times in the report.
# render_scene NAME TITLE [FLAT]: flat texture mapping draws media/FLAT.scene.json (default NAME): the room's
# reliefs look down at their walls, and its walls' own texture maps are room_walls (docs/SCENES.md).
render_scene() {
  local name=$1 title=$2 flat=${3:-$1}
  echo "== $name" >&2
  mkdir -p "out/$name"
  {
    echo
    echo "## $title (media/$name.scene.json, 640x480, its default camera)"
    echo
    echo "| method | quads drawn | quads pre-warped | texels warped | frame ms |"
    echo "|---|---:|---:|---:|---:|"
  } >>"$report.tmp"
  for method in flat two-pass; do
    local scene=$name
    [ "$method" = flat ] && scene=$flat
    build/bin/rtm render --scene "media/$scene.scene.json" --method "$method" --size 640x480 \
      --out "out/$name/${name}_$method.png" --json "out/$name/${name}_$method.json"
    python3 - "out/$name/${name}_$method.json" "$method" >>"$report.tmp" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
print(f"| {sys.argv[2]} | {j['quads_drawn']} of {j['quads']} | {j['quads_prewarped']} | {j['texels_warped']} | "
      f"{j['total_ms']['median']:.1f} |")
PY
  done
  echo >>"$report.tmp"
  echo "Pictures: out/$name/${name}_flat.png, out/$name/${name}_two-pass.png." >>"$report.tmp"
}
render_scene town "The relief town (the paper's Figures 1 and 2)"
render_scene room "The registered room: four relief walls baked from a mesh, plain floor and ceiling (Figures 22-23)" \
  room_walls
mv "$report.tmp" "$report"
echo "wrote $report; the comparison page: $(pwd)/out/compare/index.html"
