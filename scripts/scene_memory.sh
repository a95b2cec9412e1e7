#!/usr/bin/env bash
# What a scene of many placements of one relief costs: for each N, a scene of N items naming media/bumps.relief.json
# (256x256) on a grid 1.2 apart (20 to a row up to 1,000 items, 100 to a row beyond, to stay under the manifest's
# 1 MiB), one frame of `rtm render --scene` at SIZE, and a Markdown row of the process's maximum resident memory
# (getrusage's ru_maxrss of the child), its wall time and the first frame's `total_ms` (--json). docs/BENCHMARKS.md,
# "Scenes of many placements", and docs/SCENES.md, "Memory", give its runs.
#   bash scripts/scene_memory.sh [N ...]         default 1 100 400 1000 8000; RTM=... another binary, SIZE=WxH
set -euo pipefail
cd "$(dirname "$0")/.."
R=${RTM:-build/bin/rtm}
SIZE=${SIZE:-320x240}
counts=("$@")
[ ${#counts[@]} -gt 0 ] || counts=(1 100 400 1000 8000)
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
relief=$(pwd)/media/bumps.relief.json
echo "| relief items | max resident memory | wall time | first frame (total_ms) |"
echo "|---:|---:|---:|---:|"
for n in "${counts[@]}"; do
    python3 - "$n" "$relief" "$T/s$n.scene.json" <<'PY'
import json, sys
n, relief, out = int(sys.argv[1]), sys.argv[2], sys.argv[3]
row = 20 if n <= 1000 else 100
items = [{"type": "relief", "relief": relief, "transform": {"translate": [(i % row) * 1.2, 0, -(i // row) * 1.2]}}
         for i in range(n)]
scene = {"camera": {"eye": [5, 8, 10], "look_at": [10, 0, -5], "up": [0, 1, 0], "fov": 60}, "items": items}
json.dump(scene, open(out, "w"), separators=(",", ":"))
PY
    echo "scene_memory: $n items" >&2
    python3 - "$R" "$T/s$n.scene.json" "$SIZE" "$T/s$n.png" "$T/s$n.json" "$n" <<'PY'
import json, resource, subprocess, sys, time
rtm, scene, size, png, js, n = sys.argv[1:]
start = time.monotonic()
subprocess.run([rtm, "render", "--scene", scene, "--size", size, "--out", png, "--json", js], check=True)
secs = time.monotonic() - start
mib = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss // 1024  # KiB on Linux
frame = json.load(open(js))["total_ms"]["median"]
print("| %s | %d MiB | %.2f s | %.0f ms |" % (n, mib, secs, frame))
PY
done
