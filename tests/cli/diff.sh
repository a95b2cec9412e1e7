#!/usr/bin/env bash
# rtm diff: the printed figures on images with known differences, JSON, heat map, and errors naming the file.
. "$(dirname "$0")/lib.bash"

# 2x1 images (PPM). ref: (10,20,30) (0,0,0 = background); test: (13,24,30) (5,5,5).
# Covered in both: pixel 0 only, error (3,4,0): rmse = sqrt(25/3) = 2.88675, psnr = 38.9226, iou = 1/2.
printf 'P3\n2 1\n255\n10 20 30 0 0 0\n' >"$T/ref.ppm"
printf 'P3\n2 1\n255\n13 24 30 5 5 5\n' >"$T/test.ppm"
printf 'P3\n1 2\n255\n10 20 30 0 0 0\n' >"$T/tall.ppm"

expect_ok diff "$T/ref.ppm" "$T/test.ppm" --json "$T/d.json" --heatmap "$T/heat.png"
out=$(cat "$T/stdout")
check_line() {
  if ! grep -qx -- "$1" <<<"$out"; then
    echo "FAIL: rtm diff output lacks the line '$1':"; echo "$out"; fails=$((fails + 1))
  else
    passes=$((passes + 1))
  fi
}
check_line 'psnr 38.9226'
check_line 'rmse 2.88675'
check_line 'iou 0.5'
check_line 'max_error 5'
check_line 'covered_both 1'
check_line 'covered_either 2'
check_line 'only_ref 0'
check_line 'only_test 1'
if [ -s "$T/heat.png" ] && grep -q '"iou": 0.5' "$T/d.json" && grep -q '"covered_both": 1' "$T/d.json"; then
  passes=$((passes + 1))
else
  echo "FAIL: heat map or JSON missing or wrong: $(cat "$T/d.json" 2>/dev/null)"; fails=$((fails + 1))
fi

# Identical images: psnr inf.
expect_ok diff "$T/ref.ppm" "$T/ref.ppm"
out=$(cat "$T/stdout")
check_line 'psnr inf'
check_line 'rmse 0'
check_line 'iou 1'

# Errors: one line naming the file, exit 1; usage errors exit 2.
expect_fail 1 'nope\.png' -- diff "$T/nope.png" "$T/test.ppm"
expect_fail 1 'nope\.png' -- diff "$T/ref.ppm" "$T/nope.png"
echo "not an image" >"$T/text.png"
expect_fail 1 'text\.png' -- diff "$T/text.png" "$T/test.ppm"
expect_fail 1 'tall\.ppm.*1x2.*2x1' -- diff "$T/ref.ppm" "$T/tall.ppm"
expect_fail 2 'TEST' -- diff "$T/ref.ppm"
[ ! -e "$T/heat2.png" ] || { echo "FAIL: heat map left behind"; fails=$((fails + 1)); }
expect_fail 1 'tall\.ppm' -- diff "$T/ref.ppm" "$T/tall.ppm" --heatmap "$T/heat2.png"
if [ -e "$T/heat2.png" ]; then echo "FAIL: heat map written despite the error"; fails=$((fails + 1)); fi

finish
