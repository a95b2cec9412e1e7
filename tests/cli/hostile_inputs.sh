#!/usr/bin/env bash
# Hostile input on the command line (docs/FORMATS.md, "Exit status and errors"): every bad file or camera makes
# `rtm render`, `rtm prewarp` and `rtm diff` exit 1 (bad file) or 2 (bad flag) with exactly one line on stderr that
# contains the message given here (which names the file or the flag), without a crash or a hang, and without
# leaving anything in the output folder: no output image, no JSON, no temporary file.
#
# The corpus is generated at run time into a fresh temporary folder: manifests of every kind the reader must refuse,
# images that are empty, truncated, corrupt, not images at all, or whose headers claim absurd sizes, displacement
# that is non-finite or outside 0..1, colour and displacement of different sizes, and degenerate cameras.
# tests/formats/relief_manifest_test.cpp and tests/formats/image_io_test.cpp hold the finer-grained unit corpus.
. "$(dirname "$0")/lib.bash"
command -v python3 >/dev/null || { echo "FAIL: python3 is needed to write the binary test files"; exit 1; }

D=$T/m  # the corpus
make_small_relief "$D"
R=$D/ok.relief.json

# --- The checks.

n=0
# new_out: a fresh, empty output folder $O for the next case.
new_out() {
  n=$((n + 1))
  O=$T/out$n
  mkdir -p "$O"
}
# check STATUS MESSAGE -- ARGS...: rtm ARGS exits with STATUS within 120 s, prints exactly one line on stderr that
# contains MESSAGE (a fixed string), and leaves the folder $O (where ARGS put every output) empty.
check() {
  local want=$1 msg=$2
  shift 3
  timeout 120 "$RTM" "$@" >"$T/stdout" 2>"$T/stderr"
  local got=$?
  local lines
  lines=$(grep -c '' "$T/stderr")
  if [ "$got" != "$want" ] || [ "$lines" != 1 ] || ! grep -qF -- "$msg" "$T/stderr"; then
    echo "FAIL: rtm $*"
    echo "  want exit $want and one line containing: $msg"
    echo "  got exit $got, $lines line(s): $(head -c 2000 "$T/stderr")"
    fails=$((fails + 1))
  elif [ -n "$(ls -A "$O")" ]; then
    echo "FAIL: rtm $* left behind: $(ls -A "$O" | tr '\n' ' ')"
    fails=$((fails + 1))
  else
    passes=$((passes + 1))
  fi
}
# reject_relief MANIFEST MESSAGE: rtm refuses MANIFEST with exit 1 and MESSAGE, with render and prewarp taking
# turns (both read it through load_relief; a process start costs ~0.3 s, and CI time matters).
turn=0
reject_relief() {
  local m=$1 msg=$2
  new_out
  if [ $((turn++ % 2)) = 0 ]; then
    check 1 "$msg" -- render --relief "$m" --eye 0.5,0.5,3 --size 16x16 --out "$O/r.png" --json "$O/r.json"
  else
    check 1 "$msg" -- prewarp --relief "$m" --eye 0.5,0.5,3 --out "$O/p.png" --json "$O/p.json"
  fi
}
# manifest NAME JSON: writes $D/NAME.relief.json and prints its path.
manifest() {
  printf '%s' "$2" >"$D/$1.relief.json"
  echo "$D/$1.relief.json"
}
# edit NAME SED-SCRIPT: the valid manifest changed by a sed script, written as $D/NAME.relief.json; prints its path.
edit() {
  sed "$2" "$R" >"$D/$1.relief.json"
  if cmp -s "$R" "$D/$1.relief.json"; then echo "$1: '$2' changed nothing" >>"$T/test_bugs"; fi
  echo "$D/$1.relief.json"
}
# with_color NAME FILE / with_disp NAME FILE: the valid manifest with its colour / displacement image replaced.
with_color() { edit "$1" "s|\"c.ppm\"|\"$2\"|"; }
with_disp() { edit "$1" "s|\"d.pgm\"|\"$2\"|"; }

# The valid relief and images work, and leave only what was asked for.
new_out
expect_ok render --relief "$R" --eye 0.5,0.5,3 --size 16x16 --out "$O/r.png"
expect_ok prewarp --relief "$R" --eye 0.5,0.5,3 --out "$O/p.png"
expect_ok diff "$O/r.png" "$O/r.png"
[ "$(ls -A "$O" | tr '\n' ' ')" = "p.png r.png " ] || { echo "FAIL: stray files: $(ls -A "$O")"; fails=$((fails + 1)); }

# --- The manifest file itself.

reject_relief "$D/nope.relief.json" "$D/nope.relief.json: cannot open relief manifest: No such file or directory"
mkdir -p "$D/folder.relief.json"
reject_relief "$D/folder.relief.json" "$D/folder.relief.json: is a directory, expected a relief manifest file"
mkfifo "$D/fifo.relief.json"  # reading a FIFO would block: it must be refused without opening it
reject_relief "$D/fifo.relief.json" "$D/fifo.relief.json: is not a regular file"
reject_relief "$(manifest empty '')" "$D/empty.relief.json: relief manifest is empty, expected a JSON object"
reject_relief "$(manifest blank $' \n\t\r\n')" "$D/blank.relief.json: relief manifest is empty"
head -c 1048577 /dev/zero | tr '\0' ' ' >"$D/huge.relief.json"
reject_relief "$D/huge.relief.json" "$D/huge.relief.json: relief manifest is 1048577 bytes, expected at most 1048576"
head -c 600 "$(command -v bash)" >"$D/binary.relief.json"  # an ELF header: NUL bytes and all
reject_relief "$D/binary.relief.json" "$D/binary.relief.json: malformed JSON"

# --- Malformed and truncated JSON.

reject_relief "$(manifest truncated '{"color": "c.ppm", "displacement"')" "$D/truncated.relief.json: truncated JSON"
reject_relief "$(head -c 60 "$R" >"$D/cut.relief.json"; echo "$D/cut.relief.json")" "$D/cut.relief.json: truncated JSON"
reject_relief "$(manifest double_comma '{"color": "c.ppm",, }')" "$D/double_comma.relief.json: malformed JSON"
reject_relief "$( (cat "$R"; echo x) >"$D/trailing.relief.json"; echo "$D/trailing.relief.json")" \
  "$D/trailing.relief.json: malformed JSON"
reject_relief "$(edit nan_literal 's/"a": \[0.25, 0, 0\]/"a": [NaN, 0, 0]/')" \
  "$D/nan_literal.relief.json: malformed JSON"
{ printf '{ "name": "\xff\xfe",'; tail -c +2 "$R"; } >"$D/bad_utf8.relief.json"
reject_relief "$D/bad_utf8.relief.json" "$D/bad_utf8.relief.json: malformed JSON"
reject_relief "$(manifest top_array '[1, 2, 3]')" \
  "$D/top_array.relief.json: top level must be a JSON object, found [1, 2, 3]"
{ # 500,000 levels of nesting, just under the 1 MiB limit (too long for a sed argument)
  printf '{ "color": "c.ppm", "displacement": "d.pgm", "displacement_range": [0.0, 0.5], "origin": [0, 0, 0], "a": '
  printf '%*s' 500000 '' | tr ' ' '['
  printf '%*s' 500000 '' | tr ' ' ']'
  printf ', "b": [0, 0.25, 0] }'
} >"$D/deep.relief.json"
reject_relief "$D/deep.relief.json" \
  "$D/deep.relief.json: field \"a\" must be an array of 3 finite numbers, found [[...]]"

# --- Missing fields.

for f in color displacement displacement_range origin a; do
  reject_relief "$(edit "missing_$f" "s/\"$f\": \(\"[^\"]*\"\|\[[^]]*\]\), *//")" \
    "$D/missing_$f.relief.json: required field \"$f\" is missing"
done
reject_relief "$(edit missing_b 's/, "b": \[[^]]*\]//')" "$D/missing_b.relief.json: required field \"b\" is missing"

# --- Wrong types.

reject_relief "$(edit color_number 's/"c.ppm"/3/')" \
  "$D/color_number.relief.json: field \"color\" must be a non-empty string (an image file name), found 3"
reject_relief "$(edit color_empty 's/"c.ppm"/""/')" \
  "$D/color_empty.relief.json: field \"color\" must be a non-empty string"
reject_relief "$(edit disp_array 's/"d.pgm"/["d.pgm"]/')" "$D/disp_array.relief.json: field \"displacement\""
reject_relief "$(edit range_string 's/\[0.0, 0.5\]/"0 0.5"/')" \
  "$D/range_string.relief.json: field \"displacement_range\" must be an array of 2 finite numbers"\
" [min, max], found the string \"0 0.5\""
reject_relief "$(edit origin_object 's/"origin": \[0, 0, 0\]/"origin": {"x": 0, "y": 0, "z": 0}/')" \
  "$D/origin_object.relief.json: field \"origin\" must be an array of 3 finite numbers, found an object with 3 fields"
reject_relief "$(edit b_bool 's/"b": \[0, 0.25, 0\]/"b": [0, true, 0]/')" \
  "$D/b_bool.relief.json: field \"b\" must be an array of 3 finite numbers, found [0, true, 0]"
reject_relief "$(edit name_number 's/{/{ "name": 5,/')" \
  "$D/name_number.relief.json: field \"name\" must be a string, found 5"
reject_relief "$(edit threshold_string 's/{/{ "discontinuity_threshold": "abc",/')" \
  "$D/threshold_string.relief.json: field \"discontinuity_threshold\" must be a finite number >= 0"

# --- Non-finite numbers.

reject_relief "$(edit origin_inf 's/"origin": \[0, 0, 0\]/"origin": [1e999, 0, 0]/')" \
  "$D/origin_inf.relief.json: field \"origin\" must hold finite numbers, found 1e999, which overflows a double"
reject_relief "$(edit range_inf 's/\[0.0, 0.5\]/[-1e999, 0.5]/')" \
  "$D/range_inf.relief.json: field \"displacement_range\" must hold finite numbers, found -1e999"
reject_relief "$(edit threshold_inf 's/{/{ "discontinuity_threshold": 1e400,/')" \
  "$D/threshold_inf.relief.json: field \"discontinuity_threshold\" must hold finite numbers, found 1e400"

# --- Vectors of the wrong length, and values out of their domain.

reject_relief "$(edit origin_two 's/"origin": \[0, 0, 0\]/"origin": [0, 0]/')" \
  "$D/origin_two.relief.json: field \"origin\" must be an array of 3 finite numbers, found [0, 0]"
reject_relief "$(edit a_four 's/"a": \[0.25, 0, 0\]/"a": [0.25, 0, 0, 0]/')" \
  "$D/a_four.relief.json: field \"a\" must be an array of 3 finite numbers, found [0.25, 0, 0, 0]"
reject_relief "$(edit b_empty 's/"b": \[0, 0.25, 0\]/"b": []/')" \
  "$D/b_empty.relief.json: field \"b\" must be an array of 3 finite numbers, found []"
reject_relief "$(edit range_one 's/\[0.0, 0.5\]/[0.5]/')" \
  "$D/range_one.relief.json: field \"displacement_range\" must be an array of 2 finite numbers [min, max], found [0.5]"
reject_relief "$(edit range_three 's/\[0.0, 0.5\]/[0, 0.5, 1]/')" \
  "$D/range_three.relief.json: field \"displacement_range\""
reject_relief "$(edit range_inverted 's/\[0.0, 0.5\]/[0.5, 0.0]/')" \
  "$D/range_inverted.relief.json: field \"displacement_range\" must be [min, max] with min <= max, found [0.5, 0.0]"
reject_relief "$(edit range_beyond_float 's/\[0.0, 0.5\]/[-1e300, 1e300]/')" \
  "$D/range_beyond_float.relief.json: field \"displacement_range\" [-1e+300, 1e+300]"\
" gives displacements too large for single precision"
reject_relief "$(edit threshold_negative 's/{/{ "discontinuity_threshold": -1,/')" \
  "$D/threshold_negative.relief.json: field \"discontinuity_threshold\" must be a finite number >= 0"\
" (world units), found -1"
reject_relief "$(edit a_zero 's/"a": \[0.25, 0, 0\]/"a": [0, 0, 0]/')" \
  "$D/a_zero.relief.json: field \"a\" has zero length"
reject_relief "$(edit ab_parallel 's/"b": \[0, 0.25, 0\]/"b": [-0.5, 0, 0]/')" \
  "$D/ab_parallel.relief.json: fields \"a\" and \"b\" are parallel"
reject_relief "$(edit ab_tiny 's/"a": \[0.25, 0, 0\], "b": \[0, 0.25, 0\]/"a": [1e-200, 0, 0], "b": [0, 1e-200, 0]/')" \
  "$D/ab_tiny.relief.json: fields \"a\" and \"b\" are too small or too large for double precision"
reject_relief "$(edit ab_huge 's/"a": \[0.25, 0, 0\], "b": \[0, 0.25, 0\]/"a": [1e200, 0, 0], "b": [0, 1e200, 0]/')" \
  "$D/ab_huge.relief.json: fields \"a\" and \"b\" are too small or too large for double precision"

# --- Image paths that do not exist or are folders.

reject_relief "$(with_color color_missing nope.png)" \
  "$D/color_missing.relief.json: $D/nope.png: cannot open: No such file or directory"
reject_relief "$(with_disp disp_missing sub/gone.pgm)" \
  "$D/disp_missing.relief.json: $D/sub/gone.pgm: cannot open: No such file or directory"
# A newline in a file name (legal in JSON and on Linux) must not break the message's one line: shown as '?'.
reject_relief "$(with_color color_newline 'a\\nb.png')" \
  "$D/color_newline.relief.json: $D/a?b.png: cannot open: No such file or directory"
mkdir -p "$D/dir.png"
reject_relief "$(with_color color_folder dir.png)" "$D/color_folder.relief.json: $D/dir.png: is a directory"
reject_relief "$(with_disp disp_folder .)" "$D/disp_folder.relief.json: $D/: is a directory"
reject_relief "$(with_color color_fifo fifo.relief.json)" \
  "$D/color_fifo.relief.json: $D/fifo.relief.json: is not a regular file"

# --- Bad images: written with python3 (PNG chunks need their CRCs).

python3 - "$D" <<'PY'
import random, struct, sys, zlib
d = sys.argv[1]
def write(name, data):
    with open(f"{d}/{name}", "wb") as f:
        f.write(data)
def chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
def png(w, h, idat):
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", idat) + chunk(b"IEND", b""))
def pfm(w, h, values):  # little endian (scale -1), rows bottom to top
    return f"Pf\n{w} {h}\n-1.0\n".encode() + struct.pack(f"<{len(values)}f", *values)
random.seed(1)
# 64x64 RGB noise, which deflate cannot shrink: cutting it in half cuts the pixel data.
raw = b"".join(b"\0" + bytes(random.randrange(256) for _ in range(64 * 3)) for _ in range(64))
good = png(64, 64, zlib.compress(raw))
write("noise64.png", good)
write("truncated.png", good[: len(good) // 2])
write("header_only.png", good[:20])
bad = bytearray(good); bad[100] ^= 0xFF; bad[300] ^= 0xFF
write("corrupt.png", bytes(bad))                              # IDAT checksums no longer match
write("bad_zlib.png", png(64, 64, b"garbage!" * 40))          # valid chunks, garbage compressed data
write("huge.png", png(100000, 100000, zlib.compress(b"\0" * 1000)))
# A tEXt chunk claiming 2 GB in a 100-byte file: libpng would allocate and clear what it claims (a fuzzing find).
ihdr = chunk(b"IHDR", struct.pack(">IIBBBBB", 4, 4, 8, 2, 0, 0, 0))
write("text_2gb.png", b"\x89PNG\r\n\x1a\n" + ihdr + struct.pack(">I", 2016634473) + b"tEXtComment\0" + b"x" * 40)
# The same in OpenEXR: a string attribute claiming 1.9 GB, which OpenEXR 3.1 would allocate and clear.
exr_magic = b"\x76\x2f\x31\x01\x02\0\0\0"
write("attr_2gb.exr", exr_magic + b"comments\0string\0" + struct.pack("<i", 1929379935) + b"x" * 40)
# The same string behind a channel list whose size field says 1 byte: OpenEXR reads a channel list to its empty name
# whatever the size field says, so a walk trusting the field lost step and missed the string (a fuzzing find).
channel = b"R\0" + struct.pack("<iB3xii", 1, 0, 1, 1)
write("chlist_short.exr", exr_magic + b"channels\0chlist\0" + struct.pack("<i", 1) + channel + b"\0" +
      b"comments\0string\0" + struct.pack("<i", 1929379935) + b"x" * 40)
# A data window and a tile size the library would size its tables by.
write("window_huge.exr", exr_magic + b"dataWindow\0box2i\0" + struct.pack("<i4i", 16, 0, 0, 99999, 99999) + b"\0")
write("tiles_huge.exr", exr_magic + b"tiles\0tiledesc\0" + struct.pack("<iIIB", 9, 100000, 100000, 0) + b"\0")
# OpenImageIO's SGI reader throws std::length_error on this one instead of reporting an error (a fuzzing find; its
# header's 218 bytes per channel are now refused before the reader opens it).
write("throws.sgi", \
    bytes.fromhex("01da00da00010002ff2850320005785249006146ca7700000000008ef60000000000000000000000000000"
                                  "00000000000000004d4d4d4d328e8ef6000000000000000000000000004d4d4d4d328e8ef60000000000"
                                  "000000000000000000000000004d4d4d4d328e8ef60000"))
# A run-length encoded SGI header claiming 16384 rows of 16384 channels: OpenImageIO would allocate and clear its two
# row tables, 1 GiB each, on opening (a fuzzing find).
write("tables_2gb.sgi", struct.pack(">hBBHHHH", 474, 1, 1, 3, 1, 16384, 16384) + bytes(500) + bytes(64))
# A GIF whose logical screen is 19789x19789: OpenImageIO would allocate and clear a canvas that size (a fuzzing find).
write("screen_huge.gif", b"GIF89a" + struct.pack("<HHBBB", 19789, 19789, 0xf0, 0, 0) + bytes(6) + b";")
write("screen_huge_any_version.gif", b"GIFa89" + struct.pack("<HHBBB", 30244, 12591, 0xf0, 0, 0) + bytes(6) + b";")
# JPEG metadata OpenImageIO reads by fields it trusts: an IPTC block claiming 113 of the 20 bytes left in its APP13
# segment (the reader read past the segment: a fuzzing find), and an APP1 segment cut inside its "Exif" signature.
def jpeg_segment(code, payload):
    return b"\xff" + bytes([code]) + struct.pack(">H", len(payload) + 2) + payload
iptc = b"Photoshop 3.0\0" + b"8BIM" + struct.pack(">H4xH", 0x0404, 113) + b"\x1c\x02\x05\x00\x04name" + bytes(11)
write("iptc_overflow.jpg", b"\xff\xd8" + jpeg_segment(0xed, iptc) + b"\xff\xd9")
write("exif_cut.jpg", b"\xff\xd8" + jpeg_segment(0xe1, b"Exi") + b"\xff\xd9")
write("huge.ppm", b"P6\n100000 100000\n255\n")
write("wide.ppm", b"P6\n4294967297 1\n255\n")                 # wider than an int
write("dense.ppm", b"P6\n10000 10000\n255\n")                  # within the limit, but not from 19 bytes
write("zero.ppm", b"P6\n0 0\n255\n")
write("truncated.ppm", b"P6\n64 64\n255\n" + b"\x10" * 100)
write("huge.pfm", b"Pf\n100000 100000\n-1.0\n")
write("empty.png", b"")
write("text.png", b"These are notes, not an image.\nSecond line.\n")
write("text.pgm", b"P2 but then nonsense\n")
cells = [0.5] * 16
write("nan.pfm", pfm(4, 4, cells[:5] + [float("nan")] + cells[6:]))
write("inf.pfm", pfm(4, 4, cells[:15] + [float("-inf")]))
write("above_one.pfm", pfm(4, 4, cells[:3] + [1.5] + cells[4:]))
write("below_zero.pfm", pfm(4, 4, [-0.25] + cells[1:]))
write("ok.pfm", pfm(4, 4, [0.0] * 8 + [1.0] * 8))
write("small.pgm", b"P2\n3 4\n255\n" + b"5\n" * 12)
PY

# A float displacement in 0..1 is fine (the negative cases below are not refused for being PFM).
new_out
expect_ok prewarp --relief "$(with_disp disp_pfm ok.pfm)" --eye 0.5,0.5,3 --out "$O/p.png"

for img in empty.png text.png text.pgm truncated.png header_only.png corrupt.png bad_zlib.png huge.png huge.ppm \
  wide.ppm dense.ppm zero.ppm truncated.ppm huge.pfm text_2gb.png attr_2gb.exr chlist_short.exr window_huge.exr \
  tiles_huge.exr throws.sgi tables_2gb.sgi screen_huge.gif \
  screen_huge_any_version.gif iptc_overflow.jpg exif_cut.jpg; do
  case $img in
    empty.png) msg="file is empty" ;;
    text.png) msg="cannot read as an image: Not a PNG file" ;;
    text.pgm) msg="cannot read as an image" ;;
    truncated.png | corrupt.png | bad_zlib.png | truncated.ppm) msg="cannot read pixels" ;;
    header_only.png) msg="cannot read as an image" ;;
    huge.png | huge.ppm | huge.pfm) msg="image claims 100000x100000 pixels, more than the limit of 16384x16384" ;;
    wide.ppm) msg="image claims " ;; # the width overflows an int: OpenImageIO clamps it
    throws.sgi) msg="cannot read as an image: SGI header claims 218 bytes per channel, expected 1 or 2 (corrupt)" ;;
    dense.ppm) msg="image claims 10000x10000 pixels, more than 16384 per byte of a 19-byte file" ;;
    zero.ppm) msg="image header claims 0x0 pixels, expected a width and height of at least 1" ;;
    text_2gb.png) msg="cannot read as an image: PNG chunk \"tEXt\" at byte 33 claims 2016634473 bytes, more than" ;;
    attr_2gb.exr) msg="cannot read as an image: OpenEXR attribute \"comments\" at byte 8 claims 1929379935 bytes" ;;
    chlist_short.exr) msg="cannot read as an image: OpenEXR attribute \"channels\" (chlist) at byte 8 has a size field"\
" of 1 but its value takes 19 bytes (corrupt)" ;;
    screen_huge_any_version.gif) msg="image claims 30244x12591 pixels, more than the limit of 16384x16384" ;;
    iptc_overflow.jpg) msg="cannot read as an image: JPEG APP13 segment at byte 2 has an IPTC block claiming 113"\
" bytes, more than the 20 left in the segment (corrupt)" ;;
    exif_cut.jpg) msg="cannot read as an image: JPEG APP1 segment at byte 2 ends inside its \"Exif\" signature"\
" (3 bytes) (corrupt)" ;;
    screen_huge.gif) msg="image claims 19789x19789 pixels, more than the limit of 16384x16384" ;;
    window_huge.exr) msg="image claims 100000x100000 pixels, more than the limit of 16384x16384" ;;
    tables_2gb.sgi) msg="cannot read as an image: SGI run-length tables for \"16384 rows x 16384 channels\" at byte"\
" 512 claims 2147483648 bytes, more than the 64 left in the file (truncated or corrupt)" ;;
    tiles_huge.exr) msg="cannot read as an image: OpenEXR tiles of 100000x100000 pixels, more than the limit" ;;
  esac
  stem=${img//./_}
  # As colour and as displacement; render and prewarp swap roles from one image to the next.
  reject_relief "$(with_color "color_$stem" "$img")" "$D/color_$stem.relief.json: $D/$img: $msg"
  reject_relief "$(with_disp "disp_$stem" "$img")" "$D/disp_$stem.relief.json: $D/$img: $msg"
  turn=$((turn + 1))
  # rtm diff names the image itself, as the reference or (next image) as the test image.
  new_out
  if [ $((turn % 2)) = 0 ]; then
    check 1 "$D/$img: $msg" -- diff "$D/$img" "$D/noise64.png" --heatmap "$O/h.png" --json "$O/d.json"
  else
    check 1 "$D/$img: $msg" -- diff "$D/noise64.png" "$D/$img" --heatmap "$O/h.png" --json "$O/d.json"
  fi
done
# Files on which OpenImageIO 2.4's readers crash or loop without end (found by changing images it writes at random):
# read in a child process (formats/image_io.cpp), each is one line naming the file. rtm writes the images, and one
# field of each is changed: an IFF tile chunk too short for its coordinates (the reader decodes from a null pointer),
# an RLA matte channel of 0 bits (the reader's bit-depth conversion loops; stopped after 1 s of processor time here).
new_out
expect_ok render --relief "$R" --eye 0.5,0.5,3 --size 16x12 --out "$D/written.iff"
expect_ok render --relief "$R" --eye 0.5,0.5,3 --size 16x12 --out "$D/written.rla"
python3 - "$D" <<'PY'
import sys
d = sys.argv[1]
iff = bytearray(open(f"{d}/written.iff", "rb").read())
at = iff.index(b"TBMPRGBA") + 8
iff[at:at + 4] = (8).to_bytes(4, "big")  # the tile's chunk holds its 8 bytes of coordinates and nothing else
open(f"{d}/null_tile.iff", "wb").write(iff)
rla = bytearray(open(f"{d}/written.rla", "rb").read())
assert rla[662:664] == b"\0\x08", rla[662:664]  # NumOfMatteBits
rla[662:664] = b"\0\0"
open(f"{d}/no_matte_bits.rla", "wb").write(rla)
PY
# In the sanitizer build AddressSanitizer reports the read through a null pointer and ends the child itself (SIGABRT
# with abort_on_error, as scripts/test.sh runs it; else exit status 1).
crashed="crashed on it (signal 11, "
if ldd "$RTM" | grep -q libasan; then crashed=""; fi
new_out
check 1 "$D/null_tile.iff: cannot read as an image: the image reader (OpenImageIO) $crashed" -- \
  diff "$D/noise64.png" "$D/null_tile.iff" --heatmap "$O/h.png"
reject_relief "$(with_color color_null_tile null_tile.iff)" "$D/null_tile.iff: cannot read as an image: the image"\
" reader (OpenImageIO) $crashed"
new_out
RTM_IMAGE_READER_SECONDS=1 check 1 "$D/no_matte_bits.rla: cannot read as an image: the image reader (OpenImageIO) was"\
" stopped after the 1 s of processor time it may use for a file of " -- \
  diff "$D/no_matte_bits.rla" "$D/noise64.png" --heatmap "$O/h.png"
new_out
RTM_IMAGE_READER_SECONDS=x check 1 "$D/no_matte_bits.rla: cannot read as an image: RTM_IMAGE_READER_SECONDS \"x\" is"\
" not a whole number from 1 to " -- diff "$D/no_matte_bits.rla" "$D/noise64.png" --heatmap "$O/h.png"

# The first image a process reads through the module is read right after the module loads: a TIFF (which OpenImageIO
# reads in strips, through its thread pool's lock) read then hung in 9 reads of 10 until the loading waited for the
# pool's thread to end (formats/image_io_oiio.cpp). Ten fresh processes, each stopped after 2 s of processor time
# (6 s in all) if its reader hangs.
expect_ok render --relief "$R" --eye 0.5,0.5,3 --size 16x12 --out "$D/written.tif"
for i in 1 2 3 4 5 6 7 8 9 10; do
  new_out
  RTM_IMAGE_READER_SECONDS=2 expect_ok diff "$D/written.tif" "$D/written.tif" --heatmap "$O/h.png"
done

new_out
check 1 "$D/nope.png: cannot open: No such file or directory" -- diff "$D/noise64.png" \
  "$D/nope.png" --heatmap "$O/h.png"
new_out
check 1 "$D/dir.png: is a directory" -- diff "$D/dir.png" "$D/noise64.png" --heatmap "$O/h.png"
new_out
check 1 "$D/line?break.png: cannot open: No such file or directory" -- \
  diff "$D/noise64.png" "$D/line"$'\n'"break.png" --heatmap "$O/h.png"

# --- Displacement values and sizes.

reject_relief "$(with_disp disp_nan nan.pfm)" \
  "$D/disp_nan.relief.json: displacement image nan.pfm has a non-finite value (nan)"\
" at texel (1, 2), expected a finite value in 0..1"
reject_relief "$(with_disp disp_inf inf.pfm)" \
  "$D/disp_inf.relief.json: displacement image inf.pfm has a non-finite value (-inf) at texel (3, 0)"
reject_relief "$(with_disp disp_above above_one.pfm)" \
  "$D/disp_above.relief.json: displacement image above_one.pfm has the value 1.5"\
" at texel (3, 3), expected a finite value in 0..1"
reject_relief "$(with_disp disp_below below_zero.pfm)" \
  "$D/disp_below.relief.json: displacement image below_zero.pfm has the value -0.25 at texel (0, 3)"
if command -v oiiotool >/dev/null; then
  # 16-bit (half) float displacement, in OpenEXR and TIFF: NaN survives the conversion to half.
  oiiotool "$D/nan.pfm" -d half -o "$D/nan_half.exr" && oiiotool "$D/nan.pfm" -d half -o "$D/nan_half.tif"
  reject_relief "$(with_disp disp_nan_exr nan_half.exr)" \
    "$D/disp_nan_exr.relief.json: displacement image nan_half.exr has a non-finite value (nan)"
  reject_relief "$(with_disp disp_nan_tif nan_half.tif)" \
    "$D/disp_nan_tif.relief.json: displacement image nan_half.tif has a non-finite value (nan)"
else
  echo "note: oiiotool not found (openimageio-tools), half-float displacement cases skipped"
fi
reject_relief "$(with_disp disp_small small.pgm)" \
  "$D/disp_small.relief.json: displacement image small.pgm is 3x4 but color c.ppm is 4x4"
new_out
check 1 "$D/noise64.png: image is 64x64 but the reference $D/small.pgm is 3x4" -- \
  diff "$D/small.pgm" "$D/noise64.png" --heatmap "$O/h.png" --json "$O/d.json"

# --- Degenerate cameras: usage errors (exit 2) naming the flag, before any file is written.

camera() {
  local msg=$1
  shift
  new_out
  check 2 "$msg" -- render --relief "$R" "$@" --size 16x16 --out "$O/r.png" --json "$O/r.json"
}
camera "rtm: --eye and --look-at: eye (0.5,0.5,2) equals look-at (0.5,0.5,2)" --eye 0.5,0.5,2 --look-at 0.5,0.5,2
camera "rtm: --orbit: eye" --orbit 0,0,1e-300 # the eye lands on the centre
camera "rtm: --up: up (0,0,1) is parallel to the view direction" --eye 0.5,0.5,3 --look-at 0.5,0.5,0 --up 0,0,1
camera "rtm: --up: up (0,-2,0) is parallel to the view direction" --eye 0.5,3,0 --look-at 0.5,0.5,0 --up 0,-2,0
# straight down the default up, which the user did not give: the message names --orbit
camera "rtm: --orbit (with the default --up 0,1,0; give another --up): up (0,1,0) is parallel to the view" \
  --orbit 30,90,2
camera "rtm: --up: up (0,0,0) is the zero vector" --eye 0.5,0.5,3 --up 0,0,0
camera "rtm: --fov: expected degrees in (0, 180), found 0" --eye 0.5,0.5,3 --fov 0
camera "rtm: --fov: expected degrees in (0, 180), found 180" --eye 0.5,0.5,3 --fov 180
camera "rtm: --fov: expected degrees in (0, 180), found -30" --eye 0.5,0.5,3 --fov -30
camera "rtm: --fov: expected degrees in (0, 180), found nan" --eye 0.5,0.5,3 --fov nan
camera "rtm: --orbit: distance D must be > 0, found \"30,20,0\"" --orbit 30,20,0
camera "rtm: --orbit: distance D must be > 0, found \"30,20,-2\"" --orbit 30,20,-2
camera "rtm: --orbit: expected AZ,EL,D (three finite numbers separated by commas), found \"30,20,nan\"" \
  --orbit 30,20,nan
camera "rtm: --eye: the eye 1e+300,0,0 has a coordinate beyond +-1e30" --eye 1e300,0,0
camera "rtm: --eye: expected X,Y,Z (three finite numbers separated by commas), found \"1?2,3\"" --eye 1$'\n'2,3
camera "rtm: --orbit: the eye" --orbit 30,20,1e300
camera "rtm: --look-at: 0,-1e+40,0 has a coordinate beyond +-1e30" --eye 0.5,0.5,3 --look-at 0,-1e40,0

# Nothing anywhere in the corpus folder was written by rtm (no stray temporary files beside the inputs either).
if [ -n "$(find "$D" -name '*.tmp*')" ]; then echo "FAIL: temporary file left in $D"; fails=$((fails + 1)); fi
if [ -e "$T/test_bugs" ]; then echo "FAIL: edits that changed nothing: $(cat "$T/test_bugs")"; fails=$((fails + 1)); fi
finish
