#!/usr/bin/env bash
# The main job: installs what is missing, builds, and renders the shipped media with every method, writing
# pictures and a table of time against error to out/ (out/REPORT.md).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
mkdir -p out
for m in media/*.relief.json; do
  build/bin/rtm compare --relief "$m" --out "out/$(basename "$m" .relief.json)"
done
build/bin/rtm report out > out/REPORT.md
echo "wrote out/REPORT.md"
