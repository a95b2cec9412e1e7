#!/usr/bin/env bash
# The interactive viewer under Xvfb: N frames, a screenshot, equal to the headless render of the same camera.
. "$(dirname "$0")/lib.bash"
M=$SRC/media/facade.relief.json
if ! command -v xvfb-run >/dev/null; then
  echo "xvfb-run is missing (scripts/setup.sh installs it)"
  exit 1
fi
# Without a display the viewer says so and exits 1.
env -u DISPLAY -u WAYLAND_DISPLAY "$RTM" view --relief "$M" --frames 1 --screenshot "$T/x.png" 2>"$T/err"
st=$?
if [ "$st" != 1 ] || ! grep -q "display" "$T/err" || [ -e "$T/x.png" ]; then
  echo "FAIL: no display: exit $st, $(cat "$T/err")"; fails=$((fails + 1))
else passes=$((passes + 1)); fi

if xvfb-run -a "$RTM" view --relief "$M" --orbit 30,20,2.2 --size 320x240 --frames 3 --screenshot "$T/view.png" \
    2>"$T/err"; then
  passes=$((passes + 1))
else
  echo "FAIL: view under Xvfb: $(cat "$T/err")"; fails=$((fails + 1))
fi
expect_ok render --relief "$M" --orbit 30,20,2.2 --size 320x240 --out "$T/render.png"
# Same camera, same code path, another framebuffer: identical up to llvmpipe's rounding (PSNR well above 40 dB).
if "$RTM" diff "$T/render.png" "$T/view.png" >"$T/diff"; then
  psnr=$(awk '/^psnr/ {print $2}' "$T/diff")
  iou=$(awk '/^iou/ {print $2}' "$T/diff")
  if awk -v p="$psnr" -v i="$iou" 'BEGIN { exit !((p == "inf" || p > 40) && i > 0.999) }'; then
    passes=$((passes + 1))
  else
    echo "FAIL: viewer and render differ: psnr $psnr iou $iou"; fails=$((fails + 1))
  fi
else
  echo "FAIL: diff failed"; fails=$((fails + 1))
fi
finish
