#!/usr/bin/env bash
# Objects baked from real meshes against the meshes themselves (docs/ACCURACY.md, "Objects baked from meshes").
# For each model of Debian's assimp-testmodels below: `rtm compare --mesh` bakes it at 256 texels along the box's
# longest side and renders 32 views (measure/object_accuracy.h) at 512x512 by two-pass and pipelined relief
# texture mapping and by conventional OpenGL (the truth). Writes OUT/NAME/{compare.md,compare.json,*.png} and
# prints the summary table of docs/ACCURACY.md. With --figures, also writes the small pictures of docs/images/.
#   bash scripts/mesh_accuracy.sh [--figures] [OUT]        (default OUT: out/mesh_accuracy; needs build/bin/rtm)
set -euo pipefail
cd "$(dirname "$0")/.."
R=${RTM:-build/bin/rtm}
figures=0
if [ "${1:-}" = --figures ]; then figures=1; shift; fi
OUT=${1:-out/mesh_accuracy}
M=/usr/share/assimp/models
models=("$M/Collada/duck.dae" "$M/OBJ/spider.obj" "$M/glTF/CesiumMilkTruck/CesiumMilkTruck.gltf")
for m in "${models[@]}"; do
  [ -f "$m" ] || { echo "missing $m: install assimp-testmodels (scripts/setup.sh)" >&2; exit 1; }
  name=$(basename "${m%.*}")
  "$R" compare --mesh "$m" --texels 256 --size 512x512 --out "$OUT/$name" >/dev/null
done
python3 - "$OUT" "${models[@]}" <<'PY'
import json, os, sys
out, models = sys.argv[1], sys.argv[2:]
print('| model | method | views | mean IoU | worst IoU (view) | mean PSNR dB | worst PSNR dB (view) |')
print('|---|---|---:|---:|---|---:|---|')
for m in models:
    name = os.path.splitext(os.path.basename(m))[0]
    j = json.load(open(os.path.join(out, name, 'compare.json')))
    for s in j['summary']:
        print(f"| {os.path.relpath(m, '/usr/share/assimp/models')} | {s['method']} | {s['views']} | "
              f"{s['mean_iou']:.4f} | {s['worst_iou']:.4f} ({s['worst_iou_view']}) | {s['mean_psnr']:.2f} | "
              f"{s['worst_psnr']:.2f} ({s['worst_psnr_view']}) |")
PY
if [ "$figures" = 1 ]; then
  # Mesh | two-pass object | error heat map (measure/image_diff.h colours), 192 pixels each, for a few views.
  D=docs/images
  for pick in duck:az45_el35 duck:az90_el00 spider:az00_el60 CesiumMilkTruck:az45_el-30; do
    name=${pick%%:*} view=${pick#*:}
    oiiotool "$OUT/$name/${view}_mesh.png" --resize 192x192 "$OUT/$name/${view}_two-pass.png" --resize 192x192 \
      "$OUT/$name/${view}_two-pass_error.png" --resize 192x192 --mosaic 3x1 --ch R,G,B \
      -o "$D/baked_${name}_${view}.png"
  done
  echo "figures written to $D" >&2
fi
