#!/usr/bin/env bash
# rtm compare --quick: two reliefs in one run (results.csv and results.json hold every source, method id and view,
# the curved bases' quadric-silhouettes rows too (the cylinder and the sphere patch), with the fields of
# docs/COMPARE.md, each row's truth, and the pictures they name exist), an object (no per-pixel, raycast or curved
# rows), and bad input: a missing relief (exit 1), two kinds of source, no source, a bad --size (exit 2), one line each.
. "$(dirname "$0")/lib.bash"

check_results() {  # check_results DIR KINDS: the CSV and JSON agree with the sweep
  if python3 - "$1" "$2" <<'PY'; then passes=$((passes + 1)); else fails=$((fails + 1)); fi
import csv, json, os, sys
d, kind = sys.argv[1], sys.argv[2]
j = json.load(open(os.path.join(d, "results.json")))
errors = []
for k in ["title", "image_size", "machine", "threads", "quick", "sources", "views", "methods", "truths", "rows",
          "summary"]:
    if k not in j:
        errors.append("results.json has no " + k)
row_fields = ["source", "view", "method_id", "method", "setting", "family", "base", "truth", "ms", "stages", "psnr",
              "rmse", "iou", "silhouette_px", "psnr_vs_micromesh", "iou_vs_micromesh", "iterations_mean", "image",
              "heatmap", "iterations_image"]
sources = [s["name"] for s in j["sources"]]
views = [v["name"] for v in j["views"]]
ids = [m["id"] for m in j["methods"]]
if len(views) != 3:
    errors.append("--quick has %d views, not 3" % len(views))
if len(set(ids)) != len(ids):
    errors.append("method ids are not unique")
have = {m["method"] for m in j["methods"]}
if kind == "relief":
    want = {"flat", "two-pass", "pipelined", "parallax", "parallax-offset-limiting", "steep-parallax",
            "parallax-occlusion", "relief-mapping", "interval-mapping", "protruded-displacement", "micromesh",
            "raycast", "quadric-silhouettes", "curved-micromesh", "curved-raycast", "sphere-micromesh",
            "sphere-raycast"}
else:
    want = {"flat", "two-pass", "pipelined", "micromesh"}
if have != want:
    errors.append("methods %s, expected %s" % (sorted(have), sorted(want)))
def variant(m):  # quadric silhouettes with and without the quadrics sweep the same steps; the exact distance one;
    # the sphere one
    return (m["method"], m["params"].get("quadric"), m["params"].get("exact_distance"),
            m["params"].get("patch", {}).get("shape"))
for m in j["methods"]:  # --quick: at most 2 settings per method
    if sum(1 for x in j["methods"] if variant(x) == variant(m)) > 2:
        errors.append("more than 2 settings of %s" % (variant(m),))
    sphere = m["method"].startswith("sphere-") or m["setting"].startswith(("sphere-", "no-quadric-sphere-"))
    curved = m["method"] in ("quadric-silhouettes", "curved-micromesh", "curved-raycast")
    want_base = "sphere" if sphere else "curved" if curved else "flat"
    if want_base != "flat" and m["params"]["patch"]["shape"] != {"curved": "cylinder", "sphere": "sphere"}[want_base]:
        errors.append("%s on base %s has the patch %s" % (m["id"], want_base, m["params"]["patch"]))
    if m["base"] != want_base:
        errors.append("%s has base %s, not %s" % (m["id"], m["base"], want_base))
if kind == "relief":  # the curved base: each quadric setting beside the same steps without the quadrics, and the
    # paper's exact distance at the default steps; the sphere patch at the default steps with and without quadrics
    q = sorted(m["setting"] for m in j["methods"] if m["method"] == "quadric-silhouettes")
    if q != sorted(["l8-b2", "l32-b8", "no-quadric-l8-b2", "no-quadric-l32-b8", "exact-l32-b8", "sphere-l32-b8",
                    "no-quadric-sphere-l32-b8"]):
        errors.append("quadric-silhouettes settings %s" % q)
rows = j["rows"]
if len(rows) != len(sources) * len(ids) * len(views):
    errors.append("%d rows, expected %d sources x %d methods x %d views" % (len(rows), len(sources), len(ids),
                                                                          len(views)))
keys = {(r["source"], r["method_id"], r["view"]) for r in rows}
for s in sources:
    for m in ids:
        for v in views:
            if (s, m, v) not in keys:
                errors.append("no row for %s %s %s" % (s, m, v))
for r in rows:
    for f in row_fields:
        if f not in r:
            errors.append("row without " + f)
    for f in ["image", "heatmap", "iterations_image"]:
        if r.get(f) and not os.path.isfile(os.path.join(d, r[f])):
            errors.append("missing picture " + r[f])
    if r["family"] == "pre-warp" and set(r["stages"]) != {"prewarp", "upload", "texmap", "other"}:
        errors.append("pre-warp row without its stages")
    if r["family"] == "per-pixel" and (r["iterations_image"] is None or r["iterations_mean"] is None):
        errors.append("per-pixel row without iteration counts: " + r["method_id"])
    if r["image"] is None or r["ms"] is None:
        errors.append("row without image or time: " + r["method_id"])
    # The truth each row is measured against: a curved base against its own curved mesh, the rest against the ray
    # caster (a relief) or the micro-polygon mesh (an object).
    curved = r["base"] in ("curved", "sphere")
    want_truth = r["base"] + "-micromesh" if curved else "raycast" if kind == "relief" else "micromesh"
    if r["truth"] != want_truth:
        errors.append("%s measured against %s, not %s" % (r["method_id"], r["truth"], want_truth))
    if curved:
        mesh = r["base"] + "-micromesh"
        t = j["truths"][r["source"]][r["view"]].get(mesh)
        if not t or not os.path.isfile(os.path.join(d, t)):
            errors.append("no %s picture for %s %s" % (mesh, r["source"], r["view"]))
        if r["method_id"] == mesh and (r["rmse"] != 0 or r["iou"] != 1 or r["heatmap"] is not None):
            errors.append("%s against itself: rmse %s iou %s" % (mesh, r["rmse"], r["iou"]))
        # The two truths of a curved base, drawn in two ways, agree but for edge pixels and the interpolation
        # inside a texel cell (bilinear against two triangles): at 48x48 on bumps and ridges, the cylinder IoU
        # 0.9948 to 1 and PSNR 41.4 to 71.0 dB, the sphere IoU 0.9967 to 1 and PSNR 39.4 to 69.5 (2026-12-07). The
        # lowest, ridges at az45_el20, are one and two pixels at a ridge's crest (85 to 106 levels apart: the two
        # interpolations take the two sides of a colour step), every other common pixel within 3 levels; the
        # sphere's image has fewer common pixels (673 against 881), so each counts for more. Hence 40 dB for the
        # cylinder and 38 for the sphere.
        least = 38 if r["base"] == "sphere" else 40
        if r["method_id"] == r["base"] + "-raycast" and (r["iou"] < 0.99 or
                                                         r["psnr"] is not None and r["psnr"] < least):
            errors.append("%s against %s %s: iou %s psnr %s" % (r["method_id"], mesh, r["view"], r["iou"], r["psnr"]))
with open(os.path.join(d, "results.csv")) as f:
    c = list(csv.DictReader(f))
if len(c) != len(rows):
    errors.append("results.csv has %d rows, results.json %d" % (len(c), len(rows)))
for f in ["source", "view", "method_id", "method", "setting", "family", "ms", "psnr", "rmse", "iou",
          "silhouette_px", "stage_prewarp", "base", "truth"]:
    if c and f not in c[0]:
        errors.append("results.csv has no column " + f)
if len(j["summary"]) != (len(sources) + 1) * len(ids):
    errors.append("summary has %d rows, expected %d" % (len(j["summary"]), (len(sources) + 1) * len(ids)))
for base in {m["base"] for m in j["methods"]}:  # a front per source and base
    for src in sources + ["all"]:
        if not any(s["pareto"] for s in j["summary"] if s["source"] == src and s["base"] == base):
            errors.append("no %s summary row of %s on the Pareto front" % (base, src))
for x in c:
    if x["truth"] not in ("raycast", "micromesh", "curved-micromesh", "sphere-micromesh"):
        errors.append("results.csv: truth " + x["truth"])
for f in ["index.html", "compare.md"]:
    if not os.path.isfile(os.path.join(d, f)):
        errors.append("no " + f)
if kind == "relief":  # the reading names the exact distance against the approximate one
    page = open(os.path.join(d, "index.html")).read()
    if "quadric-silhouettes:exact-l32-b8 IoU" not in page or "(quadric-silhouettes:l32-b8)" not in page:
        errors.append("index.html: no reading of the exact distance against the approximate one")
    if "On the sphere patch" not in page or "quadric-silhouettes:sphere-l32-b8 IoU" not in page:
        errors.append("index.html: no reading of the sphere patch")
for e in errors[:10]:
    print("FAIL:", e)
sys.exit(1 if errors else 0)
PY
}

expect_ok compare --relief "$SRC/media/bumps.relief.json" --relief "$SRC/media/ridges.relief.json" --quick \
  --size 48x48 --out "$T/two"
grep -q '^compare 1/[0-9]*: bumps' "$T/stderr" && passes=$((passes + 1)) || {
  echo "FAIL: no progress line 1/N on stderr"
  fails=$((fails + 1))
}
check_results "$T/two" relief

expect_ok compare --object "$SRC/media/cross-box.object.json" --quick --size 48x48 --out "$T/object"
check_results "$T/object" object

expect_fail 1 'nope.relief.json' -- compare --relief "$T/nope.relief.json" --quick --out "$T/bad1"
expect_fail 2 'one kind of source' -- compare --relief "$SRC/media/bumps.relief.json" \
  --object "$SRC/media/cross-box.object.json" --quick --out "$T/bad2"
expect_fail 2 'one kind of source' -- compare --quick --out "$T/bad3"
expect_fail 2 '--size' -- compare --relief "$SRC/media/bumps.relief.json" --size 0x10 --out "$T/bad4"
expect_fail 2 '--repeat' -- compare --relief "$SRC/media/bumps.relief.json" --repeat 0 --out "$T/bad5"
for d in bad1 bad2 bad3 bad4 bad5; do
  [ -e "$T/$d/results.json" ] && { echo "FAIL: results.json after an error ($d)"; fails=$((fails + 1)); }
done
finish
