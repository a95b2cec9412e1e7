#!/usr/bin/env bash
# Every benchmark of docs/BENCHMARKS.md, one after the other, on the current build: each writes its Markdown report
# and its JSON into OUT (default out/benchmarks), and OUT/runs.txt records each command with the time it started and
# ended and the load average before and after (2 is a fully busy machine of two cores). Run it on a quiet machine:
# every figure of a shared host is an upper bound. Needs build/bin/rtm (Release), media/, xvfb-run for the viewer.
#   bash scripts/benchmarks.sh [OUT]              about 10 minutes on a quiet 2-core Zen 5 guest
#   RTM_BENCH_ONLY="bench skips" bash scripts/benchmarks.sh     only the named steps (see the list below),
#                                                               added to OUT/runs.txt
set -euo pipefail
cd "$(dirname "$0")/.."
R=${RTM:-build/bin/rtm}
OUT=${1:-out/benchmarks}
mkdir -p "$OUT"
runs="$OUT/runs.txt"
[ -n "${RTM_BENCH_ONLY:-}" ] || : >"$runs"
only=${RTM_BENCH_ONLY:-}

load() { cut -d' ' -f1-3 /proc/loadavg; }
# step NAME COMMAND...: runs COMMAND with stdout to OUT/NAME.md, stderr to OUT/NAME.err, and records it.
step() {
  local name=$1
  shift
  if [ -n "$only" ] && [[ " $only " != *" $name "* ]]; then return 0; fi
  echo "== $name: $*" >&2
  local start l0
  start=$(date -u +%FT%TZ)
  l0=$(load)
  "$@" >"$OUT/$name.md" 2>"$OUT/$name.err"
  printf '%s\n  started %s, load %s\n  ended %s, load %s\n' "$*" "$start" "$l0" "$(date -u +%FT%TZ)" "$(load)" \
    >>"$runs"
}

{
  echo "commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
  lscpu | grep -E '^(Model name|CPU family|Model|CPU\(s\))' | tr -s ' '
  echo
} >>"$runs"

step bench "$R" bench --no-scene --json "$OUT/bench.json"
step bench-large "$R" bench --sizes 2048,4096 --no-table1 --no-reference --no-exact --no-scene \
  --json "$OUT/bench-large.json"
step bench-isa "$R" bench --sizes 256,1024 --isa avx512,avx3,avx2,sse4,generic --no-exact --no-table1 --no-scene \
  --json "$OUT/bench-isa.json"
step bench-marked "$R" bench --sizes 256,1024 --isa avx512,avx3,avx2,sse4,generic --methods two-pass \
  --no-exact --no-table1 --no-scene --discontinuity 0.05 --json "$OUT/bench-marked.json"
step scene "$R" bench --scene-only --json "$OUT/scene.json"
step skips "$R" bench-skips --frames 40 --json "$OUT/skips.json"
step filter "$R" bench-filter --json "$OUT/filter.json"
if command -v xvfb-run >/dev/null; then
  cat >"$OUT/spin.json" <<'JSON'
{ "fps": 30, "keys": [ {"t": 0, "orbit": [-60, 20, 2.2]}, {"t": 10, "orbit": [60, 35, 1.6]},
                       {"t": 20, "orbit": [-60, 20, 2.2]} ] }
JSON
  V=(xvfb-run -a -s "-screen 0 1280x720x24" "$R" view --size 1280x720)
  step view-floor "${V[@]}" --relief media/facade.relief.json --orbit 180,20,2.2 --frames 300 \
    --json "$OUT/view-floor.json"
  step view-floor-panel "${V[@]}" --relief media/facade.relief.json --orbit 180,20,2.2 --frames 300 --panel \
    --insets --json "$OUT/view-floor-panel.json"
  step view-relief "${V[@]}" --relief media/facade.relief.json --camera-path "$OUT/spin.json" --frames 300 \
    --json "$OUT/view-relief.json"
  step view-relief-panel "${V[@]}" --relief media/facade.relief.json --camera-path "$OUT/spin.json" --frames 300 \
    --panel --insets --json "$OUT/view-relief-panel.json"
  # The object: an octahedron baked at 256 texels a face (its box is a cube: six 256x256 faces).
  if [ ! -f "$OUT/octahedron/octahedron.object.json" ]; then
    printf 'v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n' >"$OUT/octahedron.obj"
    printf 'f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n' >>"$OUT/octahedron.obj"
    "$R" bake --mesh "$OUT/octahedron.obj" --size 256 --out "$OUT/octahedron" >/dev/null 2>&1
  fi
  step view-object-panel "${V[@]}" --object "$OUT/octahedron/octahedron.object.json" --camera-path "$OUT/spin.json" \
    --frames 300 --panel --insets --json "$OUT/view-object-panel.json"
  # (--level 0: the viewer's default for a scene until session 42, when it became auto as render --scene's.)
  step view-town-panel "${V[@]}" --scene media/town.scene.json --camera-path media/town.scene.json --frames 120 \
    --level 0 --panel --insets --json "$OUT/view-town-panel.json"
fi
step compare bash -c "/usr/bin/time -f '%e s wall, %U s user, %S s system' $R compare --relief \
media/bricks.relief.json --out $OUT/compare --size 512x512 >/dev/null 2>$OUT/compare.time; tail -1 $OUT/compare.time"
echo "wrote $OUT (commands and load averages in $runs)" >&2
