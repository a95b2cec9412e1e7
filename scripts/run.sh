#!/usr/bin/env bash
# The main job: installs what is missing, builds, and renders the shipped media with every method at eight
# views, writing the pictures and a table of run time against error (vs the ray-cast truth) to out/:
# out/NAME/*.png, out/NAME/compare.{md,json}, and everything in out/REPORT.md.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
mkdir -p out
report=out/REPORT.md
echo "# rtm: every method on the shipped media" >"$report.tmp"
for m in media/*.relief.json; do
  name=$(basename "$m" .relief.json)
  echo "== $name" >&2
  build/bin/rtm compare --relief "$m" --out "out/$name" >/dev/null
  { echo; cat "out/$name/compare.md"; } >>"$report.tmp"
done
mv "$report.tmp" "$report"
echo "wrote $report and the pictures in out/*/"
